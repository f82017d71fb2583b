#!/usr/bin/env python3
"""Writes the mesh I/O test files of tests/test_mesh_io.cpp: the same small
pyramid in every supported form (good/) and the binary or random-byte
malformed inputs (bad/). The output is committed; rerun only to change it.
Deterministic: the random bytes come from a fixed seed."""
import os
import random
import struct

HERE = os.path.dirname(os.path.abspath(__file__))
GOOD = os.path.join(HERE, "good")
BAD = os.path.join(HERE, "bad")

# A square pyramid, outward normals: one quad (the base) and four triangles.
# Coordinates are exact in float32, so every format reads identically.
POSITIONS = [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0), (0.5, 0.5, 1)]
FACES = [(0, 3, 2, 1), (0, 1, 4), (1, 2, 4), (2, 3, 4), (3, 0, 4)]


def write(folder, name, data):
    os.makedirs(folder, exist_ok=True)
    with open(os.path.join(folder, name), "wb") as f:
        f.write(data if isinstance(data, bytes) else data.encode())


def ply_header(fmt, vertex_props, face_props, extra=""):
    lines = ["ply", "format %s 1.0" % fmt, "comment mesh I/O test file",
             "element vertex %d" % len(POSITIONS)]
    lines += ["property %s" % p for p in vertex_props]
    lines += ["element face %d" % len(FACES)]
    lines += ["property %s" % p for p in face_props]
    lines += [extra] if extra else []
    return ("\n".join(lines) + "\nend_header\n").encode()


def good_files():
    obj = ["# pyramid: v/vt/vn corners, groups and materials are skipped",
           "mtllib pyramid.mtl", "o pyramid"]
    obj += ["v %g %g %g" % p for p in POSITIONS]
    obj += ["vt 0 0", "vt 1 0", "vt 1 1", "vn 0 0 1", "g base", "usemtl stone", "s off"]
    obj.append("f 1/1/1 4/2/1 3/3/1 2/1/1  # the base")
    obj += ["g sides", "s 1", "f 1//1 2//1 5//1", "f 2/1 3/2 5/3", "f 3 4 5", "f 4/1/1 1/2/1 5/3/1"]
    write(GOOD, "pyramid.obj", "\n".join(obj) + "\n")

    # Negative (relative) indices, each face right after its vertices.
    rel = ["v %g %g %g" % p for p in POSITIONS[:4]]
    rel.append("f -4 -1 -2 -3")
    rel.append("v %g %g %g" % POSITIONS[4])
    rel += ["f -5 -4 -1", "f -4 -3 -1", "f -3 -2 -1", "f -2 -5 -1"]
    write(GOOD, "pyramid_relative.obj", "\n".join(rel) + "\n")

    # Old Mac line ends (CR only), a line continuation and no final newline.
    cr = ["v %g %g %g" % p for p in POSITIONS]
    cr += ["f 1 4 \\", "3 2", "f 1 2 5", "f 2 3 5", "f 3 4 5", "f 4 1 5"]
    write(GOOD, "pyramid_cr.obj", "\r".join(cr))

    off = ["OFF", "# comment before the counts", "5 5 8  # vertices faces edges"]
    off += ["%g %g %g" % p for p in POSITIONS]
    off += ["%d %s  0.5 0.5 0.5 # with a face colour" % (len(f), " ".join(map(str, f)))
            for f in FACES]
    write(GOOD, "pyramid.off", "\n".join(off) + "\n")

    # ASCII PLY: float coordinates, an extra vertex property, an extra list and
    # element to skip, CRLF line ends.
    head = ply_header("ascii", ["float x", "float y", "float z", "uchar quality"],
                      ["list uchar int vertex_indices", "list uchar float texcoord"],
                      "element edge 2\nproperty int vertex1\nproperty int vertex2")
    rows = ["%g %g %g %d" % (p + (i,)) for i, p in enumerate(POSITIONS)]
    rows += ["%d %s 2 0.25 0.75" % (len(f), " ".join(map(str, f))) for f in FACES]
    rows += ["0 1", "1 2"]
    write(GOOD, "pyramid_ascii.ply", (head.decode() + "\n".join(rows) + "\n").replace("\n", "\r\n"))

    # Binary little endian: double coordinates and an "edge" element.
    head = ply_header("binary_little_endian", ["double x", "double y", "double z"],
                      ["list uchar int vertex_indices"],
                      "element edge 2\nproperty list uchar int vertices\nproperty uchar flag")
    body = b"".join(struct.pack("<3d", *p) for p in POSITIONS)
    body += b"".join(struct.pack("<B%di" % len(f), len(f), *f) for f in FACES)
    body += struct.pack("<B2iB", 2, 0, 1, 7) + struct.pack("<B2iB", 2, 1, 2, 7)
    write(GOOD, "pyramid_binary_le.ply", head + body)

    # Binary big endian: short label before the coordinates, float
    # coordinates, uint counts with ushort indices, a face scalar after.
    head = ply_header("binary_big_endian", ["short id", "float x", "float y", "float z"],
                      ["list uint ushort vertex_index", "double area"])
    body = b"".join(struct.pack(">h3f", i, *p) for i, p in enumerate(POSITIONS))
    body += b"".join(struct.pack(">I%dHd" % len(f), len(f), *f, 0.5) for f in FACES)
    write(GOOD, "pyramid_binary_be.ply", head + body)

    cube = ["# a cube of six quads"]
    cube += ["v %d %d %d" % (x, y, z) for z in (0, 1) for y in (0, 1) for x in (0, 1)]
    cube += ["f 1 3 4 2", "f 5 6 8 7", "f 1 2 6 5", "f 2 4 8 6", "f 4 3 7 8", "f 3 1 5 7"]
    write(GOOD, "cube_quads.obj", "\n".join(cube) + "\n")


