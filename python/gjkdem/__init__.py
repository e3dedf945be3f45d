"""gjkdem: exact convex collision queries and a DEM engine for non-spherical grains.

Shapes and queries (intersect, distance, penetration, overlap and their
batches), worlds built with WorldBuilder or read from TOML scenes, runs with
Python observers, zero-copy NumPy views of the bodies, and the frames runs
write for the viewer (read_view). docs/python.md.
"""
from ._core import *  # noqa: F401,F403
from ._core import __version__  # noqa: F401
from .view import Frame, RunView, ViewFormatError, read_view  # noqa: F401
