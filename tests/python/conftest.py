"""Shared fixtures of the Python tests (run by ctest: tests/CMakeLists.txt).

GJKDEM_CLI names the gjkdem program built beside the module; GJKDEM_SHARED_DIR the
shared/ folder (../shared by default) with the pair samples.
"""
import os
import pathlib

import pytest

REPO = pathlib.Path(__file__).resolve().parents[2]


@pytest.fixture(scope="session")
def cli():
    path = os.environ.get("GJKDEM_CLI")
    if not path:
        pytest.fail("GJKDEM_CLI is not set: run the Python tests through ctest")
    return path


@pytest.fixture(scope="session")
def repo():
    return REPO


@pytest.fixture(scope="session")
def pairs_dir():
    d = pathlib.Path(os.environ.get("GJKDEM_SHARED_DIR", REPO.parent / "shared")) / "data" / "pairs"
    if not d.is_dir():
        pytest.fail(f"{d} is missing: the shared pair samples sit next to the repository")
    return d
