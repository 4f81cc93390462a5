// `import shadowcert`: the library's soup reader, certificates and exact image for Python
// (docs/python.md). Arrays in and out are numpy arrays; every call that does real work releases
// the GIL. Errors: shadowcert::InputError (bad file) and std::invalid_argument (bad arguments,
// worded by the library as "<function>: ...") become ValueError with the library's message.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <chrono>
#include <cmath>
#include <cstdint>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "core/camera.h"
#include "core/input_error.h"
#include "core/light.h"
#include "core/soup.h"
#include "exact/closure_certificate.h"
#include "exact/count_certificate.h"
#include "exact/edge_multiplicity.h"
#include "exact/shadow_volume_chain.h"
#include "gpu/egl_context.h"
#include "gpu/offscreen_target.h"
#include "gpu/shadow_method.h"
#include "gpu/shadow_method_renderer.h"
#include "io/scene_input.h"
#include "io/soup_file.h"
#include "pipeline/drawn_method_scene.h"
#include "pipeline/method_certificate.h"
#include "pipeline/scene_comparison.h"
#include "pipeline/stencil_choice.h"
#include "reference/exact_image.h"
#include "scene/canonical_soup.h"
#include "scene/edge_table.h"
#include "scene/merged_soup.h"

namespace py = pybind11;

