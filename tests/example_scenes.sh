#!/usr/bin/env bash
# Every scene in examples/scenes loads and runs its first steps (stopped as
# if interrupted: exit 130), with the energy log written and finite.
set -euo pipefail
gjkdem="$1"
scenes="$2"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
export OMP_WAIT_POLICY=passive
fail() { echo "FAIL: $*" >&2; exit 1; }
count=0
for scene in "$scenes"/*.toml; do
  name="$(basename "$scene" .toml)"
  status=0
  "$gjkdem" run "$scene" --out "$work/$name" --threads 1 --quiet --stop-after 100 || status=$?
  [ "$status" -eq 130 ] || fail "$name: exit status $status, expected 130 (stopped after 100 steps)"
  grep -q '"status": "interrupted"' "$work/$name/run.json" || fail "$name: run.json does not say interrupted"
  awk -F, 'NR > 1 { for (i = 1; i <= NF; ++i) if ($i !~ /^-?[0-9.e+-]+$/) exit 1 }' "$work/$name/energy.csv" ||
    fail "$name: energy.csv holds a value that is not a finite number"
  count=$((count + 1))
done
[ "$count" -ge 2 ] || fail "found only $count example scenes in $scenes"
echo "ran the first steps of $count example scenes"
