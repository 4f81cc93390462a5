#!/usr/bin/env python3
"""Writes the seed corpora of the fuzz harnesses: fuzz/corpus/<harness>/ (committed as files).

Seeds are small valid files of every variant each reader accepts, the project's own test
files (tests/data/good and tests/data/bad for soups, data/scenes and tests/data/scenes for
scenes), and a few tricky inputs near the edges of each grammar. libFuzzer mutates them, so
a seed only has to reach a part of the reader, not to be valid. Inputs that once crashed a
harness are kept in the same folders under the name crash-<what>, written by hand, not here.
Run from anywhere: python3 fuzz/make_seed_corpus.py
"""
import pathlib
import shutil
import struct

ROOT = pathlib.Path(__file__).resolve().parent.parent
CORPUS = ROOT / "fuzz" / "corpus"
GOOD = ROOT / "tests" / "data" / "good"
BAD = ROOT / "tests" / "data" / "bad"

TRI_V = [(0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0)]
TETRA = [(0, 2, 1), (0, 1, 3), (0, 3, 2), (1, 2, 3)]


def write(harness, name, data):
    folder = CORPUS / harness
    folder.mkdir(parents=True, exist_ok=True)
    (folder / name).write_bytes(data.encode("ascii") if isinstance(data, str) else data)


def copy_matching(harness, folders, suffix):
    (CORPUS / harness).mkdir(parents=True, exist_ok=True)
    for folder in folders:
        for path in sorted(folder.glob("*" + suffix)):
            shutil.copyfile(path, CORPUS / harness / (folder.name + "_" + path.name))


# ------------------------------------------------------------------------------- OBJ

def obj_seeds():
    h = "soup_file_obj"
    write(h, "triangle.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n")
    write(h, "no_final_newline.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3")
    write(h, "crlf.obj", "v 0 0 0\r\nv 1 0 0\r\nv 0 1 0\r\nf 1 2 3\r\n")
    write(h, "numbers.obj", "v +1e-3 -2.5E+2 .5\nv 1. 0x1p3 -0\nv 1e-320 7 8\nf 1 2 3\n")
    write(h, "relative_and_slashes.obj",
          "# tetrahedron\no tet\ng a b\ns 1\nusemtl m\nvt 0 0\nvn 0 0 1\n"
          "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\n"
          "f 1/1/1 3/1/1 2/1/1\nf -4//1 -3//1 -1//1\nf 1/1 4/1 3/1 # comment\nf 2 3 4\n")
    write(h, "pentagon.obj", "v 0 0 0\nv 2 0 0\nv 3 1 0\nv 1 2 0\nv -1 1 0\nf 1 2 3 4 5\n")
    write(h, "vertex_after_face.obj", "v 0 0 0\nv 1 0 0\nf 1 2 3\nv 0 1 0\n")
    write(h, "weights.obj", "v 0 0 0 1\nv 1 0 0 1\nv 0 1 0 1\nvp 0.5\nf 1 2 3\n")
    copy_matching(h, [GOOD, BAD], ".obj")


# ------------------------------------------------------------------------------- OFF

def off_seeds():
    h = "soup_file_off"
    write(h, "triangle.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n")
    write(h, "counts_on_header_line.off", "OFF 3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n")
    write(h, "comments_blank_lines.off", "OFF\n# c\n\n4 4 6\n0 0 0\n1 0 0 # x\n0 1 0\n0 0 1\n\n"
          "3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n")
    write(h, "coff_colors.off", "COFF\n3 1 0\n0 0 0 255 0 0 255\n1 0 0 0 255 0 255\n0 1 0 0 0 255 255\n"
          "3 0 1 2 0.5 0.5 0.5\n")
    write(h, "noff_normals.off", "NOFF\n3 1 0\n0 0 0 0 0 1\n1 0 0 0 0 1\n0 1 0 0 0 1\n3 0 1 2\n")
    write(h, "homogeneous.off", "4OFF\n3 1 0\n0 0 0 1\n2 0 0 2\n0 1 0 1\n3 0 1 2\n")
    write(h, "stcoff_indexed_colors.off", "STCOFF\n3 1 0\n0 0 0 7 0 0\n1 0 0 8 1 0\n0 1 0 9 0 1\n3 0 1 2 148\n")
    write(h, "cnoff_alpha.off", "CNOFF\n3 1 0\n0 0 0 0 0 1 1 0 0 0.5\n1 0 0 0 0 1 0 1 0 1\n0 1 0 0 0 1 0 0 1 0\n"
          "3 0 1 2 255 255 255 255\n")
    write(h, "crlf.off", "OFF\r\n3 1 0\r\n0 0 0\r\n1 0 0\r\n0 1 0\r\n3 0 1 2\r\n")
    copy_matching(h, [GOOD, BAD], ".off")


