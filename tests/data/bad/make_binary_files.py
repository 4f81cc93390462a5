#!/usr/bin/env python3
"""Writes the binary mesh files of tests/data/bad and tests/data/good (committed as files).

The text files next to them are written by hand; the binary ones are easier to get right
from a script. Run from anywhere: python3 tests/data/bad/make_binary_files.py
Every file describes (part of) the cube [-0.5, 1.25]^3 given as six outward quads, the
same cube as tests/data/good/cube_quads.obj.
"""
import pathlib
import struct

BAD = pathlib.Path(__file__).resolve().parent
GOOD = BAD.parent / "good"

CUBE_VERTICES = [(-0.5, -0.5, -0.5), (1.25, -0.5, -0.5), (1.25, 1.25, -0.5), (-0.5, 1.25, -0.5),
                 (-0.5, -0.5, 1.25), (1.25, -0.5, 1.25), (1.25, 1.25, 1.25), (-0.5, 1.25, 1.25)]
CUBE_QUADS = [(0, 3, 2, 1), (4, 5, 6, 7), (0, 1, 5, 4), (2, 3, 7, 6), (0, 4, 7, 3), (1, 2, 6, 5)]


def fan(polygon):
    """(v0, v1, v2), (v0, v2, v3), ...: the triangulation read_soup applies."""
    return [(polygon[0], polygon[i], polygon[i + 1]) for i in range(1, len(polygon) - 1)]


def cube_triangles():
    return [t for quad in CUBE_QUADS for t in fan(quad)]


def corner_normal(v):
    """A unit-length outward normal at a cube corner (for the normals PLY)."""
    centre = 0.375
    d = [c - centre for c in v]
    n = sum(c * c for c in d) ** 0.5
    return tuple(c / n for c in d)


# ----------------------------------------------------------------------------------- PLY

def ply_header(fmt, vertex_count, face_count, vertex_props, face_list="list uchar int vertex_indices"):
    lines = ["ply", "format %s 1.0" % fmt, "element vertex %d" % vertex_count]
    lines += ["property %s" % p for p in vertex_props]
    lines += ["element face %d" % face_count, "property %s" % face_list, "end_header"]
    return ("\n".join(lines) + "\n").encode("ascii")


def ply(fmt="binary_little_endian", vertices=CUBE_VERTICES, faces=CUBE_QUADS, coord="float", normals=False,
        count_type="B", index_type="i", face_list="list uchar int vertex_indices", face_count=None):
    """A binary PLY; struct codes: B uchar, b char, I uint, i int; coord float or double."""
    order = "<" if fmt == "binary_little_endian" else ">"
    props = ["%s %s" % (coord, axis) for axis in "xyz"]
    if normals:
        props += ["float nx", "float ny", "float nz"]
    body = b""
    c = "f" if coord == "float" else "d"
    for v in vertices:
        body += struct.pack(order + c * 3, *v)
        if normals:
            body += struct.pack(order + "fff", *corner_normal(v))
    for f in faces:
        body += struct.pack(order + count_type, len(f)) + struct.pack(order + index_type * len(f), *f)
    header = ply_header(fmt, len(vertices), len(faces) if face_count is None else face_count, props, face_list)
    return header + body


# ----------------------------------------------------------------------------------- STL

def binary_stl(triangles_xyz, declared=None, header=b"binary STL written by make_binary_files.py"):
    data = header.ljust(80, b" ")
    data += struct.pack("<I", len(triangles_xyz) if declared is None else declared)
    for t in triangles_xyz:
        data += struct.pack("<3f", 0.0, 0.0, 0.0)
        for v in t:
            data += struct.pack("<3f", *v)
        data += b"\0\0"
    return data


def cube_stl_triangles():
    return [[CUBE_VERTICES[k] for k in t] for t in cube_triangles()]


def write(directory, name, data):
    (directory / name).write_bytes(data)


def main():
    # Good: the cube in each binary encoding.
    write(GOOD, "cube_quads_binary_le.ply", ply(normals=True))
    write(GOOD, "cube_quads_binary_be.ply",
          ply(fmt="binary_big_endian", coord="double", index_type="I",
              face_list="list uchar uint vertex_indices"))
    write(GOOD, "cube_binary.stl", binary_stl(cube_stl_triangles()))
    write(GOOD, "cube_binary_solid_header.stl",
          binary_stl(cube_stl_triangles(), header=b"solid cube, but binary: the header says 'solid' anyway"))

    # Bad PLY.
    write(BAD, "garbage.ply", bytes((i * 37 + 11) % 256 for i in range(300)))
    whole = ply()
    write(BAD, "ply_binary_truncated.ply", whole[:len(whole) - 30])
    write(BAD, "ply_binary_trailing_bytes.ply", whole + b"\0\0\0\0")
    nan_vertices = list(CUBE_VERTICES)
    nan_vertices[3] = (-0.5, float("nan"), -0.5)
    write(BAD, "ply_binary_nan_vertex.ply", ply(vertices=nan_vertices))
    write(BAD, "ply_binary_index_out_of_range.ply", ply(faces=CUBE_QUADS[:2] + [(0, 1, 9, 4)] + CUBE_QUADS[3:]))
    write(BAD, "ply_binary_big_endian_negative_index.ply",
          ply(fmt="binary_big_endian", faces=[(0, 3, 2, 1), (4, 5, -1, 7)] + CUBE_QUADS[2:]))
    negative = ply(count_type="b", face_list="list char int vertex_indices")
    first_face = len(ply_header("binary_little_endian", 8, 6, ["float x", "float y", "float z"],
                                "list char int vertex_indices")) + 8 * 12
    negative = negative[:first_face] + struct.pack("<b", -3) + negative[first_face + 1:]
    write(BAD, "ply_binary_negative_list_length.ply", negative)
    # A list length of 4294967280: CGAL would size a 16 GiB buffer before reading it.
    huge = ply(count_type="I", face_list="list uint int vertex_indices")
    huge = huge[:first_face] + struct.pack("<I", 0xFFFFFFF0) + huge[first_face + 4:]
    write(BAD, "ply_binary_huge_list.ply", huge)

    # Binary bytes under a text extension, and garbage as STL.
    write(BAD, "obj_garbage.obj", b"v 0 0 0\n" + bytes(range(0, 64)) + b"\nf 1 1 1\n")
    write(BAD, "off_garbage.off", b"OFF\n3 1 0\n0 0 0\n\x7fELF\x02\x01\x01\0\0\0\n")
    write(BAD, "garbage.stl", bytes((i * 101 + 7) % 256 for i in range(200)))

    # Bad STL.
    triangles = cube_stl_triangles()
    write(BAD, "stl_binary_size_mismatch.stl", binary_stl(triangles[:2], declared=3))
    write(BAD, "stl_binary_too_short.stl", b"\x01\x02\x03 not an STL at all " + bytes(20))
    nan_triangles = [list(t) for t in triangles[:3]]
    nan_triangles[1][2] = (1.25, 1.25, float("nan"))
    write(BAD, "stl_binary_nan_vertex.stl", binary_stl(nan_triangles))
    inf_triangles = [list(t) for t in triangles[:3]]
    inf_triangles[2][0] = (float("inf"), 1.25, -0.5)
    write(BAD, "stl_binary_inf_vertex.stl", binary_stl(inf_triangles))
    write(BAD, "stl_binary_no_triangles.stl", binary_stl([]))
    write(BAD, "stl_solid_with_binary_bytes.stl",
          binary_stl(triangles[:2], declared=5, header=b"solid exported by a tool that writes 'solid' in binary"))


if __name__ == "__main__":
    main()
