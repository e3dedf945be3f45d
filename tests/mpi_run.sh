#!/usr/bin/env bash
# mpirun -np N gjkdem run (issue 15) on a pour with friction, walls and a
# fixed hopper (tests/data/scenes/mpi_pour.toml), whose grains fall through the
# cuts between domains while touching: trace.csv, energy.csv, the VTK and
# view frames and the checkpoint of a run on 2 ranks are those of the
# serial run, byte for byte (the checkpoint apart from the wall-clock
# seconds it records), and so are those of a run stopped on 3 ranks and
# resumed on 2, and of one stopped on 1 and resumed on 4; with a shaken
# floor too, and for the hopper example (inflow, compounds, a belt), surface
# grains (also stopped on 2 and resumed on 1) and the
# periodic shear example and a servoed shearing cell on 2 ranks (the
# latter also stopped on 1 and resumed on 2); a failure stops every rank
# with its message in run.json, and a rank failing outside the run's
# agreements ends them all: no run left hanging.
set -euo pipefail
gjkdem="$1"
scene="$(cd "$(dirname "$2")" && pwd)/$(basename "$2")"
root="$(cd "$(dirname "$0")/.." && pwd)"
same_checkpoint="$root/tests/same_checkpoint.py"
command -v mpirun >/dev/null || { echo "no mpirun: skipped"; exit 77; }
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
cd "$work"
fail() { echo "FAIL: $*" >&2; exit 1; }
launch=(mpirun --oversubscribe)
[ "$(id -u)" -eq 0 ] && launch+=(--allow-run-as-root)
export OMPI_MCA_mpi_yield_when_idle=1  # ranks share 2 cores with other tests: yield, do not spin

same_run() {  # folder A, folder B
  for f in trace.csv energy.csv frames/frames.vtk.series frames/frame_000004.vtk frames/frame_000008.vtk \
           view/index.csv view/shapes.bin view/frame_000004.bin view/frame_000008.bin; do
    cmp -s "$1/$f" "$2/$f" || fail "$f differs between $1 and $2"
  done
  /usr/bin/python3 "$same_checkpoint" "$1/checkpoint.bin" "$2/checkpoint.bin" || fail "checkpoints of $1 and $2 differ"
}

"$gjkdem" run "$scene" --out serial --quiet || fail "the serial run did not complete"
# The pour must have piled up: contacts at the end (energy.csv's 6th column).
awk -F, 'END { exit !($6 > 100) }' serial/energy.csv || fail "the grains did not pile up"
# More ranks than the 2 cores of the CI machine wait on each other at every
# collective: 3 and 4 ranks run half of the steps each, in the resumes below.
"${launch[@]}" -np 2 "$gjkdem" run "$scene" --out ranks2 --quiet || fail "the run on 2 ranks did not complete"
grep -q '"status": "completed"' ranks2/run.json || fail "run.json of 2 ranks does not say completed"
grep -q '"ranks": 2,' ranks2/run.json || fail "run.json of 2 ranks does not say 2 ranks"
grep -q '"ranks": 1,' serial/run.json || fail "run.json of the serial run does not say 1 rank"
same_run serial ranks2

# A new run from the serial run's end with another friction (--from): 2 ranks give the serial bytes.
sed -e 's/^friction = .*/friction = 0.2/' "$scene" > slick.toml
grep -q "^friction = 0.2" slick.toml || fail "the slick scene was not made"
"$gjkdem" run slick.toml --from serial --out slick1 --quiet || fail "the serial run --from did not complete"
"${launch[@]}" -np 2 "$gjkdem" run slick.toml --from serial --out slick2 --quiet || fail "the run --from on 2 ranks did not complete"
same_run slick1 slick2

# A shaken floor (its work on the grains is in energy.csv): 2 ranks give the serial bytes.
sed -e 's/^normal = \[0.0, 0.0, 1.0\]$/normal = [0.0, 0.0, 1.0]\nmotion = { vibration = { amplitude = [0.0, 0.0, 0.002], frequency = 16.0 } }/' \
  "$scene" > shaken.toml
grep -q vibration shaken.toml || fail "the shaken scene was not made"
"$gjkdem" run shaken.toml --out shaken1 --quiet || fail "the serial shaken run did not complete"
awk -F, 'END { exit !($7 != 0) }' shaken1/energy.csv || fail "the shaken floor did no work"
"${launch[@]}" -np 2 "$gjkdem" run shaken.toml --out shaken2 --quiet || fail "the shaken run on 2 ranks did not complete"
same_run shaken1 shaken2

# The hopper example, cut to 0.5 s: an inflow of polyhedra and L-shaped
# compounds onto a moving belt, on 2 ranks.
sed -e 's/^duration = 2.0$/duration = 0.5/' "$root/examples/scenes/hopper_inflow.toml" > hopper.toml
grep -q "^duration = 0.5$" hopper.toml || fail "the hopper scene was not cut"
"$gjkdem" run hopper.toml --out hopper1 --quiet || fail "the serial hopper run did not complete"
"${launch[@]}" -np 2 "$gjkdem" run hopper.toml --out hopper2 --quiet || fail "the hopper run on 2 ranks did not complete"
for f in trace.csv energy.csv view/index.csv view/frame_000010.bin; do
  cmp -s "hopper1/$f" "hopper2/$f" || fail "$f differs between the hopper runs on 1 and 2 ranks"
