#!/usr/bin/env bash
# pip install of the Python module from the checkout, offline (docs/python.md,
# "Installing with pip"): into a fresh virtual environment that sees Debian's
# packages (setuptools, NumPy), without build isolation or an index, reusing
# the build tree given (setup.py's GJKDEM_BUILD_DIR) so that only the
# packaging is new. The installed module, imported from elsewhere, answers a
# query and runs a small world. Usage: pip_install.sh SOURCE_DIR BUILD_DIR
set -euo pipefail
source_dir="$1"
build_dir="$2"
python3 -c "import venv, ensurepip" 2>/dev/null || { echo "no python3-venv: skipped"; exit 77; }
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }

/usr/bin/python3 -m venv --system-site-packages "$work/venv" || fail "cannot make a virtual environment"
(cd "$source_dir" && GJKDEM_BUILD_DIR="$build_dir" "$work/venv/bin/python" -m pip install --quiet \
   --no-build-isolation --no-index --no-cache-dir .) || fail "pip install --no-build-isolation --no-index . failed"
cd "$work"
"$work/venv/bin/python" - "$work" <<'PY' || fail "the installed module"
import sys
import gjkdem

assert gjkdem.__file__.startswith(sys.argv[1] + "/venv/"), gjkdem.__file__  # the installed copy, not the build tree's
d = gjkdem.distance(gjkdem.Shape("sphere", radius=1.0), gjkdem.Shape("box", half_extents=[1, 1, 1]),
                    pose_b=[3.5, 0, 0, 1, 0, 0, 0])
assert abs(d.distance - 1.5) < 1e-12, d.distance
b = gjkdem.WorldBuilder()
b.add_material("glass", density=2500, youngs_modulus=1e7)
b.add_plane([0, 0, 0], [0, 0, 1], "glass")
b.add_body(gjkdem.Shape("box", half_extents=[0.01] * 3), "glass", position=[0, 0, 0.05])
w = b.build()
w.run(0.05)
assert w.positions[0][2] < 0.05
from gjkdem import view  # the pure-Python part is installed too
print("installed", gjkdem.__version__)
PY
"$work/venv/bin/python" -m pip uninstall --quiet --yes gjkdem || fail "pip uninstall failed"
echo "pip_install: all checks passed"
