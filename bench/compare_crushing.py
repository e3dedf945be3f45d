"""The fragment sizes of a gjkdem crushing run and of Yade's run of the same
press (bench/yade_crushing.py), side by side (docs/breakage.md):

    PYTHONPATH=build/python python3 bench/compare_crushing.py RUN YADE.npz

A grain's size is the diameter of the sphere of its volume; the first table
gives the count, d10/d50/d90 by volume and the volume fraction passing each
sieve size, at the end of both runs (gjkdem's last frame). The second gives,
at gjkdem's frames from 0.40 s on (Yade records every 0.01 s from its start),
the press's height and the force on it (gjkdem: the sum of its plane's
contact forces in the frame; Yade: the force on the plate) and the number
of grains."""
import math
import sys

import numpy as np

import gjkdem


def volume(vertices, triangles):  # of a closed mesh, by the divergence theorem
    v = vertices.astype(float)
    a, b, c = v[triangles[:, 0]], v[triangles[:, 1]], v[triangles[:, 2]]
    return float(np.einsum("ij,ij->i", a, np.cross(b, c)).sum() / 6)


def gjkdem_volumes(run):
    view = gjkdem.read_view(run)
    frame = view.frame(len(view.index) - 1)
    meshes = {}
    out = []
    for i in range(len(frame.positions)):
        if frame.flags[i]:
            continue
        t = int(frame.templates[i])
        if t not in meshes:
            vertices, triangles = view.templates[t]
            meshes[t] = volume(vertices, triangles.reshape(-1, 3))
        out.append(meshes[t])
    return np.array(out), float(frame.time)


PLANE_SIDE = 0x80000000  # a contact's first side at or above this is a plane wall


def gjkdem_press(run):  # per frame: time, press height, force on the press (N, pushing up), grains
    view = gjkdem.read_view(run)
    rows = []
    for k in range(len(view.index)):
        f = view.frame(k)
        first = f.contact_first.astype(np.int64)
        force = -f.contact_forces[first >= PLANE_SIDE].astype(float).sum(axis=0)[2]
        rows.append((float(f.time), float(f.plane_points[0][2]), force, int((~f.fixed).sum())))
    return rows


def summary(volumes, sieves):
    sizes = (6 * volumes / math.pi) ** (1 / 3)
    order = np.argsort(sizes)
    passing = np.cumsum(volumes[order]) / volumes.sum()
    d = lambda f: sizes[order][np.searchsorted(passing, f)]
    rows = [len(sizes), 1e3 * d(0.1), 1e3 * d(0.5), 1e3 * d(0.9)]
    rows += [volumes[sizes <= s].sum() / volumes.sum() for s in sieves]
    return rows


def main():
    run, yade_file = sys.argv[1], sys.argv[2]
    g, time = gjkdem_volumes(run)
    y = np.load(yade_file)
    sieves = [0.002, 0.003, 0.004, 0.005, 0.006, 0.007]
    names = ["grains", "d10 (mm)", "d50 (mm)", "d90 (mm)"] + [f"passing {1e3 * s:.0f} mm" for s in sieves]
    a, b = summary(g, sieves), summary(y["volumes"], sieves)
    print(f"| at t = {time:.2f} s | gjkdem | Yade |")
    print("|---|---|---|")
    for name, x, z in zip(names, a, b):
        fmt = "{:.0f}" if name == "grains" else "{:.2f}" if "mm)" in name else "{:.1%}"
        print(f"| {name} | {fmt.format(x)} | {fmt.format(z)} |")
    if "press" not in y.files:
        return
    print()
    print("| t (s) | press (mm) gjkdem / Yade | press force (N) gjkdem / Yade | grains gjkdem / Yade |")
    print("|---|---|---|---|")
    for t, z, force, grains in gjkdem_press(run):
        j = int(np.argmin(np.abs(y["times"] - t)))
        if t < 0.4 - 1e-3 or abs(y["times"][j] - t) > 2e-3:
            continue
        force = round(force, 2) + 0  # no "-0.00"
        print(f"| {t:.2f} | {1e3 * z:.2f} / {1e3 * y['press_z'][j]:.2f} | {force:.2f} / {y['press'][j]:.2f} | "
              f"{grains} / {y['counts'][j]} |")


if __name__ == "__main__":
    main()
