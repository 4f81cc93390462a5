#include "scene/scene_file.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <limits>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>

#include "core/camera.h"
#include "core/input_error.h"
#include "core/near_plane.h"
#include "core/portable_math.h"
#include "core/vector3.h"
#include "scene/affine_transform.h"
#include "scene/detail/generator_params.h"
#include "scene/json_field.h"
#include "scene/json_text.h"

namespace shadowcert {
namespace {

// Beyond any GL framebuffer; a larger value is surely a typo, not a wish.

// ---- transforms -------------------------------------------------------------------------

AffineTransform read_matrix(const JsonField& field) {
  const std::size_t n = field.array_size();
  if (n != 16) field.fail("expected 16 numbers (a row-major 4x4 matrix), got " + std::to_string(n));
  std::array<double, 16> m{};
  for (std::size_t i = 0; i < 16; ++i) m[i] = field.element(i).number();
  // Only affine maps keep triangles triangles; a projective last row would need a divide.
  if (m[12] != 0.0 || m[13] != 0.0 || m[14] != 0.0 || m[15] != 1.0)
    field.fail("the last row must be [0, 0, 0, 1] (affine transforms only)");
  AffineTransform t;
  for (std::size_t r = 0; r < 3; ++r) {
    for (std::size_t c = 0; c < 3; ++c) t.linear[r][c] = m[4 * r + c];
    t.translation[r] = m[4 * r + 3];
  }
  return t;
}

Vec3 read_scale(const JsonField& field) {
  if (field.json().is_number()) {
    const double s = field.number();
    return {s, s, s};
  }
  if (!field.json().is_array()) field.fail(std::string("expected a number or an array of 3 numbers, got ") +
                                           field.json().type_name());
  return field.vec3();
}

AffineTransform read_transform(const JsonField& field) {
  field.require_keys_within({"matrix", "translate", "scale", "rotate_deg"});
  const auto matrix = field.member("matrix");
  const auto translate = field.member("translate");
  const auto scale = field.member("scale");
  const auto rotate = field.member("rotate_deg");
  if (matrix) {
    if (translate || scale || rotate) field.fail("'matrix' cannot be combined with 'translate', 'scale' or 'rotate_deg'");
    return read_matrix(*matrix);
  }
  return compose_trs(translate ? translate->vec3() : Vec3{0, 0, 0}, scale ? read_scale(*scale) : Vec3{1, 1, 1},
                     rotate ? rotate->vec3() : Vec3{0, 0, 0});
}

bool all_finite(const Soup& soup) {
  return std::all_of(soup.vertices.begin(), soup.vertices.end(), [](const Vec3& p) {
    return std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]);
  });
}

bool all_finite(const Ellipsoid& e) {
  for (const Vec3& v : {e.centre, e.axes[0], e.axes[1], e.axes[2]})
    if (!std::isfinite(v[0]) || !std::isfinite(v[1]) || !std::isfinite(v[2])) return false;
  return true;
}

// The mesh's soup and analytic surface mapped by its "transform".
void place(SceneMesh& mesh, const JsonField& transform_field) {
  const AffineTransform transform = read_transform(transform_field);
  if (is_identity(transform)) return;
  try {
    mesh.soup = transformed(mesh.soup, transform);
    if (mesh.ellipsoid) mesh.ellipsoid = transformed(*mesh.ellipsoid, transform);
  } catch (const std::invalid_argument&) {
    transform_field.fail("singular transform (a zero scale or a degenerate matrix)");
  }
  if (!all_finite(mesh.soup) || (mesh.ellipsoid && !all_finite(*mesh.ellipsoid)))
    transform_field.fail("maps a vertex to a non-finite coordinate (overflow)");
}

// ---- meshes -----------------------------------------------------------------------------

// The reader is outside our control (a test lambda, a future format): keep docs/definitions.md#inputs' guarantees.
void check_reader_output(const JsonField& field, const Soup& soup) {
  if (!all_finite(soup)) field.fail("the mesh has a non-finite coordinate");
  for (const Triangle& t : soup.triangles)
    for (std::uint32_t i : t)
      if (i >= soup.vertices.size()) field.fail("the mesh has a vertex index out of range");
  if (!soup.normals.empty() && soup.normals.size() != soup.vertices.size())
    field.fail("the mesh has a normal count different from its vertex count");
}

Soup load_mesh_file(const JsonField& field, const std::filesystem::path& base_dir, const MeshFileReader& read_mesh) {
  const std::filesystem::path written = field.string();
  if (written.empty()) field.fail("empty path");
  if (!read_mesh) throw std::invalid_argument("parse_scene: a mesh file is named but no MeshFileReader was given");
  const std::filesystem::path full = written.is_absolute() ? written : base_dir / written;
  Soup soup;
  try {
    soup = read_mesh(full);
  } catch (const InputError& e) {
    field.fail(e.what());  // already "FILE[:LINE]: message"
  } catch (const std::runtime_error& e) {
    field.fail("cannot read '" + full.string() + "': " + e.what());
  }
  check_reader_output(field, soup);
  return soup;
}

