"""`import shadowcert` (python/, docs/python.md) against the CLI and against counts worked out by hand.

Run by ctest (`python_module`, label python) with PYTHONPATH at the module's build folder and
SHADOWCERT_CLI, SHADOWCERT_SOURCE_DIR and SHADOWCERT_TEST_DATA set (tests/CMakeLists.txt).
"""
import json
import os
import subprocess
from pathlib import Path

import numpy as np
import pytest

import shadowcert

SOURCE = Path(os.environ.get("SHADOWCERT_SOURCE_DIR", Path(__file__).resolve().parents[2]))
TEST_DATA = Path(os.environ.get("SHADOWCERT_TEST_DATA", SOURCE / "tests" / "data"))
CLI = os.environ.get("SHADOWCERT_CLI")

CUBE = TEST_DATA / "good" / "cube_quads.off"
MESHES = [
    CUBE,
    SOURCE / "data" / "meshes" / "edge_cases" / "trimesh_shared.STL",
    SOURCE / "data" / "meshes" / "edge_cases" / "trimesh_multibody.stl",
    SOURCE / "data" / "meshes" / "closed_manifold" / "thingi10k_65004.stl",
]


def cli_certify(mesh, light, tmp_path, *options):
    if not CLI:
        pytest.fail("SHADOWCERT_CLI is not set (ctest sets it to build/cli/shadowcert)")
    out = tmp_path / "certify.json"
    light_text = ",".join(repr(float(x)) for x in light)
    run = subprocess.run([CLI, "certify", str(mesh), "--light", light_text, "--json", str(out), *options],
                         capture_output=True, text=True, timeout=300)
    assert run.returncode == 0, run.stdout + run.stderr
    return json.loads(out.read_text())


def without_timings(value):
    """The report less what differs run to run: seconds and the input's name."""
    if isinstance(value, dict):
        return {k: without_timings(v) for k, v in value.items()
                if k not in ("seconds", "stage_seconds", "input")}
    if isinstance(value, list):
        return [without_timings(v) for v in value]
    return value


def test_read_soup_shapes_and_dtypes():
    vertices, triangles = shadowcert.read_soup(str(CUBE))
    assert vertices.dtype == np.float64 and vertices.ndim == 2 and vertices.shape[1] == 3
    assert triangles.dtype == np.uint32 and triangles.ndim == 2 and triangles.shape[1] == 3
    assert triangles.shape[0] == 12  # six quads, fan-triangulated
    assert triangles.max() < vertices.shape[0]
    assert np.all(np.isfinite(vertices))


def test_read_soup_bad_file_is_value_error(tmp_path):
    with pytest.raises(ValueError, match="missing.off"):
        shadowcert.read_soup(str(tmp_path / "missing.off"))
    bad = tmp_path / "bad.off"
    bad.write_text("OFF\n3 1 0\n0 0 0\n1 0 0\nnan 1 0\n3 0 1 2\n")
    with pytest.raises(ValueError, match="bad.off"):
        shadowcert.read_soup(str(bad))


@pytest.mark.parametrize("mesh", MESHES, ids=lambda p: p.name)
@pytest.mark.parametrize("light", [(1.5, 7.0, 2.5, 1.0), (0.3, 1.0, -0.2, 0.0)], ids=["point", "directional"])
def test_certify_equals_the_cli(mesh, light, tmp_path):
    expected = cli_certify(mesh, light, tmp_path, "--samples", "400", "--seed", "3")
    vertices, triangles = shadowcert.read_soup(str(mesh))
    got = shadowcert.certify(vertices, triangles, light, samples=400, seed=3)
    assert set(got) == set(expected)
    assert set(got["methods"]) == {"exact", "kim", "peciva", "refedge"}
    assert without_timings(got) == without_timings(expected)
    assert got["methods"]["exact"]["closed"] is True
    assert got["methods"]["exact"]["count_failures"] == 0


def test_certify_one_method_double_precision_equals_the_cli(tmp_path):
    light = (1.0, 2.0, 3.0, 0.0)
    expected = cli_certify(CUBE, light, tmp_path, "--method", "refedge", "--precision", "double", "--samples", "100")
    vertices, triangles = shadowcert.read_soup(str(CUBE))
    got = shadowcert.certify(vertices, triangles, light, method="refedge", precision="double", samples=100)
    assert list(got["methods"]) == ["refedge"]
    assert without_timings(got) == without_timings(expected)


