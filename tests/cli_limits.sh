#!/usr/bin/env bash
# Issue 11's input items for the query program and the options: a line
# nested 75,000 deep, lines far outside double precision's reach, a full
# output device, and bad options each get a clear answer, never a crash, a
# silent exit 0 or a nan in the output. Usage: cli_limits.sh GJKDEM
set -euo pipefail
gjkdem="$1"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
cd "$work"
fail() { echo "FAIL: $*" >&2; exit 1; }
good='{"id": "ok", "a": {"type": "sphere", "center": [0, 0, 0], "radius": 1}, "b": {"type": "sphere", "center": [3, 0, 0], "radius": 1}}'

# 1. An id nested 75,000 deep (150 KB): an error line, and the next line is answered.
python3 -c "print('{\"id\": ' + '[' * 75000 + ']' * 75000 + ', \"a\": 1, \"b\": 2}')" > deep.jsonl
echo "$good" >> deep.jsonl
set +e
"$gjkdem" query --in deep.jsonl > deep.out 2> deep.err
rc=$?
set -e
[ "$rc" -eq 1 ] || fail "deep nesting: exit $rc, expected 1"
[ "$(wc -l < deep.out)" -eq 2 ] || fail "deep nesting: $(wc -l < deep.out) output lines, expected 2"
grep -q "nested deeper than 64" deep.out || fail "deep nesting: no error naming the depth"
grep -q '"id":"ok","intersect":false' deep.out || fail "deep nesting: the next line was lost"

# 2. Beyond double precision: refused by range, never answered with nan or inf.
cat > far.jsonl <<'JSON'
{"id": 1, "a": {"type": "sphere", "center": [1e308, 0, 0], "radius": 1}, "b": {"type": "sphere", "center": [-1e308, 0, 0], "radius": 1}}
{"id": 2, "a": {"type": "box", "center": [1e308, 0, 0], "half_extents": [1, 1, 1]}, "b": {"type": "box", "center": [-1e308, 0, 0], "half_extents": [1, 1, 1]}}
{"id": 3, "a": {"type": "polytope", "vertices": [[5.8e307, 0, 0], [5.8e307, 1, 0], [5.8e307, 0, 1], [5.9e307, 0, 0]]}, "b": {"type": "sphere", "center": [0, 0, 0], "radius": 1}}
{"id": 4, "a": {"type": "sphere", "center": [0, 0, 0], "radius": 1e160}, "b": {"type": "sphere", "center": [0, 0, 3e160], "radius": 1e160}}
{"id": 5, "a": {"type": "ellipsoid", "center": [0, 0, 0], "radii": [1e-100, 1e100, 1]}, "b": {"type": "sphere", "center": [0, 0, 0], "radius": 1}}
JSON
set +e
"$gjkdem" query --in far.jsonl > far.out 2>/dev/null
rc=$?
set -e
[ "$rc" -eq 1 ] || fail "far inputs: exit $rc, expected 1"
[ "$(grep -c '"error"' far.out)" -eq 5 ] || fail "far inputs: not every line refused: $(cat far.out)"
grep -qiE 'nan|inf[^o]' far.out && fail "far inputs: nan or inf in the output"
grep -q "supported range" far.out && grep -q "1e12" far.out || fail "far inputs: the range is not named"

# 3. Output that cannot be written: exit 2 with a message, not 0.
if [ -w /dev/full ]; then
  set +e
  "$gjkdem" query --in far.jsonl --out /dev/full 2> full.err
  rc=$?
  set -e
  [ "$rc" -eq 2 ] && grep -q "cannot write the results" full.err || fail "/dev/full: exit $rc: $(cat full.err)"
fi

# 3b. A line longer than the 64 MiB limit is refused unread, in bounded
# memory (under a 1 GB cap: parsing it would take about 1.3 GB), and the
# next line is answered. An answer that is not finite names its line too
# (tests/io/query_jsonl_test.cpp), as every refusal does.
python3 -c "import sys; sys.stdout.write('{\"id\": 1, \"a\": [' + '0,' * (33 << 20) + '0]}\n')" > long.jsonl
echo "$good" >> long.jsonl
set +e
(ulimit -v 1000000; "$gjkdem" query --in long.jsonl > long.out 2> long.err)
rc=$?
set -e
[ "$rc" -eq 1 ] || fail "long line: exit $rc, expected 1: $(cat long.err)"
grep -q '"error":"line 1: longer than 64 MiB' long.out || fail "long line: $(head -c 300 long.out)"
grep -q '"id":"ok","intersect":false' long.out || fail "long line: the next line was lost"

# 4. Bad options exit 2, as documented.
expect2() {
  set +e
  "$gjkdem" "$@" > /dev/null 2> opt.err
  local rc=$?
  set -e
  [ "$rc" -eq 2 ] || fail "gjkdem $*: exit $rc, expected 2"
}
expect2 query --no-such-option
expect2 query --tessellate 3 --in far.jsonl
expect2 run --threads -4
mkdir stopped
expect2 run --resume stopped --out elsewhere
expect2 bogus-command
"$gjkdem" --help > /dev/null || fail "--help should exit 0"
# 5. Runs that would do nothing and say "completed" (issue 11) are refused.
scene() {  # duration, dt, Young's modulus
  printf '[simulation]\nduration = %s\ndt = %s\n[[material]]\nname = "rock"\ndensity = 2500.0\nyoungs_modulus = %s\n[[body]]\nshape = { type = "box", half_extents = [0.01, 0.01, 0.01] }\nmaterial = "rock"\n' "$1" "$2" "$3"
}
scene 1e30 1e-5 1e7 > long.toml
scene 1.0 1e-30 1e7 > tiny_dt.toml
scene 0.01 1.0 1e7 > big_dt.toml
scene 0.01 '"auto"' 1e308 > stiff.toml
scene 0.01 '"auto"' 1e-308 > soft.toml
for f in long tiny_dt big_dt stiff soft; do
  expect2 run "$f.toml" --out "out_$f" --quiet
  grep -qE "2\^53|longer than the duration|must be > 0" opt.err || fail "$f.toml: $(cat opt.err)"
done

# 6. Issue 32's wrong causes: a duration of more than 2^53 steps names its
# keys; a mesh scaled beyond 1e100 m (or below 1e-100 m) names `scale`, not
# a flat mesh.
scene 9007199254740993 '"auto"' 1e7 > steps.toml
expect2 run steps.toml --out out_steps --quiet
grep -q "simulation.duration and dt: the run would take" opt.err || fail "steps.toml: $(cat opt.err)"
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n' > tet.obj
for scale in 1.0e200 1.0e-200; do
  printf '[simulation]\nduration = 0.01\n[[material]]\nname = "rock"\ndensity = 2500.0\nyoungs_modulus = 1.0e7\n[[body]]\nshape = { type = "compound", file = "tet.obj", scale = %s }\nmaterial = "rock"\n' "$scale" > scaled.toml
  expect2 run scaled.toml --out out_scaled --quiet
  grep -q "shape.scale: .* the mesh" opt.err || fail "scale $scale: $(cat opt.err)"
done

echo "cli_limits: all checks passed"
