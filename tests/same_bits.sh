#!/usr/bin/env bash
# Same bits as a reference build: every example scene, every test scene and
# the default scene run their first STEPS steps (stopped as if interrupted,
# which writes the checkpoint) with the reference binary on one thread, then
# with the binary under test on 1 and 2 threads, on 1 to 4 MPI ranks, and
# stopped half way and resumed;
# trace.csv, energy.csv and the checkpoint (but the wall-clock seconds it
# records) must match byte for byte. Kept for refactors of the engine
# (issue 29): build the commit before the change into another folder and
#   tests/same_bits.sh OLD/build/gjkdem build/gjkdem [STEPS]
# No MPI ranks are run where mpirun is missing.
set -euo pipefail
reference="$(realpath "$1")"
candidate="$(realpath "$2")"
steps="${3:-300}"
root="$(cd "$(dirname "$0")/.." && pwd)"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
export OMP_WAIT_POLICY=passive OMPI_MCA_mpi_yield_when_idle=1
launch=(mpirun --oversubscribe)
[ "$(id -u)" -eq 0 ] && launch+=(--allow-run-as-root)
failures=0

run_to() {  # out folder, then the command; a stop by --stop-after exits 130
  local out="$1"; shift
  local status=0
  "$@" --out "$out" --quiet --stop-after "$steps" >"$out.log" 2>&1 || status=$?
  if [ "$status" -ne 130 ] && [ "$status" -ne 0 ]; then
    echo "FAIL: $out: exit status $status"; cat "$out.log"; return 1
  fi
}

same() {  # reference folder, candidate folder, label
  for f in trace.csv energy.csv; do
    [ -f "$1/$f" ] || continue
    cmp -s "$1/$f" "$2/$f" || { echo "FAIL: $3: $f differs"; return 1; }
  done
  /usr/bin/python3 "$root/tests/same_checkpoint.py" "$1/checkpoint.bin" "$2/checkpoint.bin" ||
    { echo "FAIL: $3: the checkpoints differ"; return 1; }
}

scenes=("$root"/examples/scenes/*.toml "$root"/tests/data/scenes/*.toml default)
for scene in "${scenes[@]}"; do
  name="$(basename "$scene" .toml)"
  args=(run)
  [ "$scene" = default ] || args+=("$scene")
  run_to "$work/$name.ref" "$reference" "${args[@]}" --threads 1 || { failures=$((failures + 1)); continue; }
  variants=("t1:--threads 1" "t2:--threads 2")
  if command -v mpirun >/dev/null; then
    for n in 1 2 3 4; do variants+=("np$n:mpi $n"); done
  fi
  for v in "${variants[@]}"; do
    label="${v%%:*}"; how="${v#*:}"
    out="$work/$name.$label"
    if [ "${how%% *}" = mpi ]; then
      run_to "$out" "${launch[@]}" -np "${how#mpi }" "$candidate" "${args[@]}" --threads 1 || { failures=$((failures + 1)); continue; }
    else
      # shellcheck disable=SC2086
      run_to "$out" "$candidate" "${args[@]}" $how || { failures=$((failures + 1)); continue; }
    fi
    if same "$work/$name.ref" "$out" "$name $label"; then echo "same: $name $label"; else failures=$((failures + 1)); fi
  done
  # Stopped half way and resumed (one thread): the bits of the run that never stopped.
  out="$work/$name.resumed"
  status=0
  "$candidate" "${args[@]}" --threads 1 --out "$out" --quiet --stop-after $((steps / 2)) >"$out.log" 2>&1 || status=$?
  [ "$status" -eq 130 ] || { echo "FAIL: $name resumed: the first half exited $status"; failures=$((failures + 1)); continue; }
  status=0
  "$candidate" run --resume "$out" --quiet --stop-after "$steps" >>"$out.log" 2>&1 || status=$?
  if [ "$status" -ne 130 ] && [ "$status" -ne 0 ]; then
    echo "FAIL: $name resumed: the second half exited $status"; cat "$out.log"; failures=$((failures + 1)); continue
  fi
  if same "$work/$name.ref" "$out" "$name resumed"; then echo "same: $name resumed"; else failures=$((failures + 1)); fi
done
[ "$failures" -eq 0 ] || { echo "$failures differences"; exit 1; }
echo "every scene gives the reference's bits"