def test_certify_accepts_other_integer_and_float_dtypes():
    vertices, triangles = shadowcert.read_soup(str(CUBE))
    a = shadowcert.certify(vertices, triangles, (1, 5, 2, 1), method="exact", samples=50)
    b = shadowcert.certify(vertices.astype(np.float32).astype(np.float64).tolist(),
                           triangles.astype(np.int64), (1, 5, 2, 1), method="exact", samples=50)
    assert without_timings(a) == without_timings(b)


def quad_soup():
    """A floor quad at y = 0 (two triangles, facing up) and one triangle at y = 1 above it."""
    vertices = np.array([[-4, 0, -4], [4, 0, -4], [4, 0, 4], [-4, 0, 4],
                         [-1, 1, -1], [1, 1, -1], [0, 1, 1]], dtype=np.float64)
    triangles = np.array([[0, 2, 1], [0, 3, 2], [4, 6, 5]], dtype=np.uint32)
    return vertices, triangles


def pixel_rays(eye, target, size, fov_y=45.0):
    """core/pixel_ray.h's rays through the pixel centres, (h, w, 3) directions, up = +y."""
    eye, target = np.asarray(eye, float), np.asarray(target, float)
    width, height = size
    forward = (target - eye) / np.linalg.norm(target - eye)
    right = np.cross(forward, [0.0, 1.0, 0.0])
    right /= np.linalg.norm(right)
    up = np.cross(right, forward)
    half_height = np.tan(np.radians(fov_y) / 2)
    half_width = half_height * width / height
    x = np.arange(width) + 0.5
    y = np.arange(height) + 0.5
    a = (2 * x / width - 1) * half_width
    b = (1 - 2 * y / height) * half_height
    return forward + a[None, :, None] * right + b[:, None, None] * up


def inside_xz(points, corners):
    """Strictly inside the triangle `corners` (x, z) with a margin, and strictly outside with a margin."""
    signs = []
    for k in range(3):
        a, b = corners[k], corners[(k + 1) % 3]
        signs.append((b[0] - a[0]) * (points[..., 1] - a[1]) - (b[1] - a[1]) * (points[..., 0] - a[0]))
    signs = np.stack(signs)
    inside = np.all(signs > 1e-3, axis=0) | np.all(signs < -1e-3, axis=0)
    clear = np.all(np.abs(signs) > 1e-3, axis=0)
    return inside, clear


def test_exact_image_counts_match_the_shadow_worked_out_by_hand():
    vertices, triangles = quad_soup()
    light = np.array([[3.0, 4.0, 0.0, 1.0]])  # off to the side: the shadow falls beside the occluder
    eye, target, size = [0.0, 6.0, 8.0], [0.0, 0.0, 0.0], (96, 64)
    image = shadowcert.exact_image(vertices, triangles, light, {"eye": eye, "target": target, "size": list(size)})
    counts, lit, ambiguity, hits = image["counts"], image["lit"], image["ambiguity"], image["hit_triangles"]
    assert counts.shape == (1, 64, 96) and counts.dtype == np.uint32
    assert lit.shape == (1, 64, 96) and lit.dtype == np.uint8
    assert ambiguity.shape == (1, 64, 96) and ambiguity.dtype == np.uint8
    assert hits.shape == (64, 96) and hits.dtype == np.uint32
    # Each centre ray by hand: where it meets the occluder's plane y = 1 and the floor y = 0.
    d = pixel_rays(eye, target, size)
    e = np.asarray(eye)
    on_occluder = e[[0, 2]] + d[..., [0, 2]] * ((1.0 - e[1]) / d[..., 1])[..., None]
    on_floor = e[[0, 2]] + d[..., [0, 2]] * ((0.0 - e[1]) / d[..., 1])[..., None]
    hits_occluder, clear_occluder = inside_xz(on_occluder, vertices[4:7][:, [0, 2]])
    floor_inside = np.all(np.abs(on_floor) < 4 - 1e-3, axis=-1)
    # The floor point's segment to the light (3, 4, 0) crosses y = 1 at 1/4 of the way.
    crossing = light[0, [0, 2]] + (on_floor - light[0, [0, 2]]) * 0.75
    shadowed, clear_shadow = inside_xz(crossing, vertices[4:7][:, [0, 2]])
    decided = (ambiguity[0] == 0) & clear_occluder & clear_shadow
    assert np.all(hits[decided & hits_occluder] == 2)
    floor = decided & ~hits_occluder & floor_inside
    assert np.all(np.isin(hits[floor], [0, 1]))
    assert floor.sum() > 1000 and (floor & shadowed).sum() > 50
    assert np.array_equal(counts[0][floor], shadowed[floor].astype(np.uint32))
    assert np.array_equal(lit[0][floor] == 255, ~shadowed[floor])
    assert np.all(counts[0][decided & hits_occluder] == 0)  # lit from above
    missed = decided & ~hits_occluder & ~np.all(np.abs(on_floor) < 4 + 1e-3, axis=-1)
    missed |= decided & (d[..., 1] >= 0)
    assert np.all(hits[missed] == shadowcert.NO_HIT)
    assert np.all(counts[0][missed] == shadowcert.NO_HIT)


