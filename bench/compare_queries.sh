#!/usr/bin/env bash
# Instructions per pass of `gjkdem bench` for two builds of gjkdem, family by
# family and query by query: valgrind's count of a run with 1 pass and one
# with 1 + K passes, their difference over K (loading the pairs cancels).
# The count is the same for the same binary and input whatever the load, so
# two builds compare without the machine's noise.
#
#   bench/compare_queries.sh OLD/gjkdem NEW/gjkdem [PAIRS_DIR] > table.md
#
# PAIRS_DIR holds FAMILY.in.jsonl files (default ../shared/data/pairs).
# FAMILIES and QUERIES (space-separated) narrow the table.
set -euo pipefail
old="$1"
new="$2"
dir="${3:-../shared/data/pairs}"

count() {  # binary family query passes -> instructions
  valgrind --tool=cachegrind --cache-sim=no --cachegrind-out-file=/dev/null \
    "$1" bench --in "$dir/$2.in.jsonl" --query "$3" --repeat "$4" 2>&1 >/dev/null |
    sed -n 's/.*I *refs: *//p' | tr -d ,
}

echo "| family | query | old, per pass | new, per pass | new/old |"
echo "|---|---|---|---|---|"
for family in ${FAMILIES:-poly-random poly-near poly-degenerate mixed-analytic curved poly-many}; do
  extra=20
  [ "$family" = poly-many ] && extra=2
  for query in ${QUERIES:-intersect distance penetration contact}; do
    row=()
    for bin in "$old" "$new"; do
      one=$(count "$bin" "$family" "$query" 1)
      more=$(count "$bin" "$family" "$query" $((1 + extra)))
      row+=($(( (more - one) / extra )))
    done
    ratio=$(awk -v a="${row[0]}" -v b="${row[1]}" 'BEGIN { printf (a > 0 ? "%.3f" : "-"), b / a }')
    echo "| $family | $query | ${row[0]} | ${row[1]} | $ratio |"
  done
done