namespace shadowcert::python {
namespace {

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

[[noreturn]] void value_error(const std::string& message) { throw py::value_error(message); }

// A vector moved into a numpy array that owns it (no copy): the capsule frees it.
template <typename T>
py::array_t<T> to_numpy(std::vector<T>&& values, std::vector<py::ssize_t> shape) {
  auto* owned = new std::vector<T>(std::move(values));
  py::capsule free_when_done(owned, [](void* p) { delete static_cast<std::vector<T>*>(p); });
  return py::array_t<T>(shape, owned->data(), free_when_done);
}

// vertices: float64 (n, 3); triangles: integer (m, 3), any integer dtype whose values fit uint32.
// Shape and dtype are checked here; finiteness and index range by the library's own
// preconditions (core/soup.h), so the messages are the library's.
Soup soup_from_arrays(const py::object& vertices_object, const py::object& triangles_object, const char* function) {
  const std::string f(function);
  const py::array vertices = py::module_::import("numpy").attr("asarray")(vertices_object);
  const py::array triangles = py::module_::import("numpy").attr("asarray")(triangles_object);
  if (vertices.ndim() != 2 || vertices.shape(1) != 3)
    value_error(f + ": vertices must be an (n, 3) array, got shape " + std::string(py::str(vertices.attr("shape"))));
  if (triangles.ndim() != 2 || triangles.shape(1) != 3)
    value_error(f + ": triangles must be an (m, 3) array, got shape " + std::string(py::str(triangles.attr("shape"))));
  if (vertices.dtype().kind() != 'f' && vertices.dtype().kind() != 'i' && vertices.dtype().kind() != 'u')
    value_error(f + ": vertices must be a float array, got dtype " + std::string(py::str(vertices.dtype())));
  const char kind = triangles.dtype().kind();
  if (kind != 'i' && kind != 'u')
    value_error(f + ": triangles must be an integer array, got dtype " + std::string(py::str(triangles.dtype())));
  Soup soup;
  const auto v = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(vertices);
  soup.vertices.resize(static_cast<std::size_t>(v.shape(0)));
  const double* vd = v.data();
  for (std::size_t i = 0; i < soup.vertices.size(); ++i) soup.vertices[i] = {vd[3 * i], vd[3 * i + 1], vd[3 * i + 2]};
  const auto t = py::array_t<std::int64_t, py::array::c_style | py::array::forcecast>::ensure(triangles);
  soup.triangles.resize(static_cast<std::size_t>(t.shape(0)));
  const std::int64_t* td = t.data();
  for (std::size_t i = 0; i < soup.triangles.size(); ++i)
    for (int k = 0; k < 3; ++k) {
      const std::int64_t index = td[3 * i + static_cast<std::size_t>(k)];
      if (index < 0 || index >= static_cast<std::int64_t>(soup.vertices.size()))
        value_error(f + ": triangle " + std::to_string(i) + " has vertex index " + std::to_string(index) +
                    ", but the soup has " + std::to_string(soup.vertices.size()) + " vertices");
      soup.triangles[i][static_cast<std::size_t>(k)] = static_cast<std::uint32_t>(index);
    }
  require_finite_vertices(soup, function);
  require_indices_in_range(soup, function);
  return soup;
}

Light light_from(const std::vector<double>& values, const char* function) {
  if (values.size() != 4)
    value_error(std::string(function) + ": a light is four numbers x, y, z, w, got " + std::to_string(values.size()));
  Light light;
  for (std::size_t k = 0; k < 4; ++k) light.position[k] = values[k];
  require_defined(light, function);  // the library's wording
  return light;
}

// ---- read_soup ----

py::tuple soup_to_numpy(Soup&& soup);

py::tuple read_soup_py(const std::string& path) {
  Soup soup;
  {
    py::gil_scoped_release release;
    soup = read_soup(path);
  }
  return soup_to_numpy(std::move(soup));
}

py::tuple soup_to_numpy(Soup&& soup) {
  std::vector<double> v;
  v.reserve(3 * soup.vertices.size());
  for (const Vec3& p : soup.vertices) v.insert(v.end(), p.begin(), p.end());
  std::vector<std::uint32_t> t;
  t.reserve(3 * soup.triangles.size());
  for (const Triangle& tri : soup.triangles) t.insert(t.end(), tri.begin(), tri.end());
  const auto n = static_cast<py::ssize_t>(soup.vertices.size());
  const auto m = static_cast<py::ssize_t>(soup.triangles.size());
  return py::make_tuple(to_numpy(std::move(v), {n, 3}), to_numpy(std::move(t), {m, 3}));
}

// ---- read_scene: a scene file (or a mesh, as certify reads it: io/scene_input.h) ----

py::dict read_scene_py(const std::string& path) {
  Scene scene;
  Soup all, casters;
  std::vector<std::uint8_t> casts;
  {
    py::gil_scoped_release release;
    scene = load_scene_or_mesh(path);
    all = merged_soup(scene);
    casters = merged_casters(scene);
    casts = casting_triangles(scene);
  }
  py::dict out;
  const py::tuple soup = soup_to_numpy(std::move(all));
  out["vertices"] = soup[0];
  out["triangles"] = soup[1];
  const auto m = static_cast<py::ssize_t>(casts.size());
  out["casts"] = to_numpy(std::move(casts), {m});
  const py::tuple caster_soup = soup_to_numpy(std::move(casters));
  out["caster_vertices"] = caster_soup[0];
  out["caster_triangles"] = caster_soup[1];
  std::vector<double> lights;
  for (const Light& l : scene.lights) lights.insert(lights.end(), l.position.begin(), l.position.end());
  const auto k = static_cast<py::ssize_t>(scene.lights.size());
  out["lights"] = to_numpy(std::move(lights), {k, 4});
  py::dict camera;
  camera["eye"] = scene.camera.eye;
  camera["target"] = scene.camera.target;
  camera["up"] = scene.camera.up;
  camera["fov_y"] = scene.camera.fov_y_degrees;
  camera["near"] = scene.camera.near_plane;
  camera["size"] = std::vector<std::uint32_t>{scene.camera.width, scene.camera.height};
  out["camera"] = camera;
  return out;
}

// ---- certify: the same stages and the same JSON as `shadowcert certify --json` (pipeline/method_certificate.h) ----

std::vector<MultiplicityMethod> chosen_methods(const std::string& name) {
  if (name == "all")
    return {MultiplicityMethod::exact, MultiplicityMethod::kim, MultiplicityMethod::peciva,
            MultiplicityMethod::refedge};
  try {
    return {parse_method(name)};
  } catch (const std::invalid_argument&) {
    value_error("certify: unknown method '" + name + "' (exact, kim, peciva, refedge, all)");
  }
}

std::vector<Vec3> points_from(const py::object& points_object) {
  std::vector<Vec3> out;
  if (points_object.is_none()) return out;
  const py::array points = py::module_::import("numpy").attr("asarray")(points_object);
  if (points.ndim() != 2 || points.shape(1) != 3)
    value_error("certify: points must be a (k, 3) array, got shape " + std::string(py::str(points.attr("shape"))));
  const char kind = points.dtype().kind();
  if (kind != 'f' && kind != 'i' && kind != 'u')
    value_error("certify: points must be a float array, got dtype " + std::string(py::str(points.dtype())));
  const auto p = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(points);
  for (py::ssize_t i = 0; i < p.shape(0); ++i) {
    const Vec3 q{p.at(i, 0), p.at(i, 1), p.at(i, 2)};
    for (double x : q)
      if (!std::isfinite(x)) value_error("certify: point " + std::to_string(i) + " has a non-finite coordinate");
    out.push_back(q);
  }
  return out;
}

py::object certify_py(const py::object& vertices, const py::object& triangles, const std::vector<double>& light_values,
                      const std::string& method, const std::string& precision_name, std::uint64_t samples,
                      std::uint64_t seed, const py::object& points) {
  const auto start = Clock::now();
  const Soup input = soup_from_arrays(vertices, triangles, "certify");
  const Light light = light_from(light_values, "certify");
  const std::vector<MultiplicityMethod> methods = chosen_methods(method);
  if (precision_name != "float" && precision_name != "double")
    value_error("certify: precision expects float or double, got '" + precision_name + "'");
  if (input.triangles.empty()) value_error("certify: no casting triangle to certify");
  const Precision precision = precision_name == "float" ? Precision::float32 : Precision::float64;
  CountSampling sampling;
  sampling.in_box = samples / 2;
  sampling.on_triangles = samples - sampling.in_box;
  sampling.seed = seed;
  sampling.user_points = points_from(points);
  const double load_seconds = seconds_since(start);

  std::string text;
  {
    py::gil_scoped_release release;
    auto stage = Clock::now();
    const CanonicalSoup canonical = canonical_soup(input);
    const double canonical_seconds = seconds_since(stage);
    stage = Clock::now();
    const EdgeTable table = build_edge_table(canonical.soup);
    const double table_seconds = seconds_since(stage);
    nlohmann::json json_methods = nlohmann::json::object();
    for (MultiplicityMethod m : methods) {
      const MethodCertificate c = certify_method(m, precision, canonical.soup, table, light, sampling);
      json_methods[c.name] = method_certificate_json(c);
    }
    const nlohmann::json report = {
        {"input", nullptr},
        {"triangles", input.triangles.size()},
        {"welded_vertices", canonical.soup.vertices.size()},
        {"edges", table.size()},
        {"light", light.position},
        {"precision", precision_name},
        {"seed", seed},
        {"samples", samples},
        {"user_points", sampling.user_points.size()},
        {"stage_seconds", {{"load", load_seconds}, {"weld_and_order", canonical_seconds}, {"edge_table", table_seconds}}},
        {"methods", json_methods}};
    text = report.dump();
  }
  return py::module_::import("json").attr("loads")(text);
}

// ---- exact_image ----

Camera camera_from(const py::dict& camera) {
  Camera c;
  auto vec3 = [](const py::handle& h, const char* key) {
    const auto values = h.cast<std::vector<double>>();
    if (values.size() != 3) value_error(std::string("exact_image: camera '") + key + "' must be three numbers");
    return Vec3{values[0], values[1], values[2]};
  };
  for (const auto& [key_handle, value] : camera) {
    const auto key = key_handle.cast<std::string>();
    if (key == "eye") c.eye = vec3(value, "eye");
    else if (key == "target") c.target = vec3(value, "target");
    else if (key == "up") c.up = vec3(value, "up");
    else if (key == "fov_y" || key == "fov_y_degrees") c.fov_y_degrees = value.cast<double>();
    else if (key == "near") c.near_plane = value.cast<double>();
    else if (key == "size") {
      const auto size = value.cast<std::vector<std::int64_t>>();
      if (size.size() != 2) value_error("exact_image: camera 'size' must be [width, height]");
      for (std::int64_t s : size)
        if (s < 1 || s > static_cast<std::int64_t>(kMaxImageSide))
          value_error("exact_image: image sides must be in [1, " + std::to_string(kMaxImageSide) + "]");
      c.width = static_cast<std::uint32_t>(size[0]);
      c.height = static_cast<std::uint32_t>(size[1]);
    } else
      value_error("exact_image: unknown camera key '" + key + "' (eye, target, up, fov_y, near, size)");
  }
  return c;
}

py::dict exact_image_py(const py::object& vertices, const py::object& triangles, const py::object& lights_object,
                        const std::optional<py::dict>& camera_dict, const std::optional<std::vector<double>>& eye,
                        const std::optional<std::vector<double>>& target, const std::optional<std::vector<std::int64_t>>& size,
                        const py::object& casts, bool footprints) {
  const Soup soup = soup_from_arrays(vertices, triangles, "exact_image");
  const auto light_rows = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(lights_object);
  const bool one = light_rows && light_rows.ndim() == 1 && light_rows.shape(0) == 4;
  const bool rows = light_rows && light_rows.ndim() == 2 && light_rows.shape(1) == 4;
  if (!one && !rows)
    value_error("exact_image: lights must be a (k, 4) array of x, y, z, w (or one light of four numbers)");
  std::vector<Light> lights;
  const py::ssize_t k = light_rows.ndim() == 1 ? 1 : light_rows.shape(0);
  for (py::ssize_t i = 0; i < k; ++i)
    lights.push_back(light_from({light_rows.data()[4 * i], light_rows.data()[4 * i + 1], light_rows.data()[4 * i + 2],
                                 light_rows.data()[4 * i + 3]},
                                "exact_image"));
  py::dict given = camera_dict ? *camera_dict : py::dict();
  if (eye) given["eye"] = *eye;
  if (target) given["target"] = *target;
  if (size) given["size"] = *size;
  const Camera camera = camera_from(given);
  ExactImageOptions options;
  options.footprints = footprints;
  if (!casts.is_none()) {
    const auto c = py::array_t<std::uint8_t, py::array::c_style | py::array::forcecast>::ensure(
        py::module_::import("numpy").attr("asarray")(casts));
    if (!c || c.ndim() != 1) value_error("exact_image: casts must be a 1-D array of one flag per triangle");
    options.casts.assign(c.data(), c.data() + c.shape(0));
  }
  ExactImage image;
  {
    py::gil_scoped_release release;
    image = exact_image(soup, lights, camera, options);
  }
  const auto h = static_cast<py::ssize_t>(image.height), w = static_cast<py::ssize_t>(image.width);
  const auto n = static_cast<py::ssize_t>(lights.size());
  std::vector<std::uint32_t> counts;
  std::vector<std::uint8_t> lit, ambiguity;
  counts.reserve(static_cast<std::size_t>(n * h * w));
  lit.reserve(counts.capacity());
  ambiguity.reserve(counts.capacity());
  for (const ExactLightImage& l : image.lights) {
    counts.insert(counts.end(), l.counts.begin(), l.counts.end());
    lit.insert(lit.end(), l.lit.begin(), l.lit.end());
    ambiguity.insert(ambiguity.end(), l.ambiguity.begin(), l.ambiguity.end());
  }
  py::dict out;
  out["counts"] = to_numpy(std::move(counts), {n, h, w});
  out["lit"] = to_numpy(std::move(lit), {n, h, w});
  out["ambiguity"] = to_numpy(std::move(ambiguity), {n, h, w});
  out["hit_triangles"] = to_numpy(std::move(image.hit_triangles), {h, w});
  out["view_ambiguity"] = to_numpy(std::move(image.view_ambiguity), {h, w});
  out["seconds"] = image.stats.seconds;
  return out;
}

// ---- render and diff: the GL methods, headless (EGL), as the CLI draws them ----

gpu::ShadowMethod gl_method(const std::string& name, const char* function) {
  const std::optional<gpu::ShadowMethod> m = gpu::parse_shadow_method(name);
  if (!m) {
    std::string all;
    for (const gpu::ShadowMethodTraits& t : gpu::kShadowMethodTable) all += (all.empty() ? "" : ", ") + std::string(t.name);
    value_error(std::string(function) + ": unknown GL method '" + name + "' (" + all + ")");
  }
  return *m;
}

StencilChoice stencil_choice(const std::string& name, const char* function) {
  if (name == "zfail") return StencilChoice::zfail;
  if (name == "zpass") return StencilChoice::zpass;
  if (name == "auto") return StencilChoice::automatic;
  value_error(std::string(function) + ": stencil must be 'zfail', 'zpass' or 'auto', got '" + name + "'");
}

// The scene file at `path` (a scene or a mesh, as the CLI reads it), `size` (width, height)
// replacing its camera's when given.
Scene scene_for_gl(const std::string& path, const std::optional<std::array<std::uint32_t, 2>>& size,
                   const char* function) {
  Scene scene = load_scene_or_mesh(path);
  if (size) {
    if ((*size)[0] == 0 || (*size)[1] == 0) value_error(std::string(function) + ": size must be two positive integers");
    scene.camera.width = (*size)[0];
    scene.camera.height = (*size)[1];
  }
  if (scene.lights.empty()) throw InputError(path, "the scene has no light");
  return scene;
}

template <int Channels>
py::array_t<std::uint8_t> image_to_numpy(gpu::Image<Channels>&& image) {
  const auto h = static_cast<py::ssize_t>(image.height), w = static_cast<py::ssize_t>(image.width);
  if constexpr (Channels == 1) return to_numpy(std::move(image.pixels), {h, w});
  else
  return to_numpy(std::move(image.pixels), {h, w, static_cast<py::ssize_t>(Channels)});
}

py::dict render_py(const std::string& path, const std::string& method_name,
                   const std::optional<std::array<std::uint32_t, 2>>& size, const std::string& stencil_name,
                   const std::optional<int>& device) {
  const gpu::ShadowMethod method = gl_method(method_name, "render");
  const StencilChoice stencil = stencil_choice(stencil_name, "render");
  gpu::StencilShadowFrame frame;
  std::vector<gpu::StencilMethod> stencils;
  std::string renderer_name;
  {
    py::gil_scoped_release release;
    const Scene scene = scene_for_gl(path, size, "render");
    // The context first: what follows uploads to it. Made current on this thread, released on return.
    const gpu::EglContext context(gpu::EglContextOptions{device, false});
    renderer_name = context.renderer();
    const auto d = prepare_drawn_method_scene(scene, method, stencil);
    gpu::ShadowMethodRenderer renderer(method, d->method_scene(), d->renderer_options());
    const gpu::OffscreenTarget target(d->scene.camera.width, d->scene.camera.height);
    frame = renderer.render(target, d->scene.camera);
    renderer.check_capacity();  // a GPU-built volume that overflowed: an error, not an open volume's image
    stencils = d->light_stencil;
  }
  py::dict out;
  const bool counts = gpu::draws_volume(method);
  out["image"] = image_to_numpy(std::move(frame.colour));
  out["lit"] = image_to_numpy(std::move(frame.first_lit_mask));
  out["counts"] = counts ? py::object(image_to_numpy(std::move(frame.first_stencil))) : py::none();
  py::list names;
  for (const gpu::StencilMethod s : stencils) names.append(s == gpu::StencilMethod::zpass ? "zpass" : "zfail");
  out["stencil"] = names;
  out["method"] = std::string(gpu::shadow_method_name(method));
  out["renderer"] = renderer_name;
  return out;
}

py::dict comparison_dict(const PixelComparison& c) {
  py::dict d;
  d["hard_errors"] = c.hard_errors;
  d["ambiguous"] = c.ambiguous;
  d["agree"] = c.agree;
  d["coverage_errors"] = c.coverage_errors;
  d["lit_errors"] = c.lit_errors;
  d["count_errors"] = c.count_errors;
  return d;
}

py::dict diff_py(const std::string& path, const std::vector<std::string>& method_names,
                 const std::optional<std::array<std::uint32_t, 2>>& size, const std::string& stencil_name,
                 const std::optional<int>& device) {
  if (method_names.empty()) value_error("diff: no method");
  std::vector<gpu::ShadowMethod> methods;
  for (const std::string& name : method_names) methods.push_back(gl_method(name, "diff"));
  SceneComparisonOptions options;
  const StencilChoice stencil = stencil_choice(stencil_name, "diff");
  options.stencil_auto = stencil == StencilChoice::automatic;
  options.method_options.stencil = stencil == StencilChoice::zpass ? gpu::StencilMethod::zpass : gpu::StencilMethod::zfail;
  SceneComparison comparison;
  {
    py::gil_scoped_release release;
    const Scene scene = scene_for_gl(path, size, "diff");
    const gpu::EglContext context(gpu::EglContextOptions{device, false});
    comparison = compare_scene(scene, methods, options);
  }
  py::dict out;
  for (const MethodRun& run : comparison.runs) {
    py::dict m;
    m["robust"] = run.held_robust;
    m["hard_errors"] = run.sum(&PixelComparison::hard_errors);
    m["ambiguous"] = run.sum(&PixelComparison::ambiguous);
    m["agree"] = run.sum(&PixelComparison::agree);
    m["coverage_errors"] = run.sum(&PixelComparison::coverage_errors);
    m["lit_errors"] = run.sum(&PixelComparison::lit_errors);
    m["count_errors"] = run.sum(&PixelComparison::count_errors);
    const std::optional<bool> closed = run.closed();
    m["closed"] = closed ? py::object(py::bool_(*closed)) : py::none();
    m["failed"] = run.failed();
    py::list per_light;
    for (const LightRun& l : run.lights) {
      py::dict lj = comparison_dict(l.comparison);
      lj["closed"] = l.closure ? py::object(py::bool_(l.closure->closed)) : py::none();
      if (!l.capacity_error.empty()) lj["capacity_error"] = l.capacity_error;
      per_light.append(lj);
    }
    m["per_light"] = per_light;
    out[py::str(std::string(gpu::shadow_method_name(run.method)))] = m;
  }
  return out;
}

}  // namespace
}  // namespace shadowcert::python