def test_exact_image_several_lights_and_the_same_answer_per_light():
    vertices, triangles = quad_soup()
    lights = np.array([[0.0, 4.0, 0.0, 1.0], [0.2, 1.0, 0.1, 0.0]])
    both = shadowcert.exact_image(vertices, triangles, lights, eye=[0, 6, 8], target=[0, 0, 0], size=(24, 16))
    for k in range(2):
        one = shadowcert.exact_image(vertices, triangles, lights[k], eye=[0, 6, 8], target=[0, 0, 0], size=(24, 16))
        assert np.array_equal(both["counts"][k], one["counts"][0])
        assert np.array_equal(both["ambiguity"][k], one["ambiguity"][0])


BAD_ARRAYS = [
    ("wrong vertex shape", lambda v, t: (v[:, :2], t), "vertices must be an \\(n, 3\\) array"),
    ("wrong triangle shape", lambda v, t: (v, t.reshape(-1)), "triangles must be an \\(m, 3\\) array"),
    ("float triangles", lambda v, t: (v, t.astype(np.float64)), "triangles must be an integer array"),
    ("string vertices", lambda v, t: (v.astype(str), t), "vertices must be a float array"),
    ("NaN", lambda v, t: (np.where(np.arange(v.size).reshape(v.shape) == 4, np.nan, v), t),
     "vertex 1 has a non-finite coordinate"),
    ("inf", lambda v, t: (np.where(np.arange(v.size).reshape(v.shape) == 0, np.inf, v), t),
     "vertex 0 has a non-finite coordinate"),
    ("index out of range", lambda v, t: (v, np.where(t == t.max(), v.shape[0], t)),
     "triangle \\d+ has vertex index 8, but the soup has 8 vertices"),
    ("negative index", lambda v, t: (v, t.astype(np.int64) - 1), "triangle 0 has vertex index -1, but the soup has 8 vertices"),
]


@pytest.mark.parametrize("name,spoil,message", BAD_ARRAYS, ids=[b[0] for b in BAD_ARRAYS])
def test_bad_arrays_raise_value_error(name, spoil, message):
    vertices, triangles = shadowcert.read_soup(str(CUBE))
    v, t = spoil(vertices, triangles)
    with pytest.raises(ValueError, match="certify: " + message):
        shadowcert.certify(v, t, (1, 5, 2, 1))
    with pytest.raises(ValueError, match="exact_image: " + message):
        shadowcert.exact_image(v, t, [1, 5, 2, 1], eye=[3, 4, 5], target=[0, 0, 0], size=(8, 8))


def test_bad_lights_methods_and_cameras_raise_value_error():
    vertices, triangles = shadowcert.read_soup(str(CUBE))
    with pytest.raises(ValueError, match="certify: the light needs finite coordinates and w = 0 or w = 1"):
        shadowcert.certify(vertices, triangles, (1, 2, 3, 0.5))
    with pytest.raises(ValueError, match="certify: a directional light needs a nonzero direction"):
        shadowcert.certify(vertices, triangles, (0, 0, 0, 0))
    with pytest.raises(ValueError, match="certify: a light is four numbers"):
        shadowcert.certify(vertices, triangles, (1, 2, 3))
    with pytest.raises(ValueError, match="unknown method 'magic'"):
        shadowcert.certify(vertices, triangles, (1, 5, 2, 1), method="magic")
    with pytest.raises(ValueError, match="exact_image: lights must be"):
        shadowcert.exact_image(vertices, triangles, [[1, 2, 3]], eye=[3, 4, 5], target=[0, 0, 0], size=(8, 8))
    with pytest.raises(ValueError, match="exact_image"):  # eye == target: a degenerate camera
        shadowcert.exact_image(vertices, triangles, [1, 5, 2, 1], eye=[0, 0, 0], target=[0, 0, 0], size=(8, 8))
    with pytest.raises(ValueError, match="image sides"):
        shadowcert.exact_image(vertices, triangles, [1, 5, 2, 1], eye=[3, 4, 5], target=[0, 0, 0], size=(0, 8))


