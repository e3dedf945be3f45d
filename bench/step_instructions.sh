#!/usr/bin/env bash
# Instructions a step executes (valgrind's count, inclusive of begin_step and
# finish_step: the same for the same binary and input whatever the machine's
# load), for two gjkdem programs side by side:
#   bench/step_instructions.sh OLD/build/gjkdem build/gjkdem
# - the free fall of 1,000 polyhedra (bench/scenes/step_free_fall.toml, 200 steps);
# - a bed of 1,000 polyhedra (bench/scenes/step_bed.toml): each program runs
#   2,000 steps natively (it stops and keeps its checkpoint), then its last
#   300 steps under valgrind from that checkpoint (the two must give the same
#   bits, tests/same_bits.sh, for the counts to compare the same work).
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
export OMP_WAIT_POLICY=passive
count() {  # label, then the command
  local label="$1"; shift
  valgrind --tool=callgrind --callgrind-out-file="$work/cg.out" --toggle-collect='gjkdem::dem::begin_step*' \
    --toggle-collect='gjkdem::dem::finish_step*' "$@" >"$work/cg.log" 2>&1 || { cat "$work/cg.log"; exit 1; }
  echo "$label $(sed -n 's/.*Collected : //p' "$work/cg.log")"
}
n=0
for program in "$@"; do
  n=$((n + 1))
  count "free_fall[$n]" "$program" run "$root/bench/scenes/step_free_fall.toml" --out "$work/ff$n" --quiet --threads 1
  status=0
  "$program" run "$root/bench/scenes/step_bed.toml" --out "$work/bed$n" --quiet --threads 1 --stop-after 2000 || status=$?
  [ "$status" -eq 130 ] || { echo "the bed did not stop at step 2000 (status $status)"; exit 1; }
  count "bed[$n]" "$program" run --resume "$work/bed$n" --quiet --threads 1
done