PYBIND11_MODULE(shadowcert, m) {
  using namespace shadowcert;
  using namespace shadowcert::python;
  m.doc() = "Exact shadow-volume certification and the exact shadow image (docs/python.md).";
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const InputError& e) {
      PyErr_SetString(PyExc_ValueError, e.what());
    } catch (const std::invalid_argument& e) {
      PyErr_SetString(PyExc_ValueError, e.what());
    }
  });
  m.attr("NO_HIT") = kNoHit;
  m.attr("UNDEFINED_COUNT") = kUndefinedCount;
  m.def("read_soup", &read_soup_py, py::arg("path"),
        "read_soup(path) -> (vertices, triangles)\n\n"
        "Reads a mesh file (.obj .off .ply .stl; polygons fan-triangulated) as the CLI does.\n"
        "Returns vertices, float64 of shape (n, 3), and triangles, uint32 of shape (m, 3).\n"
        "Raises ValueError with the reader's message (FILE:LINE: ...) on bad input.");
  m.def("read_scene", &read_scene_py, py::arg("path"),
        "read_scene(path) -> dict\n\n"
        "Reads a scene (.json, docs/scene-format.md) or a mesh file as `shadowcert certify` does (a\n"
        "mesh gets core/scene.h's default light and camera). Returns a dict: vertices float64 (n, 3)\n"
        "and triangles uint32 (m, 3) of every mesh, casts uint8 (m,) (0: the mesh only receives,\n"
        "exact_image's casts=), caster_vertices and caster_triangles (the casting meshes alone,\n"
        "what certify takes), lights float64 (k, 4) and camera (a dict exact_image takes).\n"
        "Raises ValueError with the reader's message on bad input.");
  m.def("certify", &certify_py, py::arg("vertices"), py::arg("triangles"), py::arg("light"),
        py::arg("method") = "all", py::arg("precision") = "float", py::arg("samples") = 2000,
        py::arg("seed") = 1, py::arg("points") = py::none(),
        "certify(vertices, triangles, light, method='all', precision='float', samples=2000, seed=1, points=None) -> dict\n\n"
        "Exact multiplicities, the shadow-volume chain and its closure and count certificates for\n"
        "each method (exact, kim, peciva, refedge or all), as `shadowcert certify --json` reports\n"
        "them: the same keys and figures ('input' is None). light: x, y, z, w (w = 1 point, 0\n"
        "directional). points: extra (k, 3) sample points. Raises ValueError on a bad array\n"
        "(shape, dtype, non-finite coordinate, index out of range) or a bad light or method.");
  m.def("exact_image", &exact_image_py, py::arg("vertices"), py::arg("triangles"), py::arg("lights"),
        py::arg("camera") = py::none(), py::kw_only(), py::arg("eye") = py::none(), py::arg("target") = py::none(),
        py::arg("size") = py::none(), py::arg("casts") = py::none(), py::arg("footprints") = true,
        "exact_image(vertices, triangles, lights, camera=None, *, eye=None, target=None, size=None,\n"
        "            casts=None, footprints=True) -> dict\n\n"
        "The exact image (docs/definitions.md#pixel-protocol) for a camera and each light.\n"
        "lights: (k, 4) or four numbers. camera: a dict of eye, target, up, fov_y (degrees), near,\n"
        "size [width, height] (defaults of core/camera.h); eye, target and size override it.\n"
        "Returns a dict of numpy arrays, rows top first: counts uint32 (k, h, w) (NO_HIT, UNDEFINED_COUNT),\n"
        "lit uint8 (k, h, w) (255 lit), ambiguity uint8 (k, h, w) (reason bits), hit_triangles\n"
        "uint32 (h, w), view_ambiguity uint8 (h, w), and seconds. Raises ValueError on bad input.");
  m.def("render", &render_py, py::arg("scene"), py::arg("method") = "cpu", py::kw_only(),
        py::arg("size") = py::none(), py::arg("stencil") = "zfail", py::arg("device") = py::none(),
        "render(scene, method='cpu', *, size=None, stencil='zfail', device=None) -> dict\n\n"
        "One frame of a GL method (cpu, cs, gs, ts, pertri, shadowmap, discrete, accurate, smooth,\n"
        "smooth-gpu, pcf, pcss, smoothie) of the scene or mesh file `scene`, drawn headless through\n"
        "EGL exactly as `shadowcert render --method M` draws it with its default options (the same\n"
        "pixels). size: (width, height) for the camera's; stencil: zfail, zpass or auto (volume\n"
        "methods); device: an EGL device index (`shadowcert devices`), None to choose.\n"
        "Returns a dict, rows top first: image uint8 (h, w, 4) (alpha 0 where no receiver), lit\n"
        "uint8 (h, w) (the first light: 255 lit), counts uint8 (h, w) (the first light's stencil\n"
        "counts modulo 256; None for the shadow-map methods), stencil (each light's z-pass or\n"
        "z-fail), method and renderer (GL_RENDERER). Raises ValueError on a bad file or argument,\n"
        "RuntimeError with the driver's message when no GL 4.5 context can be made.");
  m.def("diff", &diff_py, py::arg("scene"),
        py::arg("methods") = std::vector<std::string>{"cpu", "cs", "gs", "ts", "pertri"}, py::kw_only(),
        py::arg("size") = py::none(), py::arg("stencil") = "zfail", py::arg("device") = py::none(),
        "diff(scene, methods=['cpu','cs','gs','ts','pertri'], *, size=None, stencil='zfail', device=None) -> dict\n\n"
        "Each GL method's frame against the exact image, as `shadowcert diff --json` compares them\n"
        "(docs/diff.md): a dict by method name of robust, hard_errors, ambiguous, agree,\n"
        "coverage_errors, lit_errors, count_errors, closed (None for the shadow maps), failed and\n"
        "per_light (the same figures per light). Raises as render does.");
}
