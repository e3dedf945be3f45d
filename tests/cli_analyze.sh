#!/usr/bin/env bash
# gjkdem analyze end to end on a small pour (tests/data/scenes/small_pour.toml):
# one row of measures a frame and 21 force bins a frame; a region inside the
# box holds grains once they have fallen in; bad regions and folders that are
# not runs are refused with exit 2 and a message.
set -euo pipefail
gjkdem="$1"
scene_dir="$(cd "$(dirname "$2")" && pwd)"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
cd "$work"
export OMP_WAIT_POLICY=passive
fail() { echo "FAIL: $*" >&2; exit 1; }

cp "$scene_dir/small_pour.toml" "$scene_dir/chute.obj" .
"$gjkdem" run small_pour.toml --out pour --quiet || fail "the run did not complete"

"$gjkdem" analyze pour --quiet > said.txt || fail "analyze failed"
grep -q "7 frames" said.txt || fail "analyze should report 7 frames: $(cat said.txt)"
head -1 pour/analysis/measures.csv | grep -q "^frame,time,solid_fraction,coordination,contacts,mean_normal_force,stress_xx" ||
  fail "measures.csv header"
[ "$(wc -l < pour/analysis/measures.csv)" -eq 8 ] || fail "measures.csv should hold 7 frames"
[ "$(wc -l < pour/analysis/normal_forces.csv)" -eq $((1 + 7 * 21)) ] || fail "normal_forces.csv should hold 21 bins a frame"

# The lower part of the box, at the end: grains in it, touching, pressed.
"$gjkdem" analyze pour --region=-0.1,-0.1,-0.1,0.1,0.1,0.05 --every 3 --quiet > said.txt || fail "analyze --region failed"
grep -q "3 frames" said.txt || fail "--every 3 should analyse frames 0, 3 and 6: $(cat said.txt)"
/usr/bin/python3 - pour/analysis/measures.csv <<'PY' || fail "the measures of the last frame"
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
assert [r["frame"] for r in rows] == ["0", "3", "6"], rows
last = rows[-1]
assert 0 < float(last["solid_fraction"]) < 0.7, last
assert int(last["grains"]) > 0 and abs(float(last["region_volume"]) - 0.006) < 1e-12, last
assert float(last["pressure"]) > 0 and float(last["coordination"]) > 0, last
PY

# A cylinder and a ball around the bottom of the box: their volumes, grains in them.
"$gjkdem" analyze pour --cylinder=0,0,-0.1,0,0,1,0.05,0.15 --every 6 --quiet > /dev/null || fail "analyze --cylinder failed"
/usr/bin/python3 - pour/analysis/measures.csv <<'PY' || fail "the measures in a cylinder"
import csv, math, sys
last = list(csv.DictReader(open(sys.argv[1])))[-1]
assert abs(float(last["region_volume"]) - math.pi * 0.05**2 * 0.15) < 1e-15, last
assert int(last["grains"]) > 0 and 0 < float(last["solid_fraction"]) < 0.7, last
PY
"$gjkdem" analyze pour --sphere=0,0,0,0.1 --every 6 --quiet > /dev/null || fail "analyze --sphere failed"
/usr/bin/python3 - pour/analysis/measures.csv <<'PY' || fail "the measures in a ball"
import csv, math, sys
last = list(csv.DictReader(open(sys.argv[1])))[-1]
assert abs(float(last["region_volume"]) - 4 / 3 * math.pi * 0.1**3) < 1e-15, last
assert int(last["grains"]) > 0, last
PY

refused() {  # refused EXPECTED_MESSAGE ARGS...
  local expected="$1"; shift
  set +e
  "$gjkdem" analyze "$@" --quiet 2> err.txt
  local rc=$?
  set -e
  [ "$rc" -eq 2 ] && grep -q "$expected" err.txt || fail "analyze $* should be refused with \"$expected\" (rc $rc): $(cat err.txt)"
}
refused "6 numbers" pour --region 1,2,3
refused "x0 < x1" pour --region=0,0,0,-1,1,1
refused "6 numbers" pour --region=0,0,0,1,1,1,5
refused "8 numbers" pour --cylinder=0,0,0,1,0.1,0.1
refused "radius and height > 0" pour --cylinder=0,0,0,0,0,1,0.1,0
refused "4 numbers" pour --sphere=0,0,0
refused "one of --region, --cylinder and --sphere" pour --sphere=0,0,0,1 --region=0,0,0,1,1,1
mkdir empty
refused "view/index.csv" empty
# A region whose volume underflows, and a frame holding a NaN (a blown-up run,
# or a damaged file): refused, not written into measures.csv as nan and inf.
refused "underflows" pour --region=0,0,0,1e-120,1e-120,1e-120
cp -r pour broken
/usr/bin/python3 - broken/view/frame_000003.bin <<'PY'
import struct, sys
data = bytearray(open(sys.argv[1], "rb").read())
data[40:44] = struct.pack("<f", float("nan"))  # body 0's x: after magic, version, counts, time and step
open(sys.argv[1], "wb").write(bytes(data))
PY
refused "not finite" broken
echo "analyze: ok"
