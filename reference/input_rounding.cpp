#include "reference/input_rounding.h"

#include "core/eye_frame.h"

#include <stdexcept>
#include <vector>

namespace shadowcert {
void mark_input_rounding(ExactImage& exact, const ExactImage& rounded) {
  if (exact.width != rounded.width || exact.height != rounded.height || exact.lights.size() != rounded.lights.size())
    throw std::invalid_argument("mark_input_rounding: the images differ in size or in lights");
  for (std::size_t l = 0; l < exact.lights.size(); ++l) {
    ExactLightImage& e = exact.lights[l];
    const ExactLightImage& r = rounded.lights[l];
    for (std::size_t p = 0; p < e.counts.size(); ++p)
      if (exact.hit_triangles[p] != rounded.hit_triangles[p] || e.counts[p] != r.counts[p] ||
          (r.ambiguity[p] != 0 && e.ambiguity[p] == 0))
        e.ambiguity[p] |= kInputRounding;
  }
}

ExactImage exact_image_of_float_input(const Soup& soup, std::span<const Light> lights, const Camera& camera,
                                      const ExactImageOptions& options, double* rounded_seconds) {
  ExactImage exact = exact_image(soup, lights, camera, options);
  // What GL receives (core/eye_frame.h): every position minus the eye, rounded once to float.
  const Vec3& eye = camera.eye;
  std::vector<Light> rounded_lights;
  for (const Light& light : lights) rounded_lights.push_back(float_rounded(relative_to(light, eye)));
  const ExactImage rounded =
      exact_image(float_rounded(relative_to(soup, eye)), rounded_lights, relative_to(camera, eye), options);
  mark_input_rounding(exact, rounded);
  if (rounded_seconds != nullptr) *rounded_seconds = rounded.stats.seconds;
  return exact;
}

}  // namespace shadowcert