# ------------------------------------------------------------------------------- PLY

def ply_header(fmt, nv, nf, vertex_props, face_list="list uchar int vertex_indices", extra=""):
    lines = ["ply", "format %s 1.0" % fmt, "comment seed", "element vertex %d" % nv]
    lines += ["property %s" % p for p in vertex_props]
    lines += ["element face %d" % nf, "property %s" % face_list]
    if extra:
        lines += extra.splitlines()
    lines += ["end_header"]
    return ("\n".join(lines) + "\n").encode("ascii")


def ply_binary(order, coord="float", normals=False, count="B", index="i", list_types="uchar int"):
    fmt = "binary_little_endian" if order == "<" else "binary_big_endian"
    props = ["%s %s" % (coord, a) for a in "xyz"] + (["float nx", "float ny", "float nz"] if normals else [])
    data = ply_header(fmt, len(TRI_V), len(TETRA), props, "list %s vertex_indices" % list_types)
    c = "f" if coord == "float" else "d"
    for v in TRI_V:
        data += struct.pack(order + c * 3, *v)
        if normals:
            data += struct.pack(order + "fff", 0.0, 0.0, 1.0)
    for f in TETRA:
        data += struct.pack(order + count, 3) + struct.pack(order + index * 3, *f)
    return data


def ply_seeds():
    h = "soup_file_ply"
    body = "".join("%g %g %g\n" % v for v in TRI_V) + "".join("3 %d %d %d\n" % f for f in TETRA)
    write(h, "ascii_float.ply", ply_header("ascii", 4, 4, ["float x", "float y", "float z"]) + body.encode())
    write(h, "ascii_double_uint.ply",
          ply_header("ascii", 4, 4, ["double x", "double y", "double z"], "list uchar uint vertex_indices")
          + body.encode())
    nbody = "".join("%g %g %g 0 0 1\n" % v for v in TRI_V) + "".join("3 %d %d %d\n" % f for f in TETRA)
    write(h, "ascii_normals.ply", ply_header("ascii", 4, 4, ["float x", "float y", "float z", "float nx",
                                                          "float ny", "float nz"]) + nbody.encode())
    cbody = "".join("%g %g %g 255 0 0\n" % v for v in TRI_V) + "".join("3 %d %d %d\n" % f for f in TETRA)
    write(h, "ascii_colors_extra_element.ply",
          ply_header("ascii", 4, 4, ["float x", "float y", "float z", "uchar red", "uchar green", "uchar blue"],
                     extra="element edge 1\nproperty int vertex1\nproperty int vertex2")
          + (cbody + "0 1\n").encode())
    write(h, "ascii_vertex_indices_int_list_count.ply",
          ply_header("ascii", 4, 4, ["float x", "float y", "float z"], "list int int vertex_indices") + body.encode())
    write(h, "binary_le.ply", ply_binary("<"))
    write(h, "binary_be.ply", ply_binary(">"))
    write(h, "binary_le_double_normals.ply", ply_binary("<", coord="double", normals=True))
    write(h, "binary_be_uint_indices.ply", ply_binary(">", index="I", list_types="uchar uint"))
    write(h, "binary_le_ushort_count.ply", ply_binary("<", count="H", list_types="ushort int"))
    copy_matching(h, [GOOD, BAD], ".ply")


# ------------------------------------------------------------------------------- STL

def stl_binary(header=b"seed binary stl"):
    data = header.ljust(80, b" ") + struct.pack("<I", len(TETRA))
    for f in TETRA:
        data += struct.pack("<3f", 0, 0, 0)
        for i in f:
            data += struct.pack("<3f", *TRI_V[i])
        data += struct.pack("<H", 0)
    return data


def stl_ascii(eol="\n", name="tet"):
    lines = ["solid " + name]
    for f in TETRA:
        lines += ["  facet normal 0 0 0", "    outer loop"]
        lines += ["      vertex %g %g %g" % TRI_V[i] for i in f]
        lines += ["    endloop", "  endfacet"]
    lines += ["endsolid " + name]
    return eol.join(lines) + eol