SCENES = [SOURCE / "data" / "scenes" / "default.json", SOURCE / "data" / "scenes" / "noncasting_floor.json"]


@pytest.mark.parametrize("scene_file", SCENES, ids=lambda p: p.name)
def test_certify_of_a_scene_equals_the_cli(scene_file, tmp_path):
    scene = shadowcert.read_scene(str(scene_file))
    light = scene["lights"][0]
    expected = cli_certify(scene_file, light, tmp_path, "--samples", "400")
    got = shadowcert.certify(scene["caster_vertices"], scene["caster_triangles"], light, samples=400)
    assert without_timings(got) == without_timings(expected)
    assert got["triangles"] == int(scene["casts"].sum())


def test_read_scene_and_receiving_meshes_are_never_counted():
    scene = shadowcert.read_scene(str(SOURCE / "data" / "scenes" / "noncasting_floor.json"))
    vertices, triangles, casts = scene["vertices"], scene["triangles"], scene["casts"]
    assert casts.dtype == np.uint8 and casts.shape == (triangles.shape[0],)
    assert 0 < casts.sum() < casts.size  # the floor and the pane only receive
    assert scene["lights"].shape[1] == 4 and scene["camera"]["size"][0] > 0
    camera = dict(scene["camera"], size=[64, 48])
    receiving = shadowcert.exact_image(vertices, triangles, scene["lights"], camera, casts=casts)
    everything = shadowcert.exact_image(vertices, triangles, scene["lights"], camera)
    assert np.array_equal(receiving["hit_triangles"], everything["hit_triangles"])  # every mesh is seen
    both = (receiving["counts"] < shadowcert.UNDEFINED_COUNT) & (everything["counts"] < shadowcert.UNDEFINED_COUNT)
    assert both.sum() > 1000
    assert np.all(receiving["counts"][both] <= everything["counts"][both])
    assert np.any(receiving["counts"][both] < everything["counts"][both])
    with pytest.raises(ValueError, match="exact_image"):
        shadowcert.exact_image(vertices, triangles, scene["lights"], camera, casts=casts[:-1])


def test_the_walk_through_of_docs_python_md_runs(tmp_path):
    """Every Python example of docs/python.md, as written (from the source folder), with
    matplotlib drawing to a file."""
    import matplotlib
    matplotlib.use("Agg")
    import re
    blocks = re.findall(r"```python\n(.*?)```", (SOURCE / "docs" / "python.md").read_text(), re.S)
    assert len(blocks) >= 2
    cwd = os.getcwd()
    os.chdir(SOURCE)
    try:
        for code in blocks:
            code = code.replace("plt.show()", f"plt.savefig({str(tmp_path / 'walk.png')!r})")
            exec(compile(code, "docs/python.md", "exec"), {})
    finally:
        os.chdir(cwd)
    assert (tmp_path / "walk.png").stat().st_size > 1000


ODD_INPUTS = [
    ("None", None, None, "vertices must be an \\(n, 3\\) array"),
    ("scalars", 1.0, 2, "vertices must be an \\(n, 3\\) array"),
    ("3-d", np.zeros((2, 3, 3)), np.zeros((1, 3), np.uint32), "vertices must be an \\(n, 3\\) array"),
    ("objects", np.array([[object()] * 3]), np.zeros((1, 3), np.uint32), "vertices must be a float array"),
    ("bool triangles", np.zeros((3, 3)), np.zeros((1, 3), bool), "triangles must be an integer array"),
    ("ragged", [[0, 0, 0], [1, 0]], [[0, 1, 2]], None),
]


