#include "volume/volume_workspace.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "core/float_rounding.h"
#include "core/huge_page_advice.h"
#include "core/soup.h"
#include "exact/cpu_volume.h"
#include "exact/zpass_proof.h"
#include "scene/canonical_soup.h"
#include "scene/edge_table.h"

namespace shadowcert {
namespace {

// The smallest magnitude that rounds to an infinite float: 2^128 - 2^103, half a unit in the
// last place above FLT_MAX (a tie, which goes to the even 2^128). Below it, float_rounded(x)
// is finite; the comparison is exact, and no out-of-range double is ever cast to float.
constexpr double kFloatOverflow = 0x1.ffffffp127;

[[noreturn]] void fail(const char* function, const std::string& what) {
  throw std::invalid_argument(std::string(function) + ": " + what);
}

template <typename Real>
Soup checked_soup(std::span<const Real> positions, std::span<const std::uint32_t> indices) {
  constexpr const char* kFunction = "VolumeWorkspace::set_soup";
  if (positions.size() % 3 != 0)
    fail(kFunction, "positions hold " + std::to_string(positions.size()) + " values, not 3 per vertex");
  if (indices.size() % 3 != 0)
    fail(kFunction, "indices hold " + std::to_string(indices.size()) + " values, not 3 per triangle");
  const std::size_t n = positions.size() / 3;
  // The chain's far ids n + i and the closure's packed keys need n < 2^31 (shadow_volume_chain.h).
  if (n >= (std::size_t{1} << 31)) fail(kFunction, std::to_string(n) + " vertices: at most 2^31 - 1");
  Soup soup;
  soup.vertices.resize(n);
  for (std::size_t i = 0; i < positions.size(); ++i) {
    const double x = positions[i];
    if (!std::isfinite(x)) fail(kFunction, "vertex " + std::to_string(i / 3) + " has a non-finite coordinate");
    if (!(std::abs(x) < kFloatOverflow))
      fail(kFunction, "vertex " + std::to_string(i / 3) + " has a coordinate beyond float's range");
    soup.vertices[i / 3][i % 3] = x;
  }
  soup.triangles.resize(indices.size() / 3);
  for (std::size_t i = 0; i < indices.size(); ++i) {
    if (indices[i] >= n)
      fail(kFunction, "triangle " + std::to_string(i / 3) + " has index " + std::to_string(indices[i]) +
                          ", but there are " + std::to_string(n) + " vertices");
    soup.triangles[i / 3][i % 3] = indices[i];
  }
  return soup;
}

// Entry (row r, column c) of a column-major 4x4 matrix times (x, y, z, w).
std::array<double, 4> transform(const std::array<double, 16>& m, const std::array<float, 4>& p) {
  std::array<double, 4> out{};
  for (std::size_t r = 0; r < 4; ++r)
    out[r] = m[r] * p[0] + m[4 + r] * p[1] + m[8 + r] * p[2] + m[12 + r] * p[3];
  return out;
}

ZPassReason reason_of(ZPassVerdict verdict) {
  switch (verdict) {
    case ZPassVerdict::proven:
      return ZPassReason::proven;
    case ZPassVerdict::camera_in_volume:
      return ZPassReason::camera_in_volume;
    case ZPassVerdict::face_meets_tip:
      return ZPassReason::face_meets_tip;
    case ZPassVerdict::count_undefined:
      return ZPassReason::count_undefined;
  }
  return ZPassReason::count_undefined;
}

}  // namespace

struct VolumeWorkspace::Impl {
  bool has_soup = false;
  CanonicalSoup canonical;  // the caller's soup welded and ordered; canonical_id maps its vertices
  EdgeTable table;          // of canonical.soup
  Soup rounded;             // canonical.soup rounded to float once: what every build reads
  CpuVolumeBuffers buffers;  // refilled by every build within its capacity
  bool built = false;
  Light light;  // the last build's light, as given (rounded_cpu_volume rounds it)

  void set(Soup soup) {
    has_soup = false;
    built = false;
    canonical = canonical_soup(soup);
    table = build_edge_table(canonical.soup);
    rounded = float_rounded(canonical.soup);
    reserve();
    has_soup = true;
  }

  // Every array of a build, sized for the largest volume of this soup without split far edges:
  // a point light's chain has at most 2 caps per triangle and one quad per edge entry (|m| of
  // an edge is at most its number of entries), its mesh 2n vertices and 2 triangles per quad;
  // a directional light's at most one cap per triangle and one side triangle per entry. The
  // storage is reserved, not touched: the pages a build does not fill cost no memory.
  void reserve() {
    const std::size_t n = rounded.vertices.size(), t = rounded.triangles.size();
    const std::size_t edges = table.size(), entries = table.opposite_vertex.size();
    reserve_huge(buffers.multiplicities.multiplicity, edges);
    reserve_huge(buffers.multiplicities.triangle_sign, t);
    ShadowVolumeChain& c = buffers.chain;
    reserve_huge(c.triangles, std::max(2 * t, t + entries));
    reserve_huge(c.quads, entries);
    reserve_huge(c.side_edges, edges);
    reserve_huge(c.side_multiplicity, edges);
    reserve_huge(c.cap_triangles, t);
    reserve_huge(c.cap_sign, t);
    reserve_huge(buffers.mesh.vertices, 2 * n + 1);
    reserve_huge(buffers.mesh.triangles, 2 * t + 2 * entries);
  }