// "silhouette": one of the four names of MeshSilhouette.
MeshSilhouette read_silhouette(const JsonField& field) {
  static constexpr std::array<std::pair<std::string_view, MeshSilhouette>, 4> kNames{
      {{"chain", MeshSilhouette::chain},
       {"discrete", MeshSilhouette::discrete},
       {"accurate", MeshSilhouette::accurate},
       {"smooth", MeshSilhouette::smooth}}};
  if (field.json().is_string()) {
    const std::string name = field.string();
    for (const auto& [known, value] : kNames)
      if (name == known) return value;
  }
  field.fail("expected \"chain\", \"discrete\", \"accurate\" or \"smooth\", got " + field.json().dump());
}

// "epsilon": the mesh's contour error, world units.
double read_epsilon(const JsonField& field) {
  const double epsilon = field.number();  // JSON numbers are finite
  if (!(epsilon > 0.0)) field.fail("must be a distance > 0 (world units), got " + field.json().dump());
  return epsilon;
}

SceneMesh read_mesh_entry(const JsonField& field, const std::filesystem::path& base_dir,
                          const MeshFileReader& reader) {
  field.require_keys_within({"name", "file", "generator", "params", "transform", "casts", "silhouette", "epsilon"});
  const auto file = field.member("file");
  const auto generator = field.member("generator");
  const auto params = field.member("params");
  if (file && generator) field.fail("give either 'file' or 'generator', not both");
  if (!file && !generator) field.fail("needs a 'file' or a 'generator'");
  if (file && params) params->fail("only generators take params");

  SceneMesh mesh;
  if (file) {
    mesh.name = file->string();
    mesh.soup = load_mesh_file(*file, base_dir, reader);
  } else {
    mesh.name = generator->string();
    GeneratedMesh generated = run_generator(*generator, params);
    mesh.soup = std::move(generated.soup);
    mesh.ellipsoid = generated.ellipsoid;
  }
  if (const auto name = field.member("name")) mesh.name = name->string();
  if (const auto transform = field.member("transform")) place(mesh, *transform);
  if (const auto casts = field.member("casts")) mesh.casts = casts->boolean();
  if (const auto silhouette = field.member("silhouette")) mesh.silhouette = read_silhouette(*silhouette);
  // Allowed without "silhouette": it is the mesh's contour error whenever it is cast smooth,
  // by its own "silhouette" or by the command's method.
  if (const auto epsilon = field.member("epsilon")) mesh.epsilon = read_epsilon(*epsilon);
  return mesh;
}

// ---- lights -----------------------------------------------------------------------------

Light read_light(const JsonField& field) {
  if (!field.json().is_array() || field.json().size() != 4)
    field.fail(std::string("expected [x, y, z, w], got ") +
               (field.json().is_array() ? std::to_string(field.json().size()) + " elements" : field.json().type_name()));
  Light light;
  for (std::size_t i = 0; i < 4; ++i) light.position[i] = field.element(i).number();
  const double w = light.position[3];
  if (w != 0.0 && w != 1.0)
    field.element(3).fail("w must be 0 (directional) or 1 (point), got " + field.element(3).json().dump());
  if (w == 0.0 && light.position[0] == 0.0 && light.position[1] == 0.0 && light.position[2] == 0.0)
    field.fail("a directional light (w = 0) needs a non-zero direction");
  return light;
}

// No "lights": one point light above the middle of the scene's bounding box, as high above
// its top as the box is across, so that every caster's shadow falls down and outwards. A box
// near the double range can put that point past it: an error on `root` (found by the scene
// fuzzer: a box scaled by 1e308), never an infinite light.
Light default_light(const std::vector<SceneMesh>& meshes, const JsonField& root) {
  Vec3 lo{std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity(),
          std::numeric_limits<double>::infinity()};
  Vec3 hi{-lo[0], -lo[1], -lo[2]};
  for (const SceneMesh& m : meshes)
    for (const Vec3& p : m.soup.vertices)
      for (int a = 0; a < 3; ++a) {
        lo[a] = std::min(lo[a], p[a]);
        hi[a] = std::max(hi[a], p[a]);
      }
  Light light;  // core's default, for an empty scene
  if (!(lo[0] <= hi[0])) return light;
  const double diagonal = portable::hypot(hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]);
  const double height = diagonal > 0.0 ? diagonal : 1.0;
  light.position = {lo[0] / 2 + hi[0] / 2, hi[1] + height, lo[2] / 2 + hi[2] / 2, 1.0};
  if (!std::isfinite(light.position[0]) || !std::isfinite(light.position[1]) || !std::isfinite(light.position[2]))
    root.fail("the default light (above the meshes, as high as they are across) overflows a double: give 'lights'");
  return light;
}

