"""Reading a run folder's view/ frames (docs/view-format.md) with NumPy.

    run = gjkdem.read_view("out")
    run.index["time"]                 # one row per frame written so far
    f = run.frame(-1)                 # the last one
    f.positions                       # (N, 3) float32, a read-only view of the file's bytes
    f.contact_forces.sum(axis=0)

Arrays are views of the file's bytes (no copy); they are read-only.
"""
import pathlib

import numpy as np

VERSION = 4
OLDEST_VERSION = 2  # version 2 frames hold no bonds, version 3 no channel block
PLANE_SIDE = 0x80000000  # a contact's first side at or above this is plane wall (side - PLANE_SIDE)
FIXED, DRIVEN = 1, 2     # body flags

_INDEX_DTYPE = [("frame", "u8"), ("time", "f8"), ("step", "u8"), ("bodies", "u8"), ("contacts", "u8")]


class ViewFormatError(ValueError):
    """A view file that is not one, of another version, or damaged."""


class _Cursor:
    def __init__(self, data, what):
        self.data, self.what, self.at = data, what, 0

    def magic(self, magic):
        if bytes(self.data[:8]) != magic:
            raise ViewFormatError(f"{self.what} is not a gjkdem view file (wrong magic)")
        self.at = 8
        self.version = int(self.take("<u4", 1)[0])
        if not OLDEST_VERSION <= self.version <= VERSION:
            raise ViewFormatError(f"{self.what} has view format version {self.version}; this gjkdem reads versions "
                                  f"{OLDEST_VERSION} to {VERSION}")

    def take(self, dtype, count, cols=None):
        dtype = np.dtype(dtype)
        end = self.at + dtype.itemsize * count
        if end > len(self.data):
            raise ViewFormatError(f"{self.what} is cut short")
        a = np.frombuffer(self.data, dtype=dtype, count=count, offset=self.at)
        self.at = end
        return a.reshape(-1, cols) if cols else a

    def pad4(self):
        end = self.at + -self.at % 4
        if end > len(self.data):
            raise ViewFormatError(f"{self.what} is cut short")
        if any(self.data[self.at:end]):
            raise ViewFormatError(f"{self.what} has padding that is not zero")
        self.at = end

    def end(self):
        if self.at != len(self.data):
            raise ViewFormatError(f"{self.what} has {len(self.data) - self.at} bytes past its end")


class Frame:
    """One frame: bodies (N), touching contacts (M) and plane walls (P).

    `channels` maps each channel of the frame's channel block (docs/view-format.md: applied loads while a run has
    them) to its (N, components) values, `channel_units` to its unit."""

    def __init__(self, data, what="frame"):
        c = _Cursor(data, what)
        c.magic(b"GJKFRAME")
        n, m, p = (int(x) for x in c.take("<u4", 3))
        self.time = float(c.take("<f8", 1)[0])
        self.step = int(c.take("<u8", 1)[0])
        self.positions = c.take("<f4", 3 * n, 3)
        self.orientations = c.take("<f4", 4 * n, 4)  # w, x, y, z: body frame to world
        self.velocities = c.take("<f4", 3 * n, 3)
        self.angular_velocities = c.take("<f4", 3 * n, 3)
        self.templates = c.take("<u4", n)
        self.ids = c.take("<u4", n)
        self.flags = c.take("u1", n)
        c.pad4()
        self.contact_first = c.take("<u4", m)   # body index, or PLANE_SIDE + plane
        self.contact_second = c.take("<u4", m)  # body index
        self.contact_points = c.take("<f4", 3 * m, 3)
        self.contact_normals = c.take("<f4", 3 * m, 3)  # first side -> second
        self.contact_forces = c.take("<f4", 3 * m, 3)   # on the second body
        self.plane_points = c.take("<f4", 3 * p, 3)
        self.plane_normals = c.take("<f4", 3 * p, 3)
        self.cell_axes = int(c.take("<u4", 1)[0])  # bit 0 x, 1 y, 2 z; 0: not periodic
        cell = c.take("<f4", 9, 3)
        self.cell_lo, self.cell_hi, self.cell_tilt = cell[0], cell[1], cell[2]  # tilt: xy, xz, yz
        # Bonds of bonded assemblies (docs/breakage.md): two body indices, the glued face's centre, intact or broken.
        k = int(c.take("<u4", 1)[0]) if c.version >= 3 else 0
        self.bond_first = c.take("<u4", k)
        self.bond_second = c.take("<u4", k)
        self.bond_points = c.take("<f4", 3 * k, 3)
        self.bond_intact = c.take("u1", k).astype(bool)
        # The channel block (version 4): per-body quantities by name, each (N, components) float32.
        self.channels, self.channel_units = {}, {}
        if c.version >= 4:
            c.pad4()
            for number in range(int(c.take("<u4", 1)[0])):
                components, name_bytes, unit_bytes = (int(x) for x in c.take("<u4", 3))
                if not (1 <= components <= 4 and 1 <= name_bytes <= 64 and unit_bytes <= 64):
                    raise ViewFormatError(f"{what} has channel {number} with a size, a name or a unit length it "
                                          "cannot have")
                text = bytes(c.take("u1", name_bytes + unit_bytes))
                name, unit = text[:name_bytes].decode("latin-1"), text[name_bytes:].decode("latin-1")
                if not all(ch.islower() or ch.isdigit() or ch == "_" for ch in name) or not name.isascii():
                    raise ViewFormatError(f"{what} has channel {number} whose name is not lower case letters, "
                                          "digits and _")
                if name in self.channels:
                    raise ViewFormatError(f"{what} has the channel '{name}' twice")
                if not all(" " <= ch <= "~" for ch in unit):
                    raise ViewFormatError(f"{what} has channel '{name}' whose unit is not printable ASCII")
                c.pad4()
                self.channels[name] = c.take("<f4", components * n, components)
                self.channel_units[name] = unit
        c.end()
        if np.any(self.bond_first >= n) or np.any(self.bond_second >= n):
            raise ViewFormatError(f"{what} has a bond naming a body it does not have")
        first_body = self.contact_first < PLANE_SIDE
        if (np.any(self.contact_second >= n) or np.any(self.contact_first[first_body] >= n)
                or np.any(self.contact_first[~first_body] - PLANE_SIDE >= p)):
            raise ViewFormatError(f"{what} has a contact naming a body or plane it does not have")

    @property
    def fixed(self):
        """(N,) bool: fixed bodies (walls' pieces, obstacles), the FIXED bit of flags."""
        return (self.flags & FIXED) != 0

    @property
    def driven(self):
        """(N,) bool: bodies moved by a prescribed motion, the DRIVEN bit of flags."""
        return (self.flags & DRIVEN) != 0

    def __len__(self):
        return len(self.templates)