  VolumeSizes build(const char* function, const Light& l, VolumeMethod method) {
    if (!has_soup) fail(function, "no soup: call set_soup first");
    if (method != VolumeMethod::cpu) fail(function, "unknown volume method");
    require_defined(l, function);
    for (std::size_t k = 0; k < 3; ++k)
      if (!(std::abs(l.position[k]) < kFloatOverflow)) fail(function, "the light has a coordinate beyond float's range");
    const Light r = float_rounded(l);
    if (r.directional() && r.position[0] == 0.0 && r.position[1] == 0.0 && r.position[2] == 0.0)
      fail(function, "a directional light's direction rounds to (0, 0, 0) in float");
    built = false;
    rounded_cpu_volume(rounded, table, l, buffers);
    light = l;
    built = true;
    return sizes();
  }

  [[nodiscard]] VolumeSizes sizes() const {
    if (!built) return {};
    return {buffers.mesh.vertices.size(), buffers.mesh.triangles.size()};
  }

  VolumeInfo write(const char* function, std::span<float> positions, std::span<std::uint32_t> indices,
                   const VolumeView* view) const {
    if (!built) fail(function, "nothing built: call build first");
    const VolumeSizes need = sizes();
    if (positions.size() < need.position_floats())
      fail(function, "the positions span holds " + std::to_string(positions.size()) + " floats, the volume needs " +
                         std::to_string(need.position_floats()) + " (4 per vertex)");
    if (indices.size() < need.index_count())
      fail(function, "the indices span holds " + std::to_string(indices.size()) + " values, the volume needs " +
                         std::to_string(need.index_count()) + " (3 per triangle)");
    const HomogeneousMesh& mesh = buffers.mesh;
    static_assert(sizeof(mesh.vertices[0]) == 4 * sizeof(float) && sizeof(mesh.triangles[0]) == 3 * sizeof(std::uint32_t));
    if (need.vertices > 0) std::memcpy(positions.data(), mesh.vertices.data(), need.position_floats() * sizeof(float));
    if (need.triangles > 0) std::memcpy(indices.data(), mesh.triangles.data(), need.index_count() * sizeof(std::uint32_t));

    VolumeInfo info;
    info.written = need;
    info.empty = mesh.triangles.empty();
    info.depth_bounded = view != nullptr && !info.empty;
    bool first_finite = true, first_depth = true;
    double depth_min = 0.0, depth_max = 0.0;
    for (const auto& t : mesh.triangles)
      for (const std::uint32_t id : t) {
        const std::array<float, 4>& p = mesh.vertices[id];
        if (p[3] == 0.0f) {
          info.reaches_infinity = true;
        } else {
          for (std::size_t k = 0; k < 3; ++k) {
            info.finite_min[k] = first_finite ? p[k] : std::min(info.finite_min[k], p[k]);
            info.finite_max[k] = first_finite ? p[k] : std::max(info.finite_max[k], p[k]);
          }
          first_finite = false;
        }
        if (!info.depth_bounded) continue;
        const std::array<double, 4> clip = transform(view->view_projection, p);
        if (!(clip[3] > 0.0)) {
          info.depth_bounded = false;  // the volume reaches the eye plane or behind it
          continue;
        }
        const double depth = clip[2] / clip[3];
        depth_min = first_depth ? depth : std::min(depth_min, depth);
        depth_max = first_depth ? depth : std::max(depth_max, depth);
        first_depth = false;
      }
    if (info.depth_bounded) {
      info.depth_min = depth_min;
      info.depth_max = depth_max;
    }

    if (view != nullptr && view->tip) {
      ZPassProof proof;
      try {
        proof = prove_zpass(rounded, table, float_rounded(light), view->tip->apex, view->tip->corners);
      } catch (const std::invalid_argument& e) {
        fail(function, e.what());  // a degenerate or non-finite tip
      }
      info.zpass = reason_of(proof.verdict);
      info.stencil = proof.proven() ? VolumeStencil::zpass_proven : VolumeStencil::zfail_needed;
    }
    return info;
  }
};

VolumeWorkspace::VolumeWorkspace() : impl_(std::make_unique<Impl>()) {}
VolumeWorkspace::~VolumeWorkspace() = default;
VolumeWorkspace::VolumeWorkspace(VolumeWorkspace&&) noexcept = default;
VolumeWorkspace& VolumeWorkspace::operator=(VolumeWorkspace&&) noexcept = default;

void VolumeWorkspace::set_soup(std::span<const float> positions, std::span<const std::uint32_t> indices) {
  impl_->has_soup = false;
  impl_->built = false;
  impl_->set(checked_soup(positions, indices));
}

void VolumeWorkspace::set_soup(std::span<const double> positions, std::span<const std::uint32_t> indices) {
  impl_->has_soup = false;
  impl_->built = false;
  impl_->set(checked_soup(positions, indices));
}

VolumeSizes VolumeWorkspace::build(const Light& light, VolumeMethod method) {
  return impl_->build("VolumeWorkspace::build", light, method);
}

VolumeSizes VolumeWorkspace::sizes() const { return impl_->sizes(); }

VolumeInfo VolumeWorkspace::write(std::span<float> positions, std::span<std::uint32_t> indices,
                                  const VolumeView* view) const {
  return impl_->write("VolumeWorkspace::write", positions, indices, view);
}

VolumeInfo VolumeWorkspace::generate(const Light& light, std::span<float> positions, std::span<std::uint32_t> indices,
                                     const VolumeView* view, VolumeMethod method) {
  impl_->build("VolumeWorkspace::generate", light, method);
  return impl_->write("VolumeWorkspace::generate", positions, indices, view);
}

std::span<const std::uint32_t> VolumeWorkspace::input_vertex_ids() const {
  if (!impl_->has_soup) return {};
  return impl_->canonical.canonical_id;
}

}  // namespace shadowcert