@pytest.mark.parametrize("name,vertices,triangles,message", ODD_INPUTS, ids=[o[0] for o in ODD_INPUTS])
def test_odd_inputs_raise_value_error_never_crash(name, vertices, triangles, message):
    with pytest.raises(ValueError, match=message):
        shadowcert.certify(vertices, triangles, (1, 5, 2, 1))
    with pytest.raises(ValueError, match=message):
        shadowcert.exact_image(vertices, triangles, [1, 5, 2, 1], eye=[3, 4, 5], target=[0, 0, 0], size=(8, 8))


def test_empty_and_strided_inputs():
    empty_v, empty_t = np.zeros((0, 3)), np.zeros((0, 3), np.uint32)
    with pytest.raises(ValueError, match="certify: no casting triangle to certify"):
        shadowcert.certify(empty_v, empty_t, (1, 5, 2, 1))
    nothing = shadowcert.exact_image(empty_v, empty_t, [1, 5, 2, 1], eye=[3, 4, 5], target=[0, 0, 0], size=(8, 6))
    assert nothing["counts"].shape == (1, 6, 8) and np.all(nothing["counts"] == shadowcert.NO_HIT)
    # Fortran order, a strided view and a wider integer type give the same answers as the plain arrays.
    vertices, triangles = shadowcert.read_soup(str(CUBE))
    plain = shadowcert.certify(vertices, triangles, (1, 5, 2, 1), method="exact", samples=50)
    wide = np.zeros((vertices.shape[0], 6))
    wide[:, ::2] = vertices
    odd = shadowcert.certify(wide[:, ::2], np.asfortranarray(triangles.astype(np.uint64)), (1, 5, 2, 1),
                             method="exact", samples=50)
    assert without_timings(plain) == without_timings(odd)


def test_certify_with_user_points_equals_the_cli(tmp_path):
    points = np.array([[0.3, 0.2, 0.1], [2.0, 3.0, 0.5], [0.375, 0.375, 0.375], [-1.0, 0.5, 4.0]])
    points_file = tmp_path / "points.txt"
    points_file.write_text("".join(f"{x!r} {y!r} {z!r}\n" for x, y, z in points))
    light = (10.0, 0.5, 0.5, 1.0)
    expected = cli_certify(CUBE, light, tmp_path, "--method", "exact", "--samples", "0", "--points", str(points_file))
    vertices, triangles = shadowcert.read_soup(str(CUBE))
    got = shadowcert.certify(vertices, triangles, light, method="exact", samples=0, points=points)
    assert got["user_points"] == 4
    assert without_timings(got) == without_timings(expected)
    with pytest.raises(ValueError, match="certify: point 1 has a non-finite coordinate"):
        shadowcert.certify(vertices, triangles, light, points=[[0, 0, 0], [np.nan, 0, 0]])


def test_threads_get_the_same_images_while_the_gil_is_released():
    from concurrent.futures import ThreadPoolExecutor
    vertices, triangles = quad_soup()
    lights = [[3.0, 4.0, 0.0, 1.0], [0.0, 4.0, 1.0, 1.0], [0.2, 1.0, 0.1, 0.0], [-2.0, 3.0, 2.0, 1.0]]

    def image(light):
        return shadowcert.exact_image(vertices, triangles, light, eye=[0, 6, 8], target=[0, 0, 0], size=(64, 48))

    alone = [image(light) for light in lights]
    with ThreadPoolExecutor(4) as pool:
        together = list(pool.map(image, lights))
    for a, b in zip(alone, together):
        assert np.array_equal(a["counts"], b["counts"]) and np.array_equal(a["ambiguity"], b["ambiguity"])


def test_the_stub_names_every_function_with_its_parameters():
    """python/shadowcert.pyi (installed beside the module) against the module itself."""
    import ast
    import inspect
    stub = ast.parse((SOURCE / "python" / "shadowcert.pyi").read_text())
    stubbed = {f.name: f for f in stub.body if isinstance(f, ast.FunctionDef)}
    public = {name for name, value in vars(shadowcert).items() if callable(value) and not name.startswith("_")}
    assert set(stubbed) == public
    for name, function in stubbed.items():
        doc = getattr(shadowcert, name).__doc__
        stub_parameters = [a.arg for a in function.args.args + function.args.kwonlyargs]
        signature = doc.splitlines()[0]  # pybind11's: name(a: type, b: type = default, *, c: ...) -> ...
        inside, parts, depth, word = signature[signature.index("(") + 1:signature.rindex(")")], [], 0, ""
        for ch in inside:  # split at the commas outside brackets (a default may be a list)
            depth += ch in "([{"
            depth -= ch in ")]}"
            if ch == "," and depth == 0:
                parts.append(word)
                word = ""
            else:
                word += ch
        parts.append(word)
        module_parameters = [p.split(":")[0].strip() for p in parts if p.strip() and p.strip() != "*"]
        assert stub_parameters == module_parameters, name
        assert len(doc.splitlines()) > 3, f"{name} has no docstring of its own"
    installed = Path(shadowcert.__file__).with_name("shadowcert.pyi")
    assert installed.read_text() == (SOURCE / "python" / "shadowcert.pyi").read_text()


