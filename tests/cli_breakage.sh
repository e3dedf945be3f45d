#!/usr/bin/env bash
# Grains that break, end to end (tests/data/scenes/press_cube.toml: a cube
# pressed until it lies in 16 fragments): the run says how many broke, a run
# stopped between two splits and resumed gives the bytes of the one that
# never stopped, so does one thread, the view folder names every fragment's
# shape, and gjkdem analyze writes the fragment sizes (docs/breakage.md).
set -euo pipefail
gjkdem="$1"
scene="$(cd "$(dirname "$2")" && pwd)/$(basename "$2")"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
cd "$work"
export OMP_WAIT_POLICY=passive
fail() { echo "FAIL: $*" >&2; exit 1; }

"$gjkdem" run "$scene" --out full --threads 2 2> full.txt || { cat full.txt; fail "the press did not complete"; }
grep -q "16 bodies, 15 grains broken" full.txt || { cat full.txt; fail "the summary should say 15 grains broke"; }
grep -q '"grains_broken": 15' full/run.json || fail "run.json should count 15 broken grains"

# Stopped after 150 steps: the first split was at step 107, the last at 164.
set +e
"$gjkdem" run "$scene" --out parts --threads 2 --quiet --stop-after 150
rc=$?
set -e
[ "$rc" -eq 130 ] || fail "an interrupted run should exit with 130, got $rc"
grep -q '"grains_broken": [1-9]' parts/run.json || fail "the stopped run should have broken grains already"
"$gjkdem" run --resume parts --quiet || fail "resume did not complete"
"$gjkdem" run "$scene" --out one --threads 1 --quiet || fail "the one-thread run did not complete"
for f in trace.csv energy.csv view/index.csv view/shapes.bin view/frame_000008.bin view/frame_000015.bin \
         frames/frame_000015.vtk; do
  cmp -s "full/$f" "parts/$f" || fail "$f differs between the uninterrupted and the resumed run"
  cmp -s "full/$f" "one/$f" || fail "$f differs between 1 and 2 threads"
done

# The fragment sizes: one cube, then 16 pieces smaller than unbreakable_below.
"$gjkdem" analyze full --quiet > /dev/null || fail "analyze failed"
[ "$(head -1 full/analysis/sizes.csv)" = "frame,time,grains,smallest,d10,d50,d90,largest,bonds,bonds_broken" ] || fail "sizes.csv header"
awk -F, 'NR == 2 && !($3 == 1 && $8 > 0.0124 && $8 < 0.0125) { exit 1 }' full/analysis/sizes.csv ||
  fail "the first frame should hold the cube alone (0.01241 m)"
awk -F, 'END { if (!($3 == 16 && $8 < 0.0055 && $4 > 0.75 * 0.0055)) exit 1 }' full/analysis/sizes.csv ||
  fail "the last frame should hold 16 fragments, each smaller than unbreakable_below and larger than 3/4 of it"
# Without its checkpoint the frames' fragments cannot be named: a clear error.
rm full/checkpoint.bin
set +e
"$gjkdem" analyze full --quiet 2> lost.txt
rc=$?
set -e
[ "$rc" -ne 0 ] && grep -q "fragments of broken grains" lost.txt || { cat lost.txt; fail "analyze without the checkpoint"; }

# A bad strength is refused naming its key.
sed 's/^unbreakable_below = 0.0055$/unbreakable_below = 0.0/' "$scene" > bad.toml
set +e
"$gjkdem" run bad.toml --out bad 2> bad.txt
rc=$?
set -e
[ "$rc" -eq 2 ] && grep -q "unbreakable_below" bad.txt || { cat bad.txt; fail "unbreakable_below = 0 should be refused (exit $rc)"; }
echo "cli_breakage: all checks passed"
