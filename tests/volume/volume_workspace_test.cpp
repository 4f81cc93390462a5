// volume/volume_workspace.h: the library's volume is the cpu volume `render --method cpu`
// draws (pipeline/method_inputs.cpp: cpu_volume_mesh of the scene's merged casters, welded),
// bit for bit, on every bundled scene and light, and certifies as it does: closure of the
// volume as written, and the count certificate of the chain read back from the written
// triangles. Float and double input, too-small buffers, bad input, threads, relabelling,
// face reversal, translation, the flags, and what the hot path allocates.
#include "volume/volume_workspace.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <bit>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <limits>
#include <map>
#include <new>
#include <numeric>
#include <random>
#include <stdexcept>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "core/float_rounding.h"
#include "core/homogeneous_mesh.h"
#include "exact/closure_certificate.h"
#include "exact/count_certificate.h"
#include "exact/cpu_volume.h"
#include "exact/edge_multiplicity.h"
#include "exact/shadow_volume_chain.h"
#include "exact/volume_closure.h"
#include "io/scene_input.h"
#include "scene/canonical_soup.h"
#include "scene/edge_table.h"
#include "scene/merged_soup.h"
#include "scene/procedural_mesh.h"

// Every allocation of this program through operator new, counted: the hot-path test reads the
// bytes a build asks for. (TBB's task objects come from its own allocator, not counted: the
// header says so.) Both operators are malloc and free, which GCC's inlining check cannot see.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"
#endif
namespace {
std::atomic<std::size_t> g_new_bytes{0};
std::atomic<std::size_t> g_new_calls{0};
}  // namespace

void* operator new(std::size_t bytes) {
  g_new_bytes += bytes;
  ++g_new_calls;
  if (void* p = std::malloc(bytes == 0 ? 1 : bytes)) return p;
  throw std::bad_alloc();
}
void* operator new[](std::size_t bytes) { return operator new(bytes); }
// The nothrow forms too (std::stable_sort's temporary buffer): every form a program may pair
// with these deletes must be malloc, or ASan reports the mismatch (the sanitizer build did).
void* operator new(std::size_t bytes, const std::nothrow_t&) noexcept {
  g_new_bytes += bytes;
  ++g_new_calls;
  return std::malloc(bytes == 0 ? 1 : bytes);
}
void* operator new[](std::size_t bytes, const std::nothrow_t& tag) noexcept { return operator new(bytes, tag); }
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete(void* p, const std::nothrow_t&) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, const std::nothrow_t&) noexcept { std::free(p); }