# ---- render and diff: the GL methods (headless EGL; CI has Mesa's llvmpipe) ----

SCENES = SOURCE / "data" / "scenes"


def read_png_rgba(path):
    """An 8-bit RGBA PNG as a (h, w, 4) uint8 array (what `shadowcert render --out` writes)."""
    import struct
    import zlib
    data = Path(path).read_bytes()
    pos, idat = 8, b""
    while pos < len(data):
        length, kind = struct.unpack(">I4s", data[pos:pos + 8])
        chunk = data[pos + 8:pos + 8 + length]
        pos += 12 + length
        if kind == b"IHDR":
            width, height, depth, colour = struct.unpack(">IIBB", chunk[:10])
            assert depth == 8 and colour == 6, f"{path}: not 8-bit RGBA"
        elif kind == b"IDAT":
            idat += chunk
    raw = np.frombuffer(zlib.decompress(idat), dtype=np.uint8).reshape(height, 1 + 4 * width)
    out = np.zeros((height, 4 * width), dtype=np.int32)
    previous = np.zeros(4 * width, dtype=np.int32)
    for y in range(height):
        kind, line = raw[y, 0], raw[y, 1:].astype(np.int32)
        row = np.zeros(4 * width, dtype=np.int32)
        for x in range(4 * width):
            a = row[x - 4] if x >= 4 else 0
            b = previous[x]
            c = previous[x - 4] if x >= 4 else 0
            if kind == 0:
                p = 0
            elif kind == 1:
                p = a
            elif kind == 2:
                p = b
            elif kind == 3:
                p = (a + b) // 2
            else:
                pa, pb, pc = abs(b - c), abs(a - c), abs(a + b - 2 * c)
                p = a if pa <= pb and pa <= pc else b if pb <= pc else c
            row[x] = (line[x] + p) & 255
        out[y], previous = row, row
    return out.reshape(height, width, 4).astype(np.uint8)


@pytest.mark.parametrize("method", ["cpu", "cs", "pertri", "smooth", "pcf", "smoothie"])
def test_render_equals_the_cli_pixel_for_pixel(method, tmp_path):
    if not CLI:
        pytest.fail("SHADOWCERT_CLI is not set (ctest sets it to build/cli/shadowcert)")
    scene = SCENES / "sphere_over_floor.json"
    out = tmp_path / "cli.png"
    run = subprocess.run([CLI, "render", str(scene), "--method", method, "--size", "96x72", "--out", str(out)],
                         capture_output=True, text=True, timeout=300)
    assert run.returncode == 0, run.stdout + run.stderr
    frame = shadowcert.render(str(scene), method, size=(96, 72))
    assert frame["image"].shape == (72, 96, 4) and frame["image"].dtype == np.uint8
    differing = int(np.count_nonzero(np.any(frame["image"] != read_png_rgba(out), axis=2)))
    assert differing == 0, f"{method}: {differing} pixels differ from shadowcert render"
    assert frame["method"] == method
    if method in ("pcf", "smoothie"):
        assert frame["counts"] is None and frame["stencil"] == []
    else:
        # The lit mask is the count's zero set, and some receiver pixels are shadowed.
        assert np.array_equal(frame["lit"] == 255, frame["counts"] == 0)
        assert 0 < np.count_nonzero(frame["lit"] == 0) < frame["lit"].size


