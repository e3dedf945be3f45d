"""The dynamic angle of repose of a rotating drum run, from its view frames.

Usage: python3 drum_angle.py OUT --radius R [--from T] [--axis y] [--band A B]

OUT is a gjkdem run folder (its view frames) or an .npz of `times` and
`frames` (grains' centres, one array per frame), as bench/yade_drum.py writes
for another code's run of the same drum.

For each frame from time T on, the free surface is found across the middle
half of the drum's diameter: the section perpendicular to the axis is cut
into 8 strips, each strip's surface height is the mean height of its 10
highest grains (fixed bodies, the drum's pieces, are left out), and a
straight line through the 8 heights gives the angle. The angle's mean and
spread over the frames are printed, with the centroid method's (the line
from the axis to the bed's centre of mass leans from the vertical by the
angle of a flat surface) as a check. `--band A B` keeps the grains whose
coordinate along the axis lies in [A, B] (a slice near an end cap, say).
For a run folder the drum's torque on the grains about the axis is printed
too, from the frames' contacts (whole drum, whatever the band), and with
`--mass` the torque of gravity on the grains it balances in steady flow.
"""
import argparse
import math
import sys

import numpy as np

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


def drum_torque(f, axis):
    """The torque of the fixed bodies (the drum's pieces) on the grains about the axis (N m)."""
    body = f.contact_first < 0x80000000  # the first side is a body, not a plane wall
    first_fixed = np.zeros(len(body), bool)
    first_fixed[body] = (f.flags[f.contact_first[body]] & 1) == 1
    second_fixed = (f.flags[f.contact_second] & 1) == 1
    # Forces are given on the second side: a grain first takes the opposite.
    sign = np.where(first_fixed & ~second_fixed, 1.0, 0.0) - np.where(body & second_fixed & ~first_fixed, 1.0, 0.0)
    moments = np.cross(f.contact_points.astype(float), f.contact_forces.astype(float))
    return (sign * moments[:, axis]).sum()


def grain_frames(out, axis=1):
    """(time, grains' centres, drum torque or None) of every frame of a run folder or of an .npz."""
    if out.endswith(".npz"):
        saved = np.load(out)
        return [(t, p, None) for t, p in zip(saved["times"], saved["frames"])]
    import gjkdem  # only for run folders

    view = gjkdem.read_view(out)
    frames = []
    for k in range(len(view)):
        f = view.frame(k)
        grains = f.positions[(f.flags & 1) == 0].astype(float)  # no drum pieces
        frames.append((view.index["time"][k], grains, drum_torque(f, axis)))
    return frames


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("out", help="the run folder, or an .npz of times and frames")
    parser.add_argument("--from", dest="start", type=float, default=1.0, help="first time measured (s)")
    parser.add_argument("--radius", type=float, required=True, help="the drum's radius (m)")
    parser.add_argument("--axis", choices="xyz", default="y", help="the drum's axis, through the origin")
    parser.add_argument("--band", type=float, nargs=2, metavar=("A", "B"), help="only grains with A <= axis <= B")
    parser.add_argument("--mass", type=float, help="the grains' mass (kg): compare the drum's torque with gravity's")
    args = parser.parse_args(argv)
    axis = "xyz".index(args.axis)
    across = [a for a in range(3) if a != axis]  # horizontal, vertical (z) of the section
    try:
        frames = grain_frames(args.out, axis)
    except (OSError, ValueError, KeyError) as e:  # no run folder, a damaged frame, an .npz without its arrays
        sys.exit(f"drum_angle.py: cannot read {args.out}: {e}")
    surface, centroid, torque, offset = [], [], [], []
    for time, p, t in frames:
        if time < args.start:
            continue
        if t is not None:
            torque.append(t)
            offset.append(np.cross(p.mean(axis=0), [0, 0, -9.81])[axis])  # gravity's torque per kg of grains
        if args.band:
            along = p[:, axis]
            p = p[(along >= args.band[0]) & (along <= args.band[1])]
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
    if torque:
        # Steady flow: the bed's angular momentum about the axis holds, so the
        # drum's torque on it balances gravity's, M g times the centre's offset.
        line = f"drum torque: {np.mean(torque):.4g} +- {np.std(torque):.2g} N m"
        if args.mass:
            line += f"; it balances gravity's on the grains, M g x: {-args.mass * np.mean(offset):.4g} N m"
        print(line)


if __name__ == "__main__":
    main()
