#!/usr/bin/env bash
# gjkdem query and bench on mesh pairs (examples/pairs.jsonl ends with one):
# the mesh pair answered with its patches, `bench` timing the surface
# queries, penetration (not defined for meshes) refused with exit status 2.
set -uo pipefail
gjkdem="$1" pairs="$2"
fail() { echo "FAIL: $*"; exit 1; }
line="$("$gjkdem" query --in "$pairs" | grep '"id":"mesh-l-and-box"')" || fail "no answer for the mesh pair"
echo "$line" | grep -q '"overlap_volume":0.375' || fail "wrong volume: $line"
echo "$line" | grep -q '"patches":\[{"volume":0.375' || fail "no patch: $line"
grep '"id":"mesh-l-and-box"' "$pairs" > "${TMPDIR:-/tmp}/cli_mesh_$$.jsonl"
trap 'rm -f "${TMPDIR:-/tmp}/cli_mesh_$$.jsonl"' EXIT
for q in contact intersect distance; do
  "$gjkdem" bench --in "${TMPDIR:-/tmp}/cli_mesh_$$.jsonl" --query "$q" --repeat 2 | grep -q "\"query\": \"$q\"" ||
    fail "bench --query $q on a mesh pair"
done
"$gjkdem" bench --in "${TMPDIR:-/tmp}/cli_mesh_$$.jsonl" --query penetration --repeat 2 2>/dev/null
[ $? -eq 2 ] || fail "penetration on mesh pairs not refused"
echo "1 passed, 0 failed"
