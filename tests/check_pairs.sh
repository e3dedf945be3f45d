#!/usr/bin/env bash
# Runs `gjkdem query` on one sample family of ../shared/data/pairs and checks
# it with ../shared/tools/check-pairs. Exit 77 (skipped) when shared/ is absent.
# Usage: check_pairs.sh GJKDEM SHARED_DIR FAMILY FIELDS
set -euo pipefail
gjkdem="$1" shared="$2" family="$3" fields="$4"
in="$shared/data/pairs/$family.in.jsonl"
exp="$shared/data/pairs/$family.expected.jsonl"
if [ ! -f "$in" ] || [ ! -f "$exp" ]; then
  echo "no sample data at $shared/data/pairs: skipped"
  exit 77
fi
out="$(mktemp)"
trap 'rm -f "$out"' EXIT
"$gjkdem" query --in "$in" --out "$out"
/usr/bin/python3 "$shared/tools/check-pairs" "$out" "$exp" --fields "$fields"
