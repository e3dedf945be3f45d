#!/usr/bin/env python3
"""Exit 0 when two gjkdem checkpoints hold the same run state, byte for byte,
apart from the wall-clock seconds they record (LOGS) and the header's
checksum over them. Usage: same_checkpoint.py A B"""
import struct
import sys

HEADER = 40  # src/io/checkpoint.cpp: kHeaderBytes


def sections(path):
    data = open(path, "rb").read()
    out, at = {}, HEADER
    while at < len(data):
        tag = data[at:at + 4].decode("ascii")
        (length,) = struct.unpack_from("<Q", data, at + 4)
        body = bytearray(data[at + 12:at + 12 + length])
        if tag == "LOGS":
            body[24:32] = bytes(8)  # trace, energy, cell bytes (u64 each), then wall_seconds
        out[tag] = bytes(body)
        at += 12 + length
    return data[:8], out


magic_a, a = sections(sys.argv[1])
magic_b, b = sections(sys.argv[2])
differ = [t for t in sorted(set(a) | set(b)) if a.get(t) != b.get(t)]
if magic_a != magic_b or differ:
    print(f"{sys.argv[1]} and {sys.argv[2]} differ in: {', '.join(differ) or 'magic'}")
    sys.exit(1)
