#!/usr/bin/env bash
# Runs `gjkdem query` on a pair file and checks it against its expected answers
# with the shared checker. Exit 77 (skipped) when the files or the checker are absent.
# Usage: check_pairs.sh GJKDEM CHECKER IN.jsonl EXPECTED.jsonl FIELDS
set -euo pipefail
gjkdem="$1" checker="$2" in="$3" exp="$4" fields="$5"
for f in "$checker" "$in" "$exp"; do
  if [ ! -f "$f" ]; then
    echo "missing $f: skipped"
    exit 77
  fi
done
out="$(mktemp)"
trap 'rm -f "$out"' EXIT
"$gjkdem" query --in "$in" --out "$out"
/usr/bin/python3 "$checker" "$out" "$exp" --input "$in" --fields "$fields"
