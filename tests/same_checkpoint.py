#!/usr/bin/env python3
"""Exit 0 when two gjkdem checkpoints hold the same run state, apart from the
wall-clock seconds they record (LOGS) and the header's checksum over them.
Checkpoints of one format are compared byte for byte. Across formats 9 to
11 (docs/checkpoints.md) the state is compared decoded: the bodies by their
named columns (format 9's fixed ones; a column one file lacks must be zero,
bit for bit, in the other), STAT field by field (format 10's applied_loads
flag must be 0 where the other file lacks it; format 11's split_energy is
not compared with a file that lacks it: the older build did not count it),
and every other section byte for byte; INFO, the text naming the format, is
not compared. Usage: same_checkpoint.py A B"""
import struct
import sys

HEADER = 40  # src/io/checkpoint.cpp: kHeaderBytes
FORMAT9_COLUMNS = [("position", 3), ("orientation", 4), ("velocity", 3), ("angular_momentum", 3), ("force", 3),
                   ("torque", 3)]


def sections(path):
    data = open(path, "rb").read()
    (version,) = struct.unpack_from("<I", data, 8)
    out, at = {}, HEADER
    while at < len(data):
        tag = data[at:at + 4].decode("ascii")
        (length,) = struct.unpack_from("<Q", data, at + 4)
        body = bytearray(data[at + 12:at + 12 + length])
        if tag == "LOGS":
            body[24:32] = bytes(8)  # trace, energy, cell bytes (u64 each), then wall_seconds
        out[tag] = bytes(body)
        at += 12 + length
    return data[:8], version, out


def bodies(section, version):
    """[(id, shape, material, {column: bytes of its reals})] of a BODY section."""
    at = 0
    if version >= 10:
        (ncols,) = struct.unpack_from("<Q", section, at)
        at += 8
        columns = []
        for _ in range(ncols):
            (n,) = struct.unpack_from("<Q", section, at)
            name = section[at + 8:at + 8 + n].decode()
            (components,) = struct.unpack_from("<I", section, at + 8 + n)
            columns.append((name, components))
            at += 12 + n
    else:
        columns = FORMAT9_COLUMNS
    (count,) = struct.unpack_from("<Q", section, at)
    at += 8
    out = []
    for _ in range(count):
        head = struct.unpack_from("<QII", section, at)
        at += 16
        values = {}
        for name, components in columns:
            values[name] = section[at:at + 8 * components]
            at += 8 * components
        out.append((head, values))
    return out


def same_bodies(a, va, b, vb):
    x, y = bodies(a, va), bodies(b, vb)
    if len(x) != len(y):
        return False
    for (head_x, cols_x), (head_y, cols_y) in zip(x, y):
        if head_x != head_y:
            return False
        for name in set(cols_x) | set(cols_y):
            mine, theirs = cols_x.get(name), cols_y.get(name)
            if mine is None or theirs is None:
                present = mine if theirs is None else theirs
                if present != bytes(len(present)):
                    return False
            elif mine != theirs:
                return False
    return True


def stat_fields(section, version):
    """{field: bytes} of a STAT section (src/io/checkpoint.cpp)."""
    layout = [("forces_current", 1), ("elastic_energy", 8), ("contacts", 8), ("wall_contacts", 8),
              ("wall_power", 8), ("wall_work", 8)]
    if version >= 11:
        layout.append(("split_energy", 8))
    if version >= 10:
        layout.append(("applied_loads", 1))
    out, at = {}, 0
    for name, size in layout:
        out[name] = section[at:at + size]
        at += size
    return out if at == len(section) else None


def same_stat(a, va, b, vb):
    x, y = stat_fields(a, va), stat_fields(b, vb)
    if x is None or y is None:
        return False
    for name in set(x) | set(y):
        if name in x and name in y:
            if x[name] != y[name]:
                return False
        elif name == "applied_loads" and (x.get(name) or y.get(name)) != bytes(1):
            return False
    return True


magic_a, version_a, a = sections(sys.argv[1])
magic_b, version_b, b = sections(sys.argv[2])
if version_a == version_b:
    differ = [t for t in sorted(set(a) | set(b)) if a.get(t) != b.get(t)]
else:
    differ = [t for t in sorted(set(a) | set(b)) if t not in ("INFO", "BODY", "STAT") and a.get(t) != b.get(t)]
    if not same_bodies(a["BODY"], version_a, b["BODY"], version_b):
        differ.append("BODY")
    if not same_stat(a["STAT"], version_a, b["STAT"], version_b):
        differ.append("STAT")
if magic_a != magic_b or differ:
    print(f"{sys.argv[1]} and {sys.argv[2]} differ in: {', '.join(differ) or 'magic'}")
    sys.exit(1)