class RunView:
    """The view/ folder of a run: its templates' surfaces, its index and its frames."""

    def __init__(self, run_dir):
        self.dir = pathlib.Path(run_dir) / "view"
        shapes = self.dir / "shapes.bin"
        if not shapes.is_file():
            raise FileNotFoundError(f"{self.dir} holds no shapes.bin: not a run folder, or output.view was false")
        c = _Cursor(shapes.read_bytes(), str(shapes))
        c.magic(b"GJKSHAPE")
        t, p, _ = (int(x) for x in c.take("<u4", 3))
        self.templates = []  # (vertices (V, 3) float32 in the body's frame, triangles (F, 3) uint32)
        for _ in range(t):
            v, f = (int(x) for x in c.take("<u4", 2))
            vertices, triangles = c.take("<f4", 3 * v, 3), c.take("<u4", 3 * f, 3)
            if np.any(triangles >= v):
                raise ViewFormatError(f"{shapes} has a triangle naming a vertex it does not have")
            self.templates.append((vertices, triangles))
        self.plane_ids = c.take("<u4", p)
        c.end()
        self.reload()

    def reload(self):
        """Reads the index again (a run still going adds frames)."""
        text = (self.dir / "index.csv").read_text()
        # A last line without its newline is still being written: left for the next read.
        lines = text[:text.rfind("\n") + 1].splitlines()
        if not lines or lines[0] != "frame,time,step,bodies,contacts":
            raise ViewFormatError(f"{self.dir / 'index.csv'} does not start with the view index header")
        rows = []
        for number, line in enumerate(lines[1:], start=2):
            fields = line.split(",")
            try:
                if len(fields) != 5:
                    raise ValueError(f"{len(fields)} fields, not 5")
                row = tuple(float(x) if k == 1 else int(x) for k, x in enumerate(fields))
                if any(v < 0 for k, v in enumerate(row) if k != 1) or not np.isfinite(row[1]):
                    raise ValueError("a negative count or a time that is not finite")
                if row[0] >= 2**63 or row[2] >= 2**63 or row[3] >= 2**32 or row[4] >= 2**32:
                    raise ValueError("a frame number or count out of range")
            except ValueError as e:
                raise ViewFormatError(f"{self.dir / 'index.csv'} line {number}: not a frame's row ({e})") from None
            rows.append(row)
        self.index = np.array(rows, dtype=_INDEX_DTYPE)

    def __len__(self):
        return len(self.index)

    def frame(self, k):
        """Frame k of the index (negative counts from the end)."""
        number = int(self.index["frame"][k])
        path = self.dir / f"frame_{number:06d}.bin"
        frame = Frame(path.read_bytes(), str(path))
        if np.any(frame.templates >= len(self.templates)):
            raise ViewFormatError(f"{path} names a shape template shapes.bin does not have")
        return frame


def read_view(run_dir):
    """The view/ frames of the run folder `run_dir` (docs/view-format.md)."""
    return RunView(run_dir)
