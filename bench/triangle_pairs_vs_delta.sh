#!/usr/bin/env bash
# Issue 30's triangle-pair figure, in one run: Delta's kernels (the thesis's
# code, through ../shared/tools/peers/delta, built with -O3 and with -O3
# -march=native) against `gjkdem bench --query distance`, which times the
# batched kernel, on the same seeded pair sets (random, parallel, touching) at
# triangle size 1 and 0.01. One core; best of 5 rounds for every kernel.
#
#   bench/triangle_pairs_vs_delta.sh [BUILD]    # BUILD: gjkdem's Release build (default build/)
#
# Prints a Markdown table: ns per pair for each of Delta's kernels (the
# fastest configuration), gjkdem's, and the ratio of Delta's fastest to it.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=$(cd "${1:-$root/build}" && pwd)
delta=$root/../shared/tools/peers/delta
[ -x "$build/gjkdem" ] || { echo "no $build/gjkdem: build gjkdem first" >&2; exit 1; }
GJKDEM_SRC=$root GJKDEM_LIBS=$build BUILD_DIR=$build/peers-delta "$delta/build.sh" o3 native >/dev/null 2>&1 ||
  { echo "building Delta's harness failed (run $delta/build.sh to see why)" >&2; exit 1; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
for scale in 1 0.01; do
  for cfg in o3 native; do
    "$build/peers-delta/$cfg/bench" --scale "$scale" --reps 5 > "$tmp/delta-$cfg-$scale.md"
  done
  "$build/peers-delta/o3/bench" --scale "$scale" --write-jsonl "$tmp/pairs-$scale" > /dev/null
  for set in random parallel touching; do
    "$build/gjkdem" bench --in "$tmp/pairs-$scale-$set.jsonl" --query distance --repeat 5 > "$tmp/gjkdem-$scale-$set.json"
  done
done
python3 - "$tmp" <<'EOF'
import json, pathlib, sys
tmp = pathlib.Path(sys.argv[1])
print("| scale | set | Delta's fastest kernel (config): ns/pair | its wrong pairs | gjkdem bench (batched kernel): ns/pair | gjkdem's wrong pairs | ratio |")
print("|---|---|---|---:|---:|---:|---:|")
for scale in ("1", "0.01"):
    best, ours = {}, {}
    for cfg in ("o3", "native"):
        for line in (tmp / f"delta-{cfg}-{scale}.md").read_text().splitlines():
            cells = [c.strip() for c in line.strip().strip("|").split("|")]
            if cfg == "o3" and len(cells) >= 8 and cells[0] == "gjkdem triangle_contact":
                ours[cells[1]] = cells[6]  # the one-pair path: the same bits as the batched kernel (tested)
            if len(cells) < 8 or not cells[0].startswith("delta") or "1x1" in cells[0]:
                continue  # the contact API reports only pairs within its margin: not a distance kernel
            kernel, set_, ns, wrong = cells[0], cells[1], float(cells[2]), cells[6]
            if set_ not in best or ns < best[set_][0]:
                best[set_] = (ns, f"{kernel} ({cfg})", wrong)
    for set_ in ("random", "parallel", "touching"):
        g = json.loads((tmp / f"gjkdem-{scale}-{set_}.json").read_text())
        assert g.get("kernel") == "triangle_distances", g
        ns, name, wrong = best[set_]
        print(f"| {scale} | {set_} | {ns:.1f}: {name} | {wrong} | {g['ns_min']:.1f} ({g['simd']}) | {ours[set_]} | {ns / g['ns_min']:.2f}x |")
EOF