def test_diff_equals_the_clis_json(tmp_path):
    if not CLI:
        pytest.fail("SHADOWCERT_CLI is not set (ctest sets it to build/cli/shadowcert)")
    scene = SCENES / "default.json"
    out = tmp_path / "diff.json"
    run = subprocess.run([CLI, "diff", str(scene), "--methods", "cpu,pertri,shadowmap", "--size", "80x60",
                          "--json", str(out)], capture_output=True, text=True, timeout=600)
    assert run.returncode in (0, 1), run.stdout + run.stderr
    cli = json.loads(out.read_text())["methods"]
    ours = shadowcert.diff(str(scene), ["cpu", "pertri", "shadowmap"], size=(80, 60))
    assert list(ours) == ["cpu", "pertri", "shadowmap"]
    figures = ["robust", "hard_errors", "ambiguous", "agree", "coverage_errors", "lit_errors", "count_errors",
               "closed", "failed"]
    for name, run_figures in ours.items():
        assert {k: run_figures[k] for k in figures} == {k: cli[name][k] for k in figures}, name
    # The robust methods: no hard error, a closed volume, most pixels compared.
    for name in ("cpu", "pertri"):
        assert ours[name]["hard_errors"] == 0 and ours[name]["closed"] is True
        assert ours[name]["agree"] > ours[name]["ambiguous"]


def test_render_and_diff_bad_arguments_raise_value_error(tmp_path):
    scene = str(SCENES / "default.json")
    with pytest.raises(ValueError, match="unknown GL method 'nosuch'"):
        shadowcert.render(scene, "nosuch")
    with pytest.raises(ValueError, match="stencil must be"):
        shadowcert.render(scene, "cpu", stencil="both")
    with pytest.raises(ValueError, match="size must be"):
        shadowcert.render(scene, "cpu", size=(0, 10))
    with pytest.raises(ValueError, match="missing.json"):
        shadowcert.render(str(tmp_path / "missing.json"))
    with pytest.raises(ValueError, match="no method"):
        shadowcert.diff(scene, [])


# ---- Open3D meshes as input (python3-open3d; tools/dev.sh installs it, so a missing one fails) ----

def test_open3d_meshes_certify_as_their_arrays_do():
    import open3d as o3d
    light = [0.3, 4.0, 0.2, 1.0]
    for mesh in (o3d.geometry.TriangleMesh.create_box(1.0, 2.0, 0.5),
                 o3d.geometry.TriangleMesh.create_sphere(0.8, 12),
                 o3d.geometry.TriangleMesh.create_torus(1.0, 0.3, 16, 8)):
        vertices, triangles = mesh.vertices, mesh.triangles  # Open3D's Vector3dVector and Vector3iVector
        report = shadowcert.certify(np.asarray(vertices), np.asarray(triangles), light, method="exact")
        plain = shadowcert.certify(np.asarray(vertices).tolist(), np.asarray(triangles).tolist(), light,
                                   method="exact")
        assert without_timings(report) == without_timings(plain)
        exact = report["methods"]["exact"]
        # Open3D's primitives are closed, so the chain is: no unbalanced edge, every count right.
        assert exact["closed"] and exact["unbalanced_edges"] == 0 and exact["count_failures"] == 0, exact
        assert report["triangles"] == len(triangles)
    # Open3D's vectors themselves (no np.asarray) are accepted as arrays too.
    box = o3d.geometry.TriangleMesh.create_box()
    direct = shadowcert.certify(box.vertices, box.triangles, light, method="exact")
    assert without_timings(direct) == without_timings(
        shadowcert.certify(np.asarray(box.vertices), np.asarray(box.triangles), light, method="exact"))


def test_open3d_mesh_exact_image_shadows_its_floor():
    import open3d as o3d
    box = o3d.geometry.TriangleMesh.create_box(0.5, 0.5, 0.5)
    box.translate((-0.25, 0.5, -0.25))
    floor = o3d.geometry.TriangleMesh.create_box(4.0, 0.01, 4.0)
    floor.translate((-2.0, -0.01, -2.0))
    both = box + floor
    image = shadowcert.exact_image(np.asarray(both.vertices), np.asarray(both.triangles), [0.0, 5.0, 0.0, 1.0],
                                   eye=[0.0, 4.0, 4.0], target=[0.0, 0.0, 0.0], size=[64, 48])
    counts = image["counts"][0]
    hit = image["hit_triangles"]
    floor_pixels = (hit != shadowcert.NO_HIT) & (hit >= len(box.triangles))
    # Under the box, the floor counts 2 (the box's top and bottom); elsewhere it is lit.
    assert np.any(floor_pixels & (counts == 2)) and np.any(floor_pixels & (counts == 0))
    assert not np.any(floor_pixels & (counts == 1))