done
/usr/bin/python3 "$same_checkpoint" hopper1/checkpoint.bin hopper2/checkpoint.bin || fail "the hopper checkpoints differ"

# Surface grains (issue 30): non-convex rocks onto a fixed ring, each
# patch a contact with its own slot, on 2 ranks and stopped on 2 and resumed
# on 1: the serial bits.
surface_scene="$root/tests/data/scenes/surface_grains.toml"
"$gjkdem" run "$surface_scene" --out surface1 --quiet || fail "the serial surface-grain run did not complete"
"${launch[@]}" -np 2 "$gjkdem" run "$surface_scene" --out surface2 --quiet || fail "the surface-grain run on 2 ranks did not complete"
set +e
"${launch[@]}" -np 2 "$gjkdem" run "$surface_scene" --out surface21 --quiet --stop-after 400
rc=$?
set -e
[ "$rc" -eq 130 ] || fail "the surface-grain run stopped on 2 ranks exited $rc"
"$gjkdem" run --resume surface21 --quiet || fail "the surface-grain run resumed on 1 rank did not complete"
for run in surface2 surface21; do
  for f in trace.csv energy.csv; do cmp -s "surface1/$f" "$run/$f" || fail "$f differs between surface1 and $run"; done
  /usr/bin/python3 "$same_checkpoint" surface1/checkpoint.bin "$run/checkpoint.bin" || fail "checkpoints of surface1 and $run differ"
done
awk -F, 'END { exit !($6 > 10) }' surface1/energy.csv || fail "the surface grains made no contacts"

# Grains that break as they land (docs/breakage.md): 2 ranks, and 2 ranks
# stopped mid-breakage and resumed on 1, give the serial bytes.
sed -e 's/^friction = 0.5$/friction = 0.5\nstrength = 300.0\nstrength_size = 0.01\nunbreakable_below = 0.006/' \
  "$scene" > brittle.toml
grep -q "^strength = 300.0" brittle.toml || fail "the brittle scene was not made"
"$gjkdem" run brittle.toml --out brittle1 --quiet || fail "the serial brittle run did not complete"
grep -q '"grains_broken": [1-9][0-9][0-9]' brittle1/run.json || fail "the brittle grains should break by the hundred"
"${launch[@]}" -np 2 "$gjkdem" run brittle.toml --out brittle2 --quiet || fail "the brittle run on 2 ranks did not complete"
same_run brittle1 brittle2
set +e
"${launch[@]}" -np 2 "$gjkdem" run brittle.toml --out brittle21 --quiet --stop-after 3000
rc=$?
set -e
[ "$rc" -eq 130 ] || fail "the brittle run stopped on 2 ranks exited $rc"
"$gjkdem" run --resume brittle21 --quiet || fail "the brittle run resumed on 1 rank did not complete"
same_run brittle1 brittle21

# Stopped on 3 ranks between checkpoints, resumed on 2.
set +e
"${launch[@]}" -np 3 "$gjkdem" run "$scene" --out three_two --quiet --stop-after 2500
rc=$?
set -e
[ "$rc" -eq 130 ] || fail "a run stopped on 3 ranks should exit with 130, got $rc"
grep -q '"status": "interrupted"' three_two/run.json || fail "run.json does not say interrupted"
"${launch[@]}" -np 2 "$gjkdem" run --resume three_two --quiet || fail "the resume on 2 ranks did not complete"
same_run serial three_two

# Stopped on 1, resumed on 4.
set +e
"$gjkdem" run "$scene" --out one_four --quiet --stop-after 3100
set -e
"${launch[@]}" -np 4 "$gjkdem" run --resume one_four --quiet || fail "the resume on 4 ranks did not complete"
same_run serial one_four

# Runs a scene that must fail on N ranks, promptly and saying MESSAGE:
# expect_failure NAME N MESSAGE (reads NAME.toml, writes NAME/ and NAME.txt).
expect_failure() {
  set +e
  timeout 120 "${launch[@]}" -np "$2" "$gjkdem" run "$1.toml" --out "$1" > "$1.txt" 2>&1
  local rc=$?
  set -e
  [ "$rc" -ne 0 ] && [ "$rc" -ne 124 ] || fail "$1 on $2 ranks did not fail (exit $rc)"
  grep -q "$3" "$1.txt" || fail "$1: the message is missing: $(cat "$1.txt")"
}

# A failure stops every rank, and run.json says why: a time step above the
# stability limit, which rank 0's guards see on the gathered world.
sed -e 's/^dt = "auto"$/dt = 0.01/' "$scene" > unstable.toml
expect_failure unstable 3 "above the stability limit"
grep -q '"status": "failed"' unstable/run.json && grep -q 'above the stability limit' unstable/run.json ||
  fail "run.json does not say why the run failed"

