#pragma once
// The view of a campaign case for the GL methods (`shadowcert fuzz --gl`, docs/campaign.md): what
// the camera sees when a case is rendered and compared with the exact image (docs/definitions.md#pixel-protocol).
// One rule for every case, so that a case's picture is a function of the case alone:
//
//   1. Unit frame. The case's frame p -> 2^e p + (o, o, o) (campaign/random_soup.h) is undone:
//      p -> 2^-e (p - o), for the soup and a point light (a direction is left as is), when
//      that is exact, i.e. when framing the result again gives the case back bit for bit.
//      It nearly always is: p - o by Sterbenz's lemma (for o = 1e6 every framed coordinate
//      lies within a few units of 1e6, since e <= 0 there) and the power of two unless a
//      coordinate underflows: a light moved one ulp off 0 (a subnormal) in a frame with
//      e > 0. Such a case is rendered as generated. The exact answers (signs, counts,
//      closure) are invariant under an exact map, while gpu/'s fixed near plane (0.01) and
//      its world-space float view transform are documented limits at scales 1e-6 and
//      offsets 1e6 (docs/diff.md, "Findings and limits") that would fail every case of
//      those frames without telling anything about the method.
//   2. A floor under the soup, to receive the shadows: a square of two triangles facing +y,
//      kFloorDrop box radii below the lowest vertex, kFloorHalfSide radii from the box's
//      centre in x and z; its corners are rounded to float, so that the GPU receives it
//      exactly.
//   3. The camera looks at the centre c of the soup's bounding box from direction
//      kViewDirection (elevated, parallel to no axis and to no coordinate plane, so that no
//      face of an axis-aligned soup is seen edge-on), at the distance where the box's bounding
//      sphere (radius r, at least kMinViewRadius) fits the vertical field of view with margin
//      kViewMargin: |eye - c| = kViewMargin * r / sin(fov_y / 2); up = +y.
#include <cstdint>

#include "core/camera.h"
#include "core/light.h"
#include "core/soup.h"
#include "campaign/random_soup.h"

namespace shadowcert {

// (12, 15, 16) / 25 is a unit vector: 144 + 225 + 256 = 625.
inline constexpr Vec3 kViewDirection{12.0 / 25.0, 15.0 / 25.0, 16.0 / 25.0};
inline constexpr double kCampaignViewFovDegrees = 45.0;
// The bounding sphere fills 1 / kViewMargin of the half height: room for the shadows around it.
inline constexpr double kViewMargin = 1.25;
// A soup whose vertices all coincide still gets a camera at a positive distance.
inline constexpr double kMinViewRadius = 1.0 / 64.0;
inline constexpr double kFloorDrop = 0.5;
inline constexpr double kFloorHalfSide = 3.0;

struct CampaignView {
  Soup soup;    // the case's soup in its unit frame (as generated when not unframed)
  Light light;  // the case's light in its unit frame (likewise)
  bool unframed = false;  // the frame was undone (false: not exact, or the unit frame already)
  Soup floor;   // two triangles facing +y under the soup
  Camera camera;
};

// The inverse of the case's frame (step 1 above), vertex by vertex and for a point light,
// rounded where it is not exact.
[[nodiscard]] Soup unframed(const Soup& soup, const SoupFrame& frame);
[[nodiscard]] Light unframed(const Light& light, const SoupFrame& frame);
// Whether framing the unframed soup and light again gives the case's bit for bit: then the
// map lost nothing and every exact answer is the case's.
[[nodiscard]] bool unframes_exactly(const CampaignCase& campaign_case);

// The floor and camera of steps 2 and 3 for `soup` (already in its unit frame; may be empty:
// then the box is the origin). width, height >= 1.
[[nodiscard]] Soup campaign_view_floor(const Soup& soup);
[[nodiscard]] Camera campaign_view_camera(const Soup& soup, std::uint32_t width, std::uint32_t height);

// All three steps for a case. Throws std::invalid_argument("campaign_view: ...") for an empty
// image size.
[[nodiscard]] CampaignView campaign_view(const CampaignCase& campaign_case, std::uint32_t width, std::uint32_t height);

}  // namespace shadowcert
