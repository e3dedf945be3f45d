#!/usr/bin/env python3
"""How far each grain's turn strays from a reference, for the free fall of
bench_dem_scaling (docs/benchmarks.md, "Issue 34: free fall against Yade").

    compare_rotation.py REFERENCE RUN [RUN ...]

Each file holds one grain per line: its hull vertices at the end, world
axes, from its centre of mass (bench_dem_scaling --final, or
bench/yade_free_fall.py's FINAL). Grains are matched by line; a grain's
error is the largest distance from a reference vertex to the nearest vertex
of the run's grain (the two codes may list the vertices in another order),
over the grain's size (twice its largest vertex distance). Prints, per run,
the median, 90th percentile and largest error over the grains."""
import sys

import numpy as np


def grains(path):
    with open(path) as f:
        return [np.array([float(x) for x in line.split()]).reshape(-1, 3) for line in f if line.strip()]


def errors(reference, run):
    if len(reference) != len(run):
        sys.exit("the files hold %d and %d grains" % (len(reference), len(run)))
    out = []
    for r, g in zip(reference, run):
        d = np.linalg.norm(r[:, None, :] - g[None, :, :], axis=2).min(axis=1).max()
        out.append(d / (2 * np.linalg.norm(r, axis=1).max()))
    return np.array(out)


def main():
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    reference = grains(sys.argv[1])
    for path in sys.argv[2:]:
        e = errors(reference, grains(path))
        print("%-40s median %.3e  p90 %.3e  max %.3e  (%d grains)" % (path, np.median(e), np.percentile(e, 90), e.max(), len(e)))


if __name__ == "__main__":
    main()