namespace shadowcert {
namespace {

std::vector<double> double_positions(const Soup& soup) {
  std::vector<double> out;
  for (const Vec3& v : soup.vertices) out.insert(out.end(), v.begin(), v.end());
  return out;
}

std::vector<float> float_positions(const Soup& soup) {
  std::vector<float> out;
  for (const Vec3& v : soup.vertices)
    for (const double x : v) out.push_back(static_cast<float>(x));
  return out;
}

std::vector<std::uint32_t> indices_of(const Soup& soup) {
  std::vector<std::uint32_t> out;
  for (const Triangle& t : soup.triangles) out.insert(out.end(), t.begin(), t.end());
  return out;
}

struct Output {
  std::vector<float> positions;
  std::vector<std::uint32_t> indices;
  VolumeInfo info;
};

// The documented calling sequence: build (the size query), buffers of that size, write.
Output generate(VolumeWorkspace& ws, const Light& light, const VolumeView* view = nullptr) {
  const VolumeSizes sizes = ws.build(light);
  Output out;
  out.positions.resize(sizes.position_floats());
  out.indices.resize(sizes.index_count());
  out.info = ws.write(out.positions, out.indices, view);
  return out;
}

HomogeneousMesh mesh_of(const Output& out) {
  HomogeneousMesh mesh;
  for (std::size_t i = 0; i < out.info.written.vertices; ++i)
    mesh.vertices.push_back({out.positions[4 * i], out.positions[4 * i + 1], out.positions[4 * i + 2],
                             out.positions[4 * i + 3]});
  for (std::size_t i = 0; i < out.info.written.triangles; ++i)
    mesh.triangles.push_back({out.indices[3 * i], out.indices[3 * i + 1], out.indices[3 * i + 2]});
  return mesh;
}

void expect_same_mesh(const HomogeneousMesh& a, const HomogeneousMesh& b, const std::string& what) {
  ASSERT_EQ(a.vertices.size(), b.vertices.size()) << what;
  ASSERT_EQ(a.triangles.size(), b.triangles.size()) << what;
  for (std::size_t i = 0; i < a.vertices.size(); ++i)
    for (std::size_t k = 0; k < 4; ++k)
      ASSERT_EQ(std::bit_cast<std::uint32_t>(a.vertices[i][k]), std::bit_cast<std::uint32_t>(b.vertices[i][k]))
          << what << ": vertex " << i;
  EXPECT_EQ(a.triangles, b.triangles) << what;
}

// The chain (exact/shadow_volume_chain.h) that the written triangles are, read back from them
// alone, so that the count certificate certifies the library's output itself. chain_mesh's
// faces: a triangle of three finite vertices (id < n) is a front cap, in soup triangle order;
// one of two, always first, (p, q, far) is one copy of the side of edge pq, oriented p -> q
// (a point light's quad (p, q, far q, far p) starts so; a directional light's side is the
// triangle (p, q, far)); every other triangle lies at infinity or completes a quad, which the
// count certificate does not read. `rounded`: the welded soup rounded to float, as the volume is.
ShadowVolumeChain chain_read_back(const HomogeneousMesh& mesh, const Soup& rounded, const Light& light) {
  const auto n = static_cast<std::uint32_t>(rounded.vertices.size());
  ShadowVolumeChain chain;
  chain.finite_vertices = n;
  chain.directional = light.directional();
  std::map<std::pair<std::uint32_t, std::uint32_t>, std::int32_t> sides;
  std::size_t next_triangle = 0;
  for (const auto& f : mesh.triangles) {
    const int finite = (f[0] < n) + (f[1] < n) + (f[2] < n);
    if (finite == 3) {
      auto same_set = [&f](const Triangle& t) {
        std::array<std::uint32_t, 3> a{f[0], f[1], f[2]}, b{t[0], t[1], t[2]};
        std::sort(a.begin(), a.end());
        std::sort(b.begin(), b.end());
        return a == b && a[0] != a[1] && a[1] != a[2];
      };
      while (next_triangle < rounded.triangles.size() && !same_set(rounded.triangles[next_triangle])) ++next_triangle;
      EXPECT_LT(next_triangle, rounded.triangles.size()) << "a front cap that is no soup triangle";
      if (next_triangle >= rounded.triangles.size()) return chain;
      const Triangle& t = rounded.triangles[next_triangle];
      const bool rotation = (f[0] == t[0] && f[1] == t[1]) || (f[0] == t[1] && f[1] == t[2]) ||
                            (f[0] == t[2] && f[1] == t[0]);
      chain.cap_triangles.push_back(static_cast<std::uint32_t>(next_triangle));
      chain.cap_sign.push_back(rotation ? Sign::positive : Sign::negative);
      ++next_triangle;
    } else if (finite == 2) {
      EXPECT_TRUE(f[0] < n && f[1] < n) << "a side face whose finite edge is not first";
      if (f[0] < f[1])
        ++sides[{f[0], f[1]}];
      else
        --sides[{f[1], f[0]}];
    }
  }
  for (const auto& [edge, m] : sides) {
    if (m == 0) continue;
    chain.side_edges.push_back({edge.first, edge.second});
    chain.side_multiplicity.push_back(m);
  }
  return chain;
}

CountSampling small_sampling() {
  CountSampling s;
  s.in_box = 150;
  s.on_triangles = 150;
  s.seed = 7;
  return s;
}

std::vector<std::filesystem::path> bundled_scenes() {
  const std::filesystem::path root = std::filesystem::path(SHADOWCERT_SOURCE_DIR) / "data" / "scenes";
  std::vector<std::filesystem::path> files;
  for (const auto& folder : {root, root / "hard"})
    for (const auto& entry : std::filesystem::directory_iterator(folder))
      if (entry.path().extension() == ".json") files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  return files;
}

TEST(VolumeWorkspace, BundledScenes_EqualTheCpuVolumeWithItsCertificates) {
  const std::vector<std::filesystem::path> scenes = bundled_scenes();
  ASSERT_GE(scenes.size(), 30u) << "data/scenes and data/scenes/hard";
  VolumeWorkspace ws;  // one workspace for every scene: set_soup replaces the soup
  std::size_t volumes = 0;
  for (const std::filesystem::path& file : scenes) {
    const Scene scene = load_scene_or_mesh(file);
    const Soup casters = merged_casters(scene);
    if (casters.triangles.empty()) continue;
    // What pipeline/method_inputs.cpp prepares for cpu, and what certify certifies.
    const CanonicalSoup canonical = canonical_soup(casters);
    const EdgeTable table = build_edge_table(canonical.soup);
    const Soup rounded = float_rounded(canonical.soup);
    ws.set_soup(std::span<const double>(double_positions(casters)), indices_of(casters));
    EXPECT_EQ(std::vector<std::uint32_t>(ws.input_vertex_ids().begin(), ws.input_vertex_ids().end()),
              canonical.canonical_id)
        << file;
    const bool large = casters.triangles.size() > 200'000;  // sphere_grid_1m: equality and closure only
    for (std::size_t k = 0; k < scene.lights.size(); ++k) {
      const std::string what = file.filename().string() + " light " + std::to_string(k);
      const Light& light = scene.lights[k];
      const Output out = generate(ws, light);
      const HomogeneousMesh library = mesh_of(out);
      expect_same_mesh(library, cpu_volume_mesh(canonical.soup, table, light), what);
      ++volumes;

      const VolumeClosure closure = certify_volume_closure(library);
      EXPECT_TRUE(closure.certificate.closed) << what << ": " << closure.certificate.unbalanced.size() << " unbalanced";
      if (large) continue;

      // The chain of the cpu volume, as exact/cpu_volume.cpp builds it, and the one read back
      // from the library's triangles: the same faces, and the same count certificate.
      const Light rounded_light = float_rounded(light);
      const ShadowVolumeChain reference =
          assemble_chain(rounded, table, exact_multiplicities(rounded, table, rounded_light), rounded_light);
      const ShadowVolumeChain read_back = chain_read_back(library, rounded, rounded_light);
      EXPECT_EQ(read_back.cap_triangles, reference.cap_triangles) << what;
      EXPECT_EQ(read_back.cap_sign, reference.cap_sign) << what;
      EXPECT_EQ(read_back.side_edges, reference.side_edges) << what;
      EXPECT_EQ(read_back.side_multiplicity, reference.side_multiplicity) << what;
      EXPECT_TRUE(certify_closure(reference).closed) << what;
      const CountCertificate expected = certify_counts(rounded, rounded_light, reference, small_sampling());
      const CountCertificate got = certify_counts(rounded, rounded_light, read_back, small_sampling());
      EXPECT_GT(got.checks, 0u) << what;
      EXPECT_EQ(got.failures, 0u) << what;
      EXPECT_EQ(got.checks, expected.checks) << what;
      EXPECT_EQ(got.failures, expected.failures) << what;
      EXPECT_EQ(got.redrawn, expected.redrawn) << what;
      EXPECT_EQ(got.skipped, expected.skipped) << what;
    }
  }
  EXPECT_GE(volumes, 30u);
}

// A caster over a floor, for the tests below: every coordinate a small dyadic, exact in float.
Soup box_over_floor() {
  Soup soup = box({-1.0, 1.0, -1.0}, {1.0, 2.5, 1.0});
  Soup floor = box({-8.0, -0.5, -8.0}, {8.0, 0.0, 8.0});
  append_soup(soup, floor);
  soup.normals.clear();
  return soup;
}

const Light kPoint{{0.75, 6.0, 0.5, 1.0}};
const Light kSun{{0.25, 1.0, 0.125, 0.0}};

TEST(VolumeWorkspace, FloatAndDoubleOfTheSameValues_SameVolume) {
  const Soup soup = sphere_grid(5000);  // float-rounded below, so both inputs hold the same values
  const Soup exact_in_float = float_rounded(soup);
  for (const Light& light : {kPoint, kSun}) {
    VolumeWorkspace from_float, from_double;
    from_float.set_soup(std::span<const float>(float_positions(exact_in_float)), indices_of(exact_in_float));
    from_double.set_soup(std::span<const double>(double_positions(exact_in_float)), indices_of(exact_in_float));
    const Output a = generate(from_float, light);
    const Output b = generate(from_double, light);
    ASSERT_GT(a.info.written.triangles, 0u);
    EXPECT_EQ(a.positions, b.positions);
    EXPECT_EQ(a.indices, b.indices);
    EXPECT_TRUE(std::equal(from_float.input_vertex_ids().begin(), from_float.input_vertex_ids().end(),
                           from_double.input_vertex_ids().begin(), from_double.input_vertex_ids().end()));
  }
}

// The substring check of an exception's message: the function's name must be in it.
template <typename F>
void expect_throw_naming(F&& f, const std::string& function) {
  try {
    f();
    ADD_FAILURE() << "expected std::invalid_argument naming " << function;
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find(function), std::string::npos) << e.what();
  }
}

TEST(VolumeWorkspace, TooSmallSpans_ThrowNamingTheFunction) {
  const Soup soup = box_over_floor();
  VolumeWorkspace ws;
  ws.set_soup(std::span<const double>(double_positions(soup)), indices_of(soup));
  const VolumeSizes need = ws.build(kPoint);
  ASSERT_GT(need.triangles, 0u);
  std::vector<float> positions(need.position_floats());
  std::vector<std::uint32_t> indices(need.index_count());
  std::vector<float> short_positions(need.position_floats() - 1);
  std::vector<std::uint32_t> short_indices(need.index_count() - 1);
  expect_throw_naming([&] { (void)ws.write(short_positions, indices); }, "VolumeWorkspace::write");
  expect_throw_naming([&] { (void)ws.write(positions, short_indices); }, "VolumeWorkspace::write");
  expect_throw_naming([&] { (void)ws.generate(kSun, std::span<float>{}, std::span<std::uint32_t>{}); },
                      "VolumeWorkspace::generate");
  // generate built the sun's volume all the same: sizes() says how much, write() writes it.
  const VolumeSizes sun = ws.sizes();
  std::vector<float> sun_positions(sun.position_floats());
  std::vector<std::uint32_t> sun_indices(sun.index_count());
  EXPECT_EQ(ws.write(sun_positions, sun_indices).written, sun);
  // Larger spans: only the first entries are written, the rest left as they were.
  std::vector<float> long_positions(need.position_floats() + 8, -7.0f);
  std::vector<std::uint32_t> long_indices(need.index_count() + 6, 99u);
  (void)ws.generate(kPoint, long_positions, long_indices);
  EXPECT_EQ(long_positions.back(), -7.0f);
  EXPECT_EQ(long_indices.back(), 99u);
}

TEST(VolumeWorkspace, BadInput_ThrowsNamingTheFunction) {
  const Soup soup = box_over_floor();
  std::vector<double> positions = double_positions(soup);
  std::vector<std::uint32_t> indices = indices_of(soup);
  VolumeWorkspace ws;
  expect_throw_naming([&] { (void)ws.build(kPoint); }, "VolumeWorkspace::build");  // no soup yet

  std::vector<double> nan = positions;
  nan[7] = std::numeric_limits<double>::quiet_NaN();
  expect_throw_naming([&] { ws.set_soup(std::span<const double>(nan), indices); }, "VolumeWorkspace::set_soup");
  std::vector<float> float_inf = float_positions(soup);
  float_inf[0] = std::numeric_limits<float>::infinity();
  expect_throw_naming([&] { ws.set_soup(std::span<const float>(float_inf), indices); }, "VolumeWorkspace::set_soup");
  std::vector<double> huge = positions;
  huge[4] = 1e39;  // finite in double, infinite once rounded to float
  expect_throw_naming([&] { ws.set_soup(std::span<const double>(huge), indices); }, "VolumeWorkspace::set_soup");
  std::vector<std::uint32_t> out_of_range = indices;
  out_of_range[5] = static_cast<std::uint32_t>(soup.vertices.size());
  expect_throw_naming([&] { ws.set_soup(std::span<const double>(positions), out_of_range); },
                      "VolumeWorkspace::set_soup");
  expect_throw_naming([&] { ws.set_soup(std::span<const double>(positions).first(positions.size() - 1), indices); },
                      "VolumeWorkspace::set_soup");
  expect_throw_naming([&] { ws.set_soup(std::span<const double>(positions), std::span(indices).first(4)); },
                      "VolumeWorkspace::set_soup");
  // A failed set_soup leaves no soup.
  expect_throw_naming([&] { (void)ws.build(kPoint); }, "VolumeWorkspace::build");

  ws.set_soup(std::span<const double>(positions), indices);
  std::vector<float> p(1);
  std::vector<std::uint32_t> i(1);
  expect_throw_naming([&] { (void)ws.write(p, i); }, "VolumeWorkspace::write");  // nothing built yet
  expect_throw_naming([&] { (void)ws.build(Light{{std::nan(""), 1.0, 0.0, 1.0}}); }, "VolumeWorkspace::build");
  expect_throw_naming([&] { (void)ws.build(Light{{0.0, 1.0, 0.0, 0.5}}); }, "VolumeWorkspace::build");
  expect_throw_naming([&] { (void)ws.build(Light{{0.0, 0.0, 0.0, 0.0}}); }, "VolumeWorkspace::build");
  expect_throw_naming([&] { (void)ws.build(Light{{1e-50, 0.0, 0.0, 0.0}}); }, "VolumeWorkspace::build");
  expect_throw_naming([&] { (void)ws.build(Light{{1e39, 1.0, 0.0, 1.0}}); }, "VolumeWorkspace::build");
  expect_throw_naming([&] { (void)ws.generate(Light{{0.0, 0.0, 0.0, 0.0}}, p, i); }, "VolumeWorkspace::generate");
  VolumeView degenerate;
  degenerate.tip = ZPassTip{};  // every point at the origin: no tetrahedron
  expect_throw_naming([&] { (void)generate(ws, kPoint, &degenerate); }, "VolumeWorkspace::write");
}

TEST(VolumeWorkspace, TwoThreadsOnTwoSoups_SameAsAlone) {
  const Soup first = sphere_grid(20000);
  const Soup second = box_over_floor();
  const std::vector<Light> lights{kPoint, kSun, Light{{-3.0, 4.0, 2.0, 1.0}}};
  auto run = [&lights](const Soup& soup, std::vector<Output>& results, int rounds) {
    VolumeWorkspace ws;
    ws.set_soup(std::span<const double>(double_positions(soup)), indices_of(soup));
    results.clear();
    for (int r = 0; r < rounds; ++r)
      for (const Light& light : lights) results.push_back(generate(ws, light));
  };
  std::vector<Output> alone_first, alone_second;
  run(first, alone_first, 1);
  run(second, alone_second, 1);
  std::vector<Output> together_first, together_second;
  std::thread a([&] { run(first, together_first, 3); });
  std::thread b([&] { run(second, together_second, 40); });
  a.join();
  b.join();
  ASSERT_EQ(together_first.size(), 3 * lights.size());
  ASSERT_EQ(together_second.size(), 40 * lights.size());
  for (std::size_t i = 0; i < together_first.size(); ++i) {
    EXPECT_EQ(together_first[i].positions, alone_first[i % lights.size()].positions) << i;
    EXPECT_EQ(together_first[i].indices, alone_first[i % lights.size()].indices) << i;
  }
  for (std::size_t i = 0; i < together_second.size(); ++i) {
    EXPECT_EQ(together_second[i].positions, alone_second[i % lights.size()].positions) << i;
    EXPECT_EQ(together_second[i].indices, alone_second[i % lights.size()].indices) << i;
  }
}

// Vertex labels and face orientation are not geometry: the welded, ordered soup is the same,
// and a reversed triangle's cap s(t) t is the same oriented face (its s changes sign), its
// edges' multiplicities unchanged. So the written volume is the same, bit for bit.
TEST(VolumeWorkspace, RelabelledVerticesAndReversedFaces_SameVolume) {
  const Soup soup = box_over_floor();
  std::vector<std::uint32_t> order(soup.vertices.size());
  std::iota(order.begin(), order.end(), 0u);
  std::mt19937 rng(3);
  std::shuffle(order.begin(), order.end(), rng);  // vertex i becomes vertex order[i]
  Soup relabelled = soup;
  for (std::size_t i = 0; i < order.size(); ++i) relabelled.vertices[order[i]] = soup.vertices[i];
  for (Triangle& t : relabelled.triangles)
    for (std::uint32_t& v : t) v = order[v];
  Soup reversed = soup;
  for (Triangle& t : reversed.triangles) std::swap(t[1], t[2]);
  for (const Light& light : {kPoint, kSun}) {
    VolumeWorkspace a, b, c;
    a.set_soup(std::span<const double>(double_positions(soup)), indices_of(soup));
    b.set_soup(std::span<const double>(double_positions(relabelled)), indices_of(relabelled));
    c.set_soup(std::span<const double>(double_positions(reversed)), indices_of(reversed));
    const Output oa = generate(a, light), ob = generate(b, light), oc = generate(c, light);
    ASSERT_GT(oa.info.written.triangles, 0u);
    EXPECT_EQ(oa.positions, ob.positions);
    EXPECT_EQ(oa.indices, ob.indices);
    EXPECT_EQ(oa.positions, oc.positions);
    EXPECT_EQ(oa.indices, oc.indices);
    for (std::size_t i = 0; i < order.size(); ++i) EXPECT_EQ(b.input_vertex_ids()[order[i]], a.input_vertex_ids()[i]);
  }
}

// Moving soup and point light by one vector (exact in float here) moves the finite vertices by
// it and leaves the directions x - l, the order and the triangles as they were.
TEST(VolumeWorkspace, TranslatedSoupAndLight_TranslatedVolume) {
  const Soup soup = box_over_floor();
  const Vec3 shift{8.0, -4.0, 2.5};
  Soup moved = soup;
  for (Vec3& v : moved.vertices)
    for (std::size_t k = 0; k < 3; ++k) v[k] += shift[k];
  const Light moved_point{{kPoint.position[0] + shift[0], kPoint.position[1] + shift[1],
                           kPoint.position[2] + shift[2], 1.0}};
  VolumeWorkspace a, b;
  a.set_soup(std::span<const double>(double_positions(soup)), indices_of(soup));
  b.set_soup(std::span<const double>(double_positions(moved)), indices_of(moved));
  for (const auto& [light, light_moved] : {std::pair{kPoint, moved_point}, std::pair{kSun, kSun}}) {
    const Output oa = generate(a, light), ob = generate(b, light_moved);
    ASSERT_EQ(oa.positions.size(), ob.positions.size());
    EXPECT_EQ(oa.indices, ob.indices);
    for (std::size_t v = 0; v < oa.positions.size() / 4; ++v) {
      const bool finite = oa.positions[4 * v + 3] == 1.0f;
      EXPECT_EQ(ob.positions[4 * v + 3], oa.positions[4 * v + 3]);
      for (std::size_t k = 0; k < 3; ++k)
        EXPECT_EQ(ob.positions[4 * v + k], oa.positions[4 * v + k] + (finite ? static_cast<float>(shift[k]) : 0.0f))
            << "vertex " << v;
    }
    for (std::size_t k = 0; k < 3; ++k) {
      EXPECT_EQ(ob.info.finite_min[k], oa.info.finite_min[k] + static_cast<float>(shift[k]));
      EXPECT_EQ(ob.info.finite_max[k], oa.info.finite_max[k] + static_cast<float>(shift[k]));
    }
  }
}

// GL's perspective projection (column-major), camera at the origin looking down -z.
std::array<double, 16> perspective(double near, double far) {
  std::array<double, 16> m{};
  m[0] = 1.0;
  m[5] = 1.0;
  m[10] = -(far + near) / (far - near);
  m[11] = -1.0;
  m[14] = -2.0 * far * near / (far - near);
  return m;
}

TEST(VolumeWorkspace, BoundsAndDepth_CoverEveryVertexOrAreRefused) {
  // One triangle at z = -5 facing the camera; a point light between them casts away from the
  // camera (every vertex, at infinity too, has clip w > 0), one beyond it casts towards it.
  Soup soup;
  soup.vertices = {{-1.0, -1.0, -5.0}, {1.0, -1.0, -5.0}, {0.0, 1.0, -5.0}};
  soup.triangles = {{0, 1, 2}};
  VolumeWorkspace ws;
  ws.set_soup(std::span<const double>(double_positions(soup)), indices_of(soup));
  VolumeView view;
  view.view_projection = perspective(0.5, 100.0);

  const Output away = generate(ws, Light{{0.0, 0.0, -1.0, 1.0}}, &view);
  EXPECT_FALSE(away.info.empty);
  EXPECT_TRUE(away.info.reaches_infinity);
  EXPECT_EQ(away.info.finite_min, (std::array<float, 3>{-1.0f, -1.0f, -5.0f}));
  EXPECT_EQ(away.info.finite_max, (std::array<float, 3>{1.0f, 1.0f, -5.0f}));
  ASSERT_TRUE(away.info.depth_bounded);
  bool min_met = false, max_met = false;
  for (const auto& t : mesh_of(away).triangles)
    for (const std::uint32_t id : t) {
      const float* p = &away.positions[4 * id];
      const double w = -p[2];  // row 3 of the projection: -z
      const double z = view.view_projection[10] * p[2] + view.view_projection[14] * p[3];
      EXPECT_GE(z / w, away.info.depth_min);
      EXPECT_LE(z / w, away.info.depth_max);
      min_met = min_met || z / w == away.info.depth_min;
      max_met = max_met || z / w == away.info.depth_max;
    }
  EXPECT_TRUE(min_met && max_met);
  // The points at infinity lie beyond the finite far plane: depth -m[10] = (f + n) / (f - n) > 1
  // (a host draws them with depth clamp).
  EXPECT_DOUBLE_EQ(away.info.depth_max, -view.view_projection[10]);
  EXPECT_LT(away.info.depth_min, 1.0);

  const Output towards = generate(ws, Light{{0.0, 0.0, -20.0, 1.0}}, &view);
  EXPECT_FALSE(towards.info.empty);
  EXPECT_FALSE(towards.info.depth_bounded);  // its sides pass the eye plane

  const Output without_view = generate(ws, Light{{0.0, 0.0, -1.0, 1.0}});
  EXPECT_FALSE(without_view.info.depth_bounded);
  EXPECT_EQ(without_view.info.stencil, VolumeStencil::zfail_needed);
  EXPECT_EQ(without_view.info.zpass, ZPassReason::not_asked);

  // A light in the triangle's plane: it casts nothing, the volume has no triangle.
  const Output edge_on = generate(ws, Light{{3.0, 0.0, -5.0, 1.0}}, &view);
  EXPECT_TRUE(edge_on.info.empty);
  EXPECT_EQ(edge_on.info.written.triangles, 0u);
  EXPECT_FALSE(edge_on.info.reaches_infinity);
}

// A small near tip around `eye` looking down -y (the corners below it, cyclic).
ZPassTip tip_at(const Vec3& eye) {
  ZPassTip tip;
  tip.apex = eye;
  const double d = 0.01;
  tip.corners = {Vec3{eye[0] - d, eye[1] - d, eye[2] - d}, Vec3{eye[0] + d, eye[1] - d, eye[2] - d},
                 Vec3{eye[0] + d, eye[1] - d, eye[2] + d}, Vec3{eye[0] - d, eye[1] - d, eye[2] + d}};
  return tip;
}

TEST(VolumeWorkspace, ZPassFlag_ProvenOutsideTheVolumesZFailInside) {
  const Soup soup = box_over_floor();
  VolumeWorkspace ws;
  ws.set_soup(std::span<const double>(double_positions(soup)), indices_of(soup));
  VolumeView view;
  view.tip = tip_at({5.0, 3.0, 5.0});  // beside the box, above the floor, lit
  const Output lit = generate(ws, kPoint, &view);
  EXPECT_EQ(lit.info.zpass, ZPassReason::proven);
  EXPECT_EQ(lit.info.stencil, VolumeStencil::zpass_proven);
  view.tip = tip_at({0.5, 0.5, 0.5});  // under the box, in its shadow
  const Output shadowed = generate(ws, kPoint, &view);
  EXPECT_EQ(shadowed.info.zpass, ZPassReason::camera_in_volume);
  EXPECT_EQ(shadowed.info.stencil, VolumeStencil::zfail_needed);
}

// After set_soup, a build allocates no array proportional to the soup: the workspace's arrays
// are refilled within their capacity. The same volume built by the value function allocates
// at least its own size, which shows the counter sees the allocations it should.
TEST(VolumeWorkspace, BuildAfterSetSoup_AllocatesNoArrayOfTheSoupsSize) {
  const Soup soup = sphere_grid(100'000);
  VolumeWorkspace ws;
  ws.set_soup(std::span<const double>(double_positions(soup)), indices_of(soup));
  for (const Light& light : {kPoint, kSun, Light{{-2.0, 9.0, 4.0, 1.0}}}) {
    const std::size_t bytes_before = g_new_bytes, calls_before = g_new_calls;
    const VolumeSizes sizes = ws.build(light);
    const std::size_t bytes = g_new_bytes - bytes_before, calls = g_new_calls - calls_before;
    const std::size_t volume_bytes = sizes.position_floats() * sizeof(float) + sizes.index_count() * 4;
    ASSERT_GT(volume_bytes, std::size_t{1} << 20);
    EXPECT_LT(bytes, std::size_t{64} << 10) << calls << " allocations for a volume of " << volume_bytes << " bytes";
  }
  const CanonicalSoup canonical = canonical_soup(soup);
  const EdgeTable table = build_edge_table(canonical.soup);
  const std::size_t bytes_before = g_new_bytes;
  const HomogeneousMesh mesh = cpu_volume_mesh(canonical.soup, table, kPoint);
  EXPECT_GE(g_new_bytes - bytes_before, mesh.triangles.size() * sizeof(mesh.triangles[0]));
}

}  // namespace
}  // namespace shadowcert