def bad_files():
    rng = random.Random(20240515)
    header = ply_header("binary_little_endian", ["float x", "float y", "float z"],
                        ["list uchar int vertex_indices"])
    body = b"".join(struct.pack("<3f", *p) for p in POSITIONS)
    faces = b"".join(struct.pack("<B%di" % len(f), len(f), *f) for f in FACES)
    # Cut inside face 2 (faces 0 and 1 take 17 and 13 bytes).
    write(BAD, "truncated_binary.ply", header + body + faces[:17 + 13 + 6])

    def custom(fmt, vertex_count, vertex_props, face_count, face_props, body_bytes):
        text = ["ply", "format %s 1.0" % fmt, "element vertex %d" % vertex_count]
        text += ["property %s" % p for p in vertex_props]
        text += ["element face %d" % face_count]
        text += ["property %s" % p for p in face_props]
        return ("\n".join(text) + "\nend_header\n").encode() + body_bytes

    xyz = ["float x", "float y", "float z"]
    tri = ["list uchar int vertex_indices"]
    write(BAD, "huge_vertex_count.ply",
          custom("binary_little_endian", 10 ** 12, xyz, 1, tri, body))
    write(BAD, "huge_count_little_data.ply",
          custom("binary_little_endian", 2000000000, xyz, 1, tri, body))
    write(BAD, "huge_list_count.ply",
          custom("binary_little_endian", 5, xyz, 1, ["list uint int vertex_indices"],
                 body + struct.pack("<I3i", 4000000000, 0, 1, 2)))
    write(BAD, "negative_index_binary_be.ply",
          custom("binary_big_endian", 5, xyz, 1, tri,
                 b"".join(struct.pack(">3f", *p) for p in POSITIONS) + struct.pack(">B3i", 3, 0, -1, 2)))
    # Three triangles on the edge (0, 1), binary: no lines to point at.
    pts = [(0, 0, 0), (1, 0, 0), (0, 1, 0), (0, -1, 0), (0, 0, 1)]
    tris = [(0, 1, 2), (1, 0, 3), (0, 1, 4)]
    write(BAD, "nonmanifold_edge_binary.ply",
          custom("binary_little_endian", 5, xyz, 3, tri,
                 b"".join(struct.pack("<3f", *p) for p in pts) +
                 b"".join(struct.pack("<B3i", 3, *t) for t in tris)))
    # A valid header followed by random bytes.
    write(BAD, "random_binary_data.ply",
          custom("binary_little_endian", 100, xyz, 100, tri,
                 bytes(rng.getrandbits(8) for _ in range(3000))))
    for name in ("garbage.obj", "garbage.off", "garbage.ply"):
        write(BAD, name, bytes(rng.getrandbits(8) for _ in range(2048)))


if __name__ == "__main__":
    good_files()
    bad_files()
