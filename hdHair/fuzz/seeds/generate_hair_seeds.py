#!/usr/bin/python3
"""Writes the .tfx and .hair fuzzing seeds: small valid files in each layout
the importers read (hdHair/assets/TressFxReader.h, YukselHairReader.h).

    /usr/bin/python3 hdHair/fuzz/seeds/generate_hair_seeds.py
"""
import os
import struct

HERE = os.path.dirname(os.path.abspath(__file__))


def hair(arrays, segments, default_segments=4):
    """Cem Yuksel .hair: 128-byte header, then the arrays the bit field names."""
    n = sum(s + 1 for s in segments) if arrays & 1 else len(segments) * (default_segments + 1)
    b = b"HAIR" + struct.pack("<IIII", len(segments), n, arrays, default_segments)
    b += struct.pack("<ff3f", 0.5, 0.25, 0.1, 0.2, 0.3) + b"fuzz seed".ljust(88, b"\0")
    if arrays & 1:
        b += b"".join(struct.pack("<H", s) for s in segments)
    if arrays & 2:
        b += b"".join(struct.pack("<3f", i, 2 * i, -0.5 * i) for i in range(n))
    if arrays & 4:
        b += b"".join(struct.pack("<f", 0.1 + 0.01 * i) for i in range(n))
    if arrays & 8:
        b += b"".join(struct.pack("<f", 0.05 * i) for i in range(n))
    if arrays & 16:
        b += b"".join(struct.pack("<3f", 0.1 * i, 0.5, 1 - 0.1 * i) for i in range(n))
    return b


def tfx40(strands, vertices):
    """TressFX 4.0: a 160-byte header of counts and byte offsets, float4 positions, strand thickness."""
    positions = 160
    thickness = positions + strands * vertices * 16
    header = struct.pack("<fII", 4.0, strands, vertices) + struct.pack("<5I", positions, 0, 0, thickness, 0)
    body = b"".join(struct.pack("<4f", s, v * 0.5, 0.25, 1.0) for s in range(strands) for v in range(vertices))
    return header.ljust(160, b"\0") + body + b"".join(struct.pack("<f", 1.0) for _ in range(strands))


def tfx30(strands, vertices):
    """TressFX 3.0: counts, then word 36 holds the byte offset of float3 positions."""
    header = bytearray(struct.pack("<fII", 3.0, strands, vertices).ljust(37 * 4, b"\0"))
    struct.pack_into("<I", header, 36 * 4, 37 * 4)
    body = b"".join(struct.pack("<3f", s, v * 0.5, 0.25) for s in range(strands) for v in range(vertices))
    return bytes(header) + body


def write(relative, data):
    with open(os.path.join(HERE, relative), "wb") as f:
        f.write(data)


write("hair/every-array.hair", hair(0x1F, [2, 1]))
write("hair/header-defaults.hair", hair(0x2, [0, 0, 0], 3))
write("tfx/four-strands-4.0.tfx", tfx40(2, 3))
write("tfx/two-strands-3.0.tfx", tfx30(2, 3))
