#!/usr/bin/env bash
# The example scene of ../shared/spec/scene-format.md, cut from the spec's own
# text, runs as written (issue 10): loaded, run for 30 steps on 2 threads and
# stopped, every output present. Usage: spec_scene_test.sh GJKDEM SPEC.md
set -euo pipefail
gjkdem="$1"
spec="$2"
[ -f "$spec" ] || { echo "spec_scene: $spec not found"; exit 77; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
# The first ```toml block, verbatim.
awk '/^```toml$/ {inside = 1; next} inside && /^```$/ {exit} inside {print}' "$spec" >"$work/spec.toml"
grep -q 'half_extents' "$work/spec.toml" || { echo "spec_scene: no example scene in $spec"; exit 1; }
status=0
"$gjkdem" run "$work/spec.toml" --out "$work/out" --stop-after 30 --threads 2 --quiet || status=$?
[ "$status" -eq 130 ] || { echo "spec_scene: exit status $status, expected 130 (stopped)"; exit 1; }
for f in run.json trace.csv energy.csv checkpoint.bin frames/frame_000000.vtk; do
  [ -s "$work/out/$f" ] || { echo "spec_scene: $f missing"; exit 1; }
done
grep -q '"status": "interrupted"' "$work/out/run.json" || { echo "spec_scene: run.json does not say interrupted"; exit 1; }
grep -q '^0,cube1,' "$work/out/trace.csv" || { echo "spec_scene: cube1 is not traced"; exit 1; }
bodies=$(sed -nE 's/^  "bodies": ([0-9]+),/\1/p' "$work/out/run.json")
[ "$bodies" -eq 1001 ] || { echo "spec_scene: $bodies bodies, expected 1001"; exit 1; }
echo "spec_scene: the spec's example scene runs ($bodies bodies)"
