#!/usr/bin/env python3
"""Writes the fuzzers' seed corpora: OUT/srm_decode/ and OUT/mesh_read/.

Each seed starts with the option bytes its fuzzer reads (see the comments at
the top of srm_decode_fuzzer.cpp and mesh_read_fuzzer.cpp), then a valid file:
the golden .srm files and the version-3 sample (creases) for the decoder; for
the reader a piece of data/spot.obj (the whole file is 330 KB, too big to
mutate quickly), the golden level-0 OBJ and tiny OFF, PLY and STL files made
here. Every seed is well under 200 KB.

usage: make_seeds.py SOURCE_DIR OUT_DIR
"""
import os
import struct
import sys

OBJ, OFF, PLY, STL = 0, 1, 2, 3  # mesh_read_fuzzer's first byte

# A unit square pyramid: 5 vertices, 4 triangles and a quad base.
PYRAMID_V = [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0), (0.5, 0.5, 1)]
PYRAMID_TRI = [(0, 1, 4), (1, 2, 4), (2, 3, 4), (3, 0, 4)]
PYRAMID_QUAD = (3, 2, 1, 0)


def write(path, data):
    assert len(data) < 200 * 1024, path
    with open(path, "wb") as f:
        f.write(data)


def spot_piece(source, max_faces=400):
    """spot.obj's first faces with the vertices and texture coordinates they
    use (renumbered): keeps its `f v/vt` syntax in a small file."""
    v, vt, faces = [], [], []
    with open(os.path.join(source, "data", "spot.obj")) as f:
        for line in f:
            if line.startswith("v "):
                v.append(line)
            elif line.startswith("vt "):
                vt.append(line)
            elif line.startswith("f ") and len(faces) < max_faces:
                faces.append([[int(i) for i in c.split("/")] for c in line.split()[1:]])
    used_v, used_vt = {}, {}
    for corners in faces:
        for c in corners:
            used_v.setdefault(c[0], len(used_v) + 1)
            used_vt.setdefault(c[1], len(used_vt) + 1)
    out = [v[i - 1] for i in used_v] + [vt[i - 1] for i in used_vt]  # dicts keep insertion order
    out += ["f %s\n" % " ".join("%d/%d" % (used_v[c[0]], used_vt[c[1]]) for c in corners) for corners in faces]
    return "".join(out).encode()


def obj_polygons():
    lines = ["# pyramid with a quad base, a normal and negative indices\n", "vn 0 0 1\n"]
    lines += ["v %g %g %g\n" % p for p in PYRAMID_V]
    lines += ["f %d//1 %d//1 %d//1\n" % tuple(i + 1 for i in t) for t in PYRAMID_TRI[:2]]
    lines += ["f %d %d %d\n" % tuple(i - 5 for i in t) for t in PYRAMID_TRI[2:]]
    lines += ["f %d %d %d %d\n" % tuple(i + 1 for i in PYRAMID_QUAD)]
    return "".join(lines).encode()


def off_text():
    lines = ["OFF\n# pyramid\n%d %d 0\n" % (len(PYRAMID_V), len(PYRAMID_TRI) + 1)]
    lines += ["%g %g %g\n" % p for p in PYRAMID_V]
    lines += ["3 %d %d %d\n" % t for t in PYRAMID_TRI]
    lines += ["4 %d %d %d %d\n" % PYRAMID_QUAD]
    return "".join(lines).encode()


def coff_text():
    lines = ["COFF\n%d %d 0\n" % (len(PYRAMID_V), len(PYRAMID_TRI))]
    lines += ["%g %g %g 255 0 0 255\n" % p for p in PYRAMID_V]
    lines += ["3 %d %d %d\n" % t for t in PYRAMID_TRI]
    return "".join(lines).encode()


def ply_header(fmt, face_element):
    return ("ply\nformat %s 1.0\ncomment pyramid\nelement vertex %d\n"
            "property float x\nproperty float y\nproperty float z\n%s"
            "end_header\n" % (fmt, len(PYRAMID_V), face_element)).encode()


def ply_ascii():
    body = "".join("%g %g %g\n" % p for p in PYRAMID_V)
    body += "".join("3 %d %d %d\n" % t for t in PYRAMID_TRI)
    body += "4 %d %d %d %d\n" % PYRAMID_QUAD
    faces = "element face %d\nproperty list uchar int vertex_indices\n" % (len(PYRAMID_TRI) + 1)
    return ply_header("ascii", faces) + body.encode()


def ply_binary(endian):
    fmt = "binary_little_endian" if endian == "<" else "binary_big_endian"
    faces = "element face %d\nproperty list uchar int vertex_indices\n" % len(PYRAMID_TRI)
    body = b"".join(struct.pack(endian + "3f", *p) for p in PYRAMID_V)
    body += b"".join(struct.pack(endian + "B3i", 3, *t) for t in PYRAMID_TRI)
    return ply_header(fmt, faces) + body


