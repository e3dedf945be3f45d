#!/usr/bin/env python3
"""Two builds' bench_surfaces on the same pairs, alternated run by run.

On a noisy machine one run's figures are not enough: this runs each build's
bench_surfaces RUNS times, alternating, keeps each pair's smallest median
(overlap plus distance, us) per build, and prints them pair by pair with
their ratio, then the median per size (triangles of A + B; the upper median,
as bench_surfaces prints) and the range of the ratios:

  python3 bench/compare_surfaces.py PAIRS.jsonl OLD_BUILD NEW_BUILD [--runs 5] [--repeat 21]

OLD_BUILD and NEW_BUILD are build folders holding bench/bench_surfaces.
"""
import argparse
import collections
import subprocess
import sys


def run_once(build, pairs, repeat):
    out = subprocess.run([f"{build}/bench/bench_surfaces", "--in", pairs, "--repeat", str(repeat)],
                         capture_output=True, text=True, check=True).stdout
    times = {}
    for line in out.splitlines():
        f = line.split()
        if len(f) == 4 and f[0].startswith('"'):
            times[f[0].strip('"')] = (int(f[1]), float(f[2]) + float(f[3]))
    return times


def main():
    p = argparse.ArgumentParser()
    p.add_argument("pairs")
    p.add_argument("old")
    p.add_argument("new")
    p.add_argument("--runs", type=int, default=5)
    p.add_argument("--repeat", type=int, default=21)
    a = p.parse_args()
    best = collections.defaultdict(dict)
    size = {}
    for _ in range(a.runs):
        for build in (a.old, a.new):
            for pair, (tris, t) in run_once(build, a.pairs, a.repeat).items():
                size[pair] = tris
                best[pair][build] = min(best[pair].get(build, float("inf")), t)
    by_size = collections.defaultdict(list)
    print(f"{'pair':44s} {'old us':>9s} {'new us':>9s} {'new/old':>8s}")
    for pair in best:
        old, new = best[pair][a.old], best[pair][a.new]
        by_size[size[pair]].append((old, new))
        print(f"{pair:44s} {old:9.2f} {new:9.2f} {new / old:8.3f}")
    print(f"\n{'tris':>6s} {'pairs':>5s} {'old median':>10s} {'new median':>10s} {'ratios':>11s}")
    for tris in sorted(by_size):
        rows = by_size[tris]
        old = sorted(o for o, _ in rows)[len(rows) // 2]
        new = sorted(n for _, n in rows)[len(rows) // 2]
        ratios = sorted(n / o for o, n in rows)
        print(f"{tris:6d} {len(rows):5d} {old:10.2f} {new:10.2f} {ratios[0]:5.2f}-{ratios[-1]:.2f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
