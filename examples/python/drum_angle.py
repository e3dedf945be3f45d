"""The dynamic angle of repose of a rotating drum run, from its view frames.

Usage: python3 drum_angle.py OUT --radius R [--from T] [--axis y] [--band A B]

For each frame from time T on, the free surface is found across the middle
half of the drum's diameter: the section perpendicular to the axis is cut
into 8 strips, each strip's surface height is the mean height of its 10
highest grains (fixed bodies, the drum's pieces, are left out), and a
straight line through the 8 heights gives the angle. The angle's mean and
spread over the frames are printed, with the centroid method's (the line
from the axis to the bed's centre of mass leans from the vertical by the
angle of a flat surface) as a check. `--band A B` keeps the grains whose
coordinate along the axis lies in [A, B] (a slice near an end cap, say).
"""
import argparse
import math
import sys

import numpy as np

import gjkdem

STRIPS = 8
TOP = 10


def surface_angle(x, z, radius):
    """Angle (degrees) of the line through the strips' top heights."""
    edges = np.linspace(-radius / 2, radius / 2, STRIPS + 1)
    centres, heights = [], []
    for k in range(STRIPS):
        inside = (x >= edges[k]) & (x < edges[k + 1])
        if np.count_nonzero(inside) < TOP:
            continue
        top = np.sort(z[inside])[-TOP:]
        centres.append(0.5 * (edges[k] + edges[k + 1]))
        heights.append(top.mean())
    if len(centres) < 3:
        return math.nan
    slope = np.polyfit(centres, heights, 1)[0]
    return math.degrees(math.atan(abs(slope)))


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("out", help="the run folder")
    parser.add_argument("--from", dest="start", type=float, default=1.0, help="first time measured (s)")
    parser.add_argument("--radius", type=float, required=True, help="the drum's radius (m)")
    parser.add_argument("--axis", choices="xyz", default="y", help="the drum's axis, through the origin")
    parser.add_argument("--band", type=float, nargs=2, metavar=("A", "B"), help="only grains with A <= axis <= B")
    args = parser.parse_args(argv)
    axis = "xyz".index(args.axis)
    across = [a for a in range(3) if a != axis]  # horizontal, vertical (z) of the section
    view = gjkdem.read_view(args.out)
    surface, centroid = [], []
    for k in range(len(view)):
        if view.index["time"][k] < args.start:
            continue
        f = view.frame(k)
        grains = (f.flags & 1) == 0
        if args.band:
            along = f.positions[:, axis]
            grains &= (along >= args.band[0]) & (along <= args.band[1])
        p = f.positions[grains].astype(float)
        x, z = p[:, across[0]], p[:, across[1]]
        surface.append(surface_angle(x, z, args.radius))
        centroid.append(math.degrees(math.atan2(abs(x.mean()), -z.mean())))
    if not surface:
        sys.exit(f"no frame at or after t = {args.start} s")
    surface = np.array(surface)
    surface = surface[np.isfinite(surface)]
    print(f"frames {len(centroid)}, from t = {args.start} s")
    print(f"free surface: {surface.mean():.2f} +- {surface.std():.2f} degrees")
    print(f"centroid: {np.mean(centroid):.2f} +- {np.std(centroid):.2f} degrees")


if __name__ == "__main__":
    main()