def stl_seeds():
    h = "soup_file_stl"
    write(h, "ascii.stl", stl_ascii())
    write(h, "ascii_crlf.stl", stl_ascii("\r\n"))
    write(h, "ascii_unnamed.stl", stl_ascii(name=""))
    write(h, "binary.stl", stl_binary())
    write(h, "binary_solid_header.stl", stl_binary(b"solid but binary"))
    copy_matching(h, [GOOD, BAD], ".stl")


# --------------------------------------------------------------------- other readers

def vol_seeds():
    h = "captured_volume"
    write(h, "tetrahedron.vol", "# seed\nv 0 0 0 1\nv 1 0 0 1\nv 0 1 0 1\nv 0 0 1 0\n"
          "f 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n")
    write(h, "quad_face_before_vertices.vol", "f 1 2 3 4\n\n# c\nv 0 0 0 1\nv 1 0 0 1\nv 1 1 0 1\nv 0 1 0 0\n")
    write(h, "signed_zeros_duplicates.vol", "v -0 0 0 1\nv 0 -0 0 1\nv 1.00000001 2e-45 3.4028235e38 1\n"
          "v 1 0 0 0\r\nf 1 2 3\t\nf 2 3 4\n")
    write(h, "bad_w.vol", "v 0 0 0 0.5\nf 1 1 1\n")


def point_seeds():
    h = "point_file"
    write(h, "points.txt", "# sample points\n0 0 0\n1.5 -2 3e-3\n\n  4\t5 6\r\n")
    write(h, "no_final_newline.txt", "1 2 3")
    write(h, "bad_word.txt", "1 two 3\n")
    write(h, "four_values.txt", "1 2 3 4\n")


def light_path_seeds():
    h = "light_path_file"
    write(h, "orbit.txt", "# a path\n3 1 0 1\n0 1 3 1\n\n  -3\t1 0 1\r\n0.3 1 0.2 0\n")
    write(h, "no_final_newline.txt", "1 2 3 1")
    write(h, "bad_w.txt", "1 2 3 0.5\n")
    write(h, "zero_direction.txt", "0 0 0 0\n")


def scene_seeds():
    h = "scene_file"
    for folder in [ROOT / "data" / "scenes", ROOT / "data" / "scenes" / "hard", ROOT / "tests" / "data" / "scenes",
                   ROOT / "tests" / "data" / "scenes" / "bad"]:
        copy_matching(h, [folder], ".json")
    write(h, "every_generator.json",
          '{"meshes": [{"generator": "floor"}, {"generator": "box", "params": {"min": [0, 0, 0], "max": [1, 2, 3]}},'
          ' {"generator": "uv_sphere", "params": {"slices": 3, "stacks": 2}},'
          ' {"generator": "icosphere", "params": {"subdivisions": 0}},'
          ' {"generator": "torus", "params": {"major_segments": 3, "minor_segments": 3}},'
          ' {"generator": "sphere_grid", "params": {"triangles": 600}},'
          ' {"generator": "random_soup", "params": {"seed": 7, "triangles": 5, "extent": 2}},'
          ' {"generator": "nonmanifold_fan", "params": {"k": 3}}, {"generator": "open_box_with_fins"}]}')
    write(h, "transforms.json",
          '{"meshes": [{"file": "a.obj", "transform": {"scale": [1, -1, 2], "rotate_deg": [90, 45, 30],'
          ' "translate": [1e300, 0, -1e-300]}}, {"file": "missing.obj"},'
          ' {"name": "m", "generator": "box", "transform": {"matrix": [0, 1, 0, 0, 1, 0, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1]}}],'
          ' "lights": [[0, 1e308, 0, 1], [1, 0, 0, 0]],'
          ' "camera": {"eye": [1, 2, 3], "target": [0, 0, 0], "up": [0, 0, 1], "fov_y_deg": 179.9, "size": [1, 32768]}}')
    write(h, "empty_object.json", "{}")
    write(h, "nested_arrays.json", '{"meshes": [[[[[[]]]]]], "description": "\\u00e9\\ud83d\\ude00"}')


if __name__ == "__main__":
    for seeds in (obj_seeds, off_seeds, ply_seeds, stl_seeds, vol_seeds, point_seeds, light_path_seeds, scene_seeds):
        seeds()
