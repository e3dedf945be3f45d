#!/usr/bin/env bash
# gjkdem query on a file with malformed lines: one output line per input pair
# line, errors naming their line, good lines answered, exit status 1.
set -uo pipefail
gjkdem="$1" input="$2"
out="$("$gjkdem" query --in "$input" 2>/dev/null)"
status=$?
fail() { echo "FAIL: $*"; echo "$out"; exit 1; }
[ "$status" -eq 1 ] || fail "exit status $status, expected 1"
[ "$(echo "$out" | wc -l)" -eq 7 ] || fail "expected 7 result lines"
echo "$out" | sed -n 1p | grep -q '"id":"good-1","intersect":false,"distance":1' || fail "good-1 not answered"
echo "$out" | sed -n 2p | grep -q '"id":null,"error":"line 3: not valid JSON' || fail "bad JSON line"
echo "$out" | sed -n 3p | grep -q "unknown type 'blob'" || fail "unknown type"
echo "$out" | sed -n 4p | grep -q 'line 5: a.radius must be >= 0' || fail "negative radius"
echo "$out" | sed -n 5p | grep -q '"error":"line 6' || fail "NaN"
echo "$out" | sed -n 6p | grep -q "line 8: pair needs shapes 'a' and 'b'" || fail "missing b"
echo "$out" | sed -n 7p | grep -q '"id":"good-2","intersect":true' || fail "good-2 not answered"
echo "1 passed, 0 failed"