// ---- camera -----------------------------------------------------------------------------

// Vectors divided by their largest component, so that huge coordinates cannot overflow.
Vec3 max_normalised(const Vec3& v) {
  const double m = std::max({std::fabs(v[0]), std::fabs(v[1]), std::fabs(v[2])});
  return {v[0] / m, v[1] / m, v[2] / m};
}

bool nearly_parallel(const Vec3& a, const Vec3& b) {
  const Vec3 u = max_normalised(a), v = max_normalised(b);
  const Vec3 c = cross(u, v);
  return portable::hypot(c[0], c[1], c[2]) <= 1e-12;
}

std::uint32_t read_image_side(const JsonField& field) {
  const std::uint64_t side = field.unsigned_integer(kMaxImageSide);
  if (side == 0) field.fail("the image size must be at least 1 pixel");
  return static_cast<std::uint32_t>(side);
}

// The camera, and whether it gives its near plane ("near"; else parse_scene fits one).
Camera read_camera(const JsonField& field, bool& has_near) {
  field.require_keys_within({"eye", "target", "up", "fov_y_deg", "size", "near"});
  Camera camera;
  camera.eye = vec3_or(field, "eye", camera.eye);
  camera.target = vec3_or(field, "target", camera.target);
  camera.up = vec3_or(field, "up", camera.up);
  if (const auto fov = field.member("fov_y_deg")) {
    camera.fov_y_degrees = fov->number();
    if (!(camera.fov_y_degrees > 0.0 && camera.fov_y_degrees < 180.0))
      fov->fail("must be in (0, 180) degrees, got " + fov->json().dump());
  }
  if (const auto size = field.member("size")) {
    if (!size->json().is_array() || size->json().size() != 2)
      size->fail(std::string("expected [width, height], got ") +
                 (size->json().is_array() ? std::to_string(size->json().size()) + " elements"
                                          : size->json().type_name()));
    camera.width = read_image_side(size->element(0));
    camera.height = read_image_side(size->element(1));
  }
  has_near = false;
  if (const auto near = field.member("near")) {
    camera.near_plane = near->number();
    if (!(camera.near_plane > 0.0) || !std::isfinite(camera.near_plane))
      near->fail("must be a finite distance > 0, got " + near->json().dump());
    has_near = true;
  }
  if (camera.eye == camera.target) field.fail("eye and target must be different points");
  const Vec3 view{camera.target[0] - camera.eye[0], camera.target[1] - camera.eye[1],
                  camera.target[2] - camera.eye[2]};
  if (!std::isfinite(view[0]) || !std::isfinite(view[1]) || !std::isfinite(view[2]))
    field.fail("target - eye overflows a double");
  if (camera.up == Vec3{0, 0, 0}) field.fail("up must be a non-zero vector");
  if (nearly_parallel(camera.up, view)) field.fail("up must not be parallel to the viewing direction (target - eye)");
  return camera;
}

}  // namespace

Scene parse_scene(std::string_view json_text, const std::string& file_name, const std::filesystem::path& base_dir,
                  const MeshFileReader& read_mesh) {
  const nlohmann::json document = parse_json_text(json_text, file_name);
  const JsonField root(document, file_name);
  if (!document.is_object()) root.fail(std::string("a scene is a JSON object {...}, got ") + document.type_name());
  root.require_keys_within({"description", "meshes", "lights", "camera"});
  if (const auto description = root.member("description")) (void)description->string();  // type check only

  Scene scene;
  if (const auto meshes = root.member("meshes")) {
    const std::size_t n = meshes->array_size();
    scene.meshes.reserve(n);
    for (std::size_t i = 0; i < n; ++i) scene.meshes.push_back(read_mesh_entry(meshes->element(i), base_dir, read_mesh));
  }
  if (const auto lights = root.member("lights")) {
    const std::size_t n = lights->array_size();
    if (n == 0) lights->fail("needs at least one light (leave 'lights' out for the default one)");
    for (std::size_t i = 0; i < n; ++i) scene.lights.push_back(read_light(lights->element(i)));
  } else {
    scene.lights.push_back(default_light(scene.meshes, root));
  }
  bool has_near = false;
  if (const auto camera = root.member("camera")) scene.camera = read_camera(*camera, has_near);
  if (!has_near) scene.camera = camera_fitted_to(scene);
  return scene;
}

Scene load_scene(const std::filesystem::path& file, const MeshFileReader& read_mesh) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw InputError(file.string(), "cannot open the scene file");
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw InputError(file.string(), "cannot read the scene file");
  return parse_scene(text.str(), file.string(), file.parent_path(), read_mesh);
}

}  // namespace shadowcert
