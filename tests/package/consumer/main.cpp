// The package test's consumer (tests/package/package_test.cmake): one computation of each
// exported library, checked against a known answer; exit 1 on a wrong one. Its headers are
// the installed ones (include/shadowcert), included as in the source tree. Nothing here needs
// a GL context: gpu/ is exercised through its pure functions (a matrix, a PNG encoding), which
// still link the whole export (glm, libpng; epoxy and EGL on the link line).
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <span>
#include <vector>

#include "core/camera.h"
#include "core/light.h"
#include "core/soup.h"
#include "exact/edge_multiplicity.h"
#include "gpu/camera_transform.h"
#include "gpu/image.h"
#include "gpu/png_image.h"
#include "scene/canonical_soup.h"
#include "scene/edge_table.h"
#include "volume/volume_workspace.h"

namespace {

int failures = 0;

void check(bool ok, const char* what) {
  std::printf("%s: %s\n", ok ? "ok" : "FAILED", what);
  failures += ok ? 0 : 1;
}

}  // namespace

int main() {
  using namespace shadowcert;

  // exact (CGAL inside): a lone triangle facing a point light, docs/definitions.md#counts's sign
  // convention (tests/exact/edge_multiplicity_test.cpp): edges (0, 1) and (1, 2) get -1, (0, 2)
  // gets +1, and the triangle's cap sign is positive.
  Soup soup;
  soup.vertices = {{0.0, 0.0, 0.0}, {1.0, 0.0, 0.0}, {1.0, 1.0, 0.0}};
  soup.triangles = {{0, 1, 2}};
  const CanonicalSoup canonical = canonical_soup(soup);
  const EdgeTable table = build_edge_table(canonical.soup);
  const EdgeMultiplicities m = exact_multiplicities(canonical.soup, table, Light{{0.5, 0.25, 3.0, 1.0}});
  check(table.size() == 3, "the edge table has three edges");
  check(m.multiplicity == std::vector<std::int32_t>{-1, 1, -1}, "exact multiplicities of (0,1), (0,2), (1,2) are -1, 1, -1");
  check(m.triangle_sign == std::vector<Sign>{Sign::positive}, "the triangle's cap sign is positive");

  // volume (exact inside, no GL): the same triangle as the caller's float arrays. Its volume
  // for a point light above it: 3 vertices and their 3 points at infinity, front and back cap
  // and one side quad (two triangles) per edge, 8 triangles, written into the caller's buffers.
  VolumeWorkspace workspace;
  const std::vector<float> positions{0.0f, 0.0f, 0.0f, 1.0f, 0.0f, 0.0f, 1.0f, 1.0f, 0.0f};
  const std::vector<std::uint32_t> indices{0, 1, 2};
  workspace.set_soup(std::span<const float>(positions), indices);
  const VolumeSizes sizes = workspace.build(Light{{0.5, 0.25, 3.0, 1.0}});
  std::vector<float> volume_positions(sizes.position_floats());
  std::vector<std::uint32_t> volume_indices(sizes.index_count());
  const VolumeInfo info = workspace.write(volume_positions, volume_indices);
  check(sizes.vertices == 6 && sizes.triangles == 8, "the triangle's volume has 6 vertices and 8 triangles");
  check(info.written == sizes && info.reaches_infinity && !info.empty && volume_positions[3] == 1.0f &&
            volume_positions[4 * 3 + 3] == 0.0f,
        "write() wrote it: finite vertices first (w = 1), then their points at infinity (w = 0)");

  // gpu (glm public): the camera's target projects to the image's centre.
  const Camera camera;  // 1024 x 768, looking at the origin
  const glm::dvec2 centre = gpu::project_to_image(camera, camera.target);
  check(std::abs(centre.x - 512.0) < 1e-9 && std::abs(centre.y - 384.0) < 1e-9,
        "project_to_image(target) is the image centre (512, 384)");

  // gpu (libpng private): a 2 x 2 gray image encodes to bytes with PNG's signature.
  gpu::GrayImage image(2, 2);
  const std::vector<std::uint8_t> png = gpu::encode_png(image);
  check(png.size() > 8 && png[0] == 0x89 && png[1] == 'P' && png[2] == 'N' && png[3] == 'G',
        "encode_png writes a PNG");

  std::printf("%s\n", failures == 0 ? "consumer: all checks passed" : "consumer: some checks FAILED");
  return failures == 0 ? 0 : 1;
}
