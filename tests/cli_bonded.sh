#!/usr/bin/env bash
# Bonded assemblies, end to end (tests/data/scenes/bonded_drop.toml: a box of
# 12 glued pieces dropped on a floor, some bonds break): the run says how
# many bonds broke, a run stopped between two breaks and resumed gives the
# bytes of the one that never stopped, so does one thread, gjkdem analyze
# counts the pieces still held together as one grain and the broken bonds,
# and 2 MPI ranks give the bytes of one (docs/breakage.md).
set -euo pipefail
gjkdem="$1"
scene="$(cd "$(dirname "$2")" && pwd)/$(basename "$2")"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
cd "$work"
export OMP_WAIT_POLICY=passive
fail() { echo "FAIL: $*" >&2; exit 1; }

"$gjkdem" run "$scene" --out full --threads 2 2> full.txt || { cat full.txt; fail "the drop did not complete"; }
broken=$(python3 -c 'import json; print(json.load(open("full/run.json"))["bonds_broken"])')
[ "$broken" -gt 0 ] && [ "$broken" -lt 38 ] || fail "some bonds of 38 should break, not $broken"
grep -q "12 bodies, $broken of 38 bonds broken" full.txt || { cat full.txt; fail "the summary should count the broken bonds"; }

set +e
"$gjkdem" run "$scene" --out parts --threads 2 --quiet --stop-after 700
rc=$?
set -e
[ "$rc" -eq 130 ] || fail "an interrupted run should exit with 130, got $rc"
"$gjkdem" run --resume parts --quiet || fail "resume did not complete"
"$gjkdem" run "$scene" --out one --threads 1 --quiet || fail "the one-thread run did not complete"
for f in trace.csv energy.csv view/index.csv view/frame_000005.bin view/frame_000010.bin frames/frame_000010.vtk; do
  cmp -s "full/$f" "parts/$f" || fail "$f differs between the uninterrupted and the resumed run"
  cmp -s "full/$f" "one/$f" || fail "$f differs between 1 and 2 threads"
done

"$gjkdem" analyze full --quiet > /dev/null || fail "analyze failed"
awk -F, 'NR == 2 && !($3 == 1 && $9 == 38 && $10 == 0) { exit 1 }' full/analysis/sizes.csv ||
  fail "the first frame should hold one grain of 12 glued pieces and 38 bonds"
awk -F, -v b="$broken" 'END { if (!($3 > 1 && $10 == b)) exit 1 }' full/analysis/sizes.csv ||
  fail "the last frame should hold several grains and $broken broken bonds"

# A new run from its state keeps its bonds (as broken as they were); a
# scene cannot hold bonds yet: export refuses, saying why.
"$gjkdem" run "$scene" --from full --out from --quiet || fail "a run --from a bonded run"
python3 -c 'import json, sys; b = json.load(open("from/run.json"))["bonds_broken"]; sys.exit(b < int(sys.argv[1]))' "$broken" ||
  fail "a run --from the bonded run should start with its broken bonds"
set +e
"$gjkdem" export full > exported.toml 2> export.txt
rc=$?
set -e
[ "$rc" -ne 0 ] && grep -q "bonded assemblies" export.txt || { cat export.txt; fail "export should refuse bonds (exit $rc)"; }

# On 2 MPI ranks: the bytes of one; stopped on 2 ranks and resumed on 1, too.
if command -v mpirun > /dev/null; then
  mpi="mpirun --oversubscribe --allow-run-as-root -np 2"
  $mpi "$gjkdem" run "$scene" --out mpi --quiet --threads 1 > mpi.txt 2>&1 || { cat mpi.txt; fail "2 ranks did not complete"; }
  set +e
  $mpi "$gjkdem" run "$scene" --out mpi_parts --quiet --threads 1 --stop-after 700 > mpi_parts.txt 2>&1
  set -e
  "$gjkdem" run --resume mpi_parts --quiet --threads 1 || fail "a run stopped on 2 ranks did not resume on 1"
  for f in trace.csv energy.csv view/frame_000005.bin view/frame_000010.bin; do
    cmp -s "full/$f" "mpi/$f" || fail "$f differs between 1 and 2 ranks"
    cmp -s "full/$f" "mpi_parts/$f" || fail "$f differs between one rank and 2 ranks resumed on 1"
  done
fi
# A generator of bonded assemblies (bonded_generator.toml beside the scene):
# every assembly is cut into its pieces, some bonds break, and 1 thread,
# a resumed run and 2 ranks give the bytes of 2 threads.
generator="$(dirname "$scene")/bonded_generator.toml"
"$gjkdem" run "$generator" --out gen --threads 2 2> gen.txt || { cat gen.txt; fail "the generator's drop did not complete"; }
grep -q "^gjkdem: 48 bodies" gen.txt || { cat gen.txt; fail "8 assemblies of 6 pieces should be 48 bodies"; }
python3 - gen/run.json <<'PY' || fail "the generator's assemblies should hold bonds, some of them broken"
import json, sys
r = json.load(open(sys.argv[1]))
sys.exit(not (r["bonds"] >= 8 * 5 and 0 < r["bonds_broken"] < r["bonds"]))
PY
set +e
"$gjkdem" run "$generator" --out gen_parts --threads 2 --quiet --stop-after 1500
set -e
"$gjkdem" run --resume gen_parts --quiet || fail "the generator's run did not resume"
"$gjkdem" run "$generator" --out gen_one --threads 1 --quiet || fail "the generator's one-thread run did not complete"
for f in trace.csv energy.csv view/frame_000005.bin view/frame_000010.bin; do
  cmp -s "gen/$f" "gen_parts/$f" || fail "$f of the generator differs between the uninterrupted and the resumed run"
  cmp -s "gen/$f" "gen_one/$f" || fail "$f of the generator differs between 1 and 2 threads"
done
if command -v mpirun > /dev/null; then
  $mpi "$gjkdem" run "$generator" --out gen_mpi --quiet --threads 1 > gen_mpi.txt 2>&1 ||
    { cat gen_mpi.txt; fail "the generator on 2 ranks did not complete"; }
  for f in trace.csv energy.csv view/frame_000010.bin; do
    cmp -s "gen/$f" "gen_mpi/$f" || fail "$f of the generator differs between 1 and 2 ranks"
  done
fi
# Issue 54, point 14: a long build printed nothing. Three boxes of 1,500
# pieces (about 8 s here): run --check says what the build is on after its
# first second.
{
  printf '[simulation]\nduration = 0.001\n[[material]]\nname = "rock"\ndensity = 2500.0\nyoungs_modulus = 1.0e8\n'
  printf 'bond_tensile_strength = 1.0e5\nbond_shear_strength = 4.0e5\n'
  for k in 0 1 2; do
    printf '[[body]]\nshape = { type = "bonded", shape = { type = "box", half_extents = [0.05, 0.05, 0.05] }, pieces = 1500, seed = %s }\n' $((k + 1))
    printf 'material = "rock"\nposition = [%s, 0.0, 0.0]\n' "$k.0"
  done
} > long_build.toml
"$gjkdem" run long_build.toml --check > long_check.txt 2> long_build.err || { cat long_build.err; fail "the long build's check failed"; }
grep -qE "^gjkdem: building \([0-9]+ s\): (body\[[12]\]: cutting it into 1500 pieces|checking that the 4500 bodies start apart)" long_build.err ||
  fail "a long build said nothing: $(cat long_build.err)"
echo "cli_bonded: all checks passed"