def ply_tristrips():
    strip = [0, 1, 4, 2, -1, 2, 4, 3, 0]  # -1 restarts the strip
    faces = "element tristrips 1\nproperty list int int vertex_indices\n"
    body = b"".join(struct.pack("<3f", *p) for p in PYRAMID_V)
    body += struct.pack("<i", len(strip)) + b"".join(struct.pack("<i", i) for i in strip)
    return ply_header("binary_little_endian", faces) + body


def stl_ascii():
    lines = ["solid pyramid\n"]
    for t in PYRAMID_TRI:
        lines.append("  facet normal 0 0 0\n    outer loop\n")
        lines += ["      vertex %g %g %g\n" % PYRAMID_V[i] for i in t]
        lines.append("    endloop\n  endfacet\n")
    lines.append("endsolid pyramid\n")
    return "".join(lines).encode()


def stl_binary():
    data = b"binary pyramid".ljust(80, b" ") + struct.pack("<I", len(PYRAMID_TRI))
    for t in PYRAMID_TRI:
        data += struct.pack("<3f", 0, 0, 0)
        data += b"".join(struct.pack("<3f", *PYRAMID_V[i]) for i in t)
        data += struct.pack("<H", 0)
    return data


def varint(data, pos):
    value, shift = 0, 0
    while True:
        byte = data[pos]
        value |= (byte & 0x7F) << shift
        pos, shift = pos + 1, shift + 7
        if not byte & 0x80:
            return value, pos


def crease_chunk(srm):
    """(offset, length) of a version-3 file's crease chunk: the header's
    fields up to the crease entry (format/srm/README.md), skipped."""
    assert srm[4] == 3
    body = struct.unpack_from("<I", srm, 6)[0]
    pos = 10
    for _ in range(2):
        pos = varint(srm, pos)[1]  # input vertices, triangles
    levels = srm[pos + 24]
    pos += 24 + 2 + 4  # bounding box, levels, base bits, grid step
    for _ in range(2 + levels + 1):
        pos = varint(srm, pos)[1]  # base vertices, triangles, level vertices
    pos += 4 + 4 + 1 + 1  # quantizer step, tangential factor, top plane + 1, raw planes
    base, pos = varint(srm, pos)
    creases, pos = varint(srm, pos + 4)
    return 10 + body + 4 + base, creases


def main():
    source, out = sys.argv[1], sys.argv[2]
    srm_dir = os.path.join(out, "srm_decode")
    mesh_dir = os.path.join(out, "mesh_read")
    os.makedirs(srm_dir, exist_ok=True)
    os.makedirs(mesh_dir, exist_ok=True)

    # The golden files of versions 1 and 2 (raw planes), and a file of version
    # 3 (creases).
    for name in ("golden_v1", "golden_v2", "creases_v3"):
        with open(os.path.join(source, "tests", "data", name + ".srm"), "rb") as f:
            golden = f.read()
        # (level byte, prefix byte): whole file at the finest level; level 0, then
        # inspect and truncate; level 2 from the first half, cut and by max_bytes.
        for seed, level, prefix in [("whole", 0, 0), ("level0_inspect_truncate", 0x80 | 1, 0),
                                    ("level2_half_cut", 3, 64), ("level2_half_max_bytes", 3, 0x80 | 64)]:
            write(os.path.join(srm_dir, name + "_" + seed), bytes([level, prefix]) + golden)
    # Version 3 cut inside its crease chunk, with inspect and truncate.
    with open(os.path.join(source, "tests", "data", "creases_v3.srm"), "rb") as f:
        v3 = f.read()
    write(os.path.join(srm_dir, "creases_v3_cut_in_creases"), bytes([0x80, 0]) + v3[:crease_chunk(v3)[0] + 1])

    with open(os.path.join(source, "tests", "data", "golden_v1_l0.obj"), "rb") as f:
        golden_obj = f.read()
    seeds = {
        "spot_piece.obj": (OBJ, spot_piece(source)),
        "golden_v1_l0.obj": (OBJ, golden_obj),
        "pyramid.obj": (OBJ, obj_polygons()),
        "pyramid.off": (OFF, off_text()),
        "pyramid_color.off": (OFF, coff_text()),
        "pyramid_ascii.ply": (PLY, ply_ascii()),
        "pyramid_le.ply": (PLY, ply_binary("<")),
        "pyramid_be.ply": (PLY, ply_binary(">")),
        "pyramid_tristrips.ply": (PLY, ply_tristrips()),
        "pyramid_ascii.stl": (STL, stl_ascii()),
        "pyramid_binary.stl": (STL, stl_binary()),
    }
    for name, (fmt, data) in seeds.items():
        write(os.path.join(mesh_dir, name), bytes([fmt]) + data)


if __name__ == "__main__":
    main()