# A rank that fails outside the run's agreements ends every rank at once
# (MPI_Abort), instead of leaving the others waiting for it: here rank 0
# cannot write run.json when a resume starts (a directory stands where its
# temporary file goes).
set +e
"$gjkdem" run "$scene" --out blocked --quiet --stop-after 300
set -e
mkdir -p blocked/run.json.tmp && touch blocked/run.json.tmp/keep
set +e
timeout 120 "${launch[@]}" -np 2 "$gjkdem" run --resume blocked > blocked.txt 2>&1
rc=$?
set -e
[ "$rc" -ne 0 ] && [ "$rc" -ne 124 ] || fail "a rank that could not write run.json left the run hanging or passing (exit $rc)"
grep -q "cannot write" blocked.txt || fail "the failing rank's message is missing: $(cat blocked.txt)"

# The periodic shear example, cut to 0.06 s: a bed periodic across x and y
# under a sliding plate, on 2 ranks (the cell's stress in cell.csv too).
sed -e 's/^duration = 2.0$/duration = 0.06/' "$root/examples/scenes/periodic_shear.toml" > shear.toml
grep -q "^duration = 0.06$" shear.toml || fail "the shear scene was not cut"
"$gjkdem" run shear.toml --out shear1 --quiet || fail "the serial shear run did not complete"
"${launch[@]}" -np 2 "$gjkdem" run shear.toml --out shear2 --quiet || fail "the shear run on 2 ranks did not complete"
for f in trace.csv energy.csv cell.csv view/index.csv view/frame_000003.bin; do
  cmp -s "shear1/$f" "shear2/$f" || fail "$f differs between the shear runs on 1 and 2 ranks"
done

# The simple shear example, cut to 0.44 s: a cell without walls squeezed by
# a servo (which reads the whole stress at every step) while it shears, on
# 2 ranks; stopped on 1 and resumed on 2.
sed -e 's/^duration = 2.0$/duration = 0.44/' "$root/examples/scenes/periodic_simple_shear.toml" > servo.toml
grep -q "^duration = 0.44$" servo.toml || fail "the servo scene was not cut"
"$gjkdem" run servo.toml --out servo1 --quiet || fail "the serial servo run did not complete"
awk -F, 'END { exit !($6 > 50) }' servo1/energy.csv || fail "the servo did not bring the grains into contact"
"${launch[@]}" -np 2 "$gjkdem" run servo.toml --out servo2 --quiet || fail "the servo run on 2 ranks did not complete"
set +e
"$gjkdem" run servo.toml --out servo12 --quiet --stop-after 46000
set -e
"${launch[@]}" -np 2 "$gjkdem" run --resume servo12 --quiet || fail "the servo resume on 2 ranks did not complete"
for run in servo2 servo12; do
  for f in trace.csv energy.csv cell.csv view/index.csv view/frame_000022.bin; do
    cmp -s "servo1/$f" "$run/$f" || fail "$f differs between servo1 and $run"
  done
  /usr/bin/python3 "$same_checkpoint" servo1/checkpoint.bin "$run/checkpoint.bin" || fail "the servo checkpoints of servo1 and $run differ"
done
# A SIGTERM sent to rank 1 alone stops the run at a step's end on every rank,
# as one to rank 0 does: exit 130, run.json says interrupted, and the run
# resumes to the serial bytes.
"${launch[@]}" -np 2 "$gjkdem" run "$scene" --out signalled --quiet > /dev/null 2>&1 &
mpi_pid=$!
rank1=""
for _ in $(seq 1 400); do
  if [ -z "$rank1" ]; then
    for p in $(pgrep -f -- "--out signalled" || true); do
      tr '\0' '\n' < "/proc/$p/environ" 2>/dev/null | grep -qx "OMPI_COMM_WORLD_RANK=1" && rank1="$p"
    done
  fi
  [ -n "$rank1" ] && grep -qs '"status": "running"' signalled/run.json && break
  sleep 0.05
done
[ -n "$rank1" ] || { kill "$mpi_pid" 2>/dev/null; fail "rank 1 of the signalled run was not found"; }
kill -TERM "$rank1"
set +e
wait "$mpi_pid"
rc=$?
set -e
[ "$rc" -eq 130 ] || fail "a SIGTERM to rank 1 should stop the run with 130, got $rc"
grep -q '"status": "interrupted"' signalled/run.json || fail "run.json of the signalled run does not say interrupted"
grep -q "another rank" signalled/run.json || fail "run.json does not say another rank stopped the run"
"${launch[@]}" -np 2 "$gjkdem" run --resume signalled --quiet || fail "the resume of the signalled run did not complete"
same_run serial signalled

echo "mpi_run: serial = 2 ranks = 3 -> 2 = 1 -> 4 ranks; shaken floor, hopper, surface grains, breaking grains, periodic shear and a servoed cell on 2 ranks"
