// exact/volume_closure.h: the closure of a volume as drawn, on a closed tetrahedron with a
// vertex at infinity, without one face, and read back as the GPU emits it (three fresh
// vertices per triangle, signed zeros), which welding must make closed again.
#include "exact/volume_closure.h"

#include <gtest/gtest.h>

#include <cstdint>

namespace shadowcert {
namespace {

// A tetrahedron with outward faces: the smallest closed volume; vertex 3 is at infinity so
// w = 0 vertices take part like any other.
HomogeneousMesh tetrahedron() {
  HomogeneousMesh v;
  v.vertices = {{0, 0, 0, 1}, {1, 0, 0, 1}, {0, 1, 0, 1}, {0.25f, 0.25f, 1, 0}};
  v.triangles = {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {2, 0, 3}};
  return v;
}

TEST(VolumeClosure, ClosedTetrahedron_IsClosed) {
  const VolumeClosure result = certify_volume_closure(tetrahedron());
  EXPECT_TRUE(result.certificate.closed);
  EXPECT_TRUE(result.certificate.unbalanced.empty());
}

TEST(VolumeClosure, TetrahedronMissingAFace_HasThreeUnbalancedEdges) {
  HomogeneousMesh v = tetrahedron();
  v.triangles.pop_back();
  const VolumeClosure result = certify_volume_closure(v);
  EXPECT_FALSE(result.certificate.closed);
  EXPECT_EQ(result.certificate.unbalanced.size(), 3u);
}

TEST(VolumeClosure, TriangleSoupOfAClosedVolume_IsClosedAfterWelding) {
  // As the GPU reads back: three fresh vertices per triangle, some zeros negative.
  HomogeneousMesh soup;
  const HomogeneousMesh tet = tetrahedron();
  for (const auto& t : tet.triangles) {
    const auto first = static_cast<std::uint32_t>(soup.vertices.size());
    for (std::uint32_t id : t) {
      auto p = tet.vertices[id];
      if (first % 2 == 1)
        for (float& x : p)
          if (x == 0.0f) x = -0.0f;
      soup.vertices.push_back(p);
    }
    soup.triangles.push_back({first, first + 1, first + 2});
  }
  const VolumeClosure result = certify_volume_closure(soup);
  EXPECT_TRUE(result.certificate.closed);
  EXPECT_EQ(result.welded.vertices.size(), 4u);
}

}  // namespace
}  // namespace shadowcert
