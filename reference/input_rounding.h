#pragma once
// A GL renderer receives the scene in float (vertex buffers, light uniforms): where rounding
// the input to float changes the exact answer, no float renderer can be held to the double
// one. The diff (`shadowcert diff`, docs/diff.md) therefore computes the exact image twice,
// of the scene as given and of the scene rounded to float, and calls a pixel ambiguous when the
// two disagree (docs/definitions.md#pixel-protocol extended to the input's own precision; docs/definitions.md#hard-cases' cases one double
// ulp off a plane are exactly such scenes: in float the light lies on the plane).
#include <span>

#include "core/float_rounding.h"
#include "core/light.h"
#include "core/soup.h"
#include "reference/exact_image.h"

namespace shadowcert {


// Marks, in every light's ambiguity of `exact`, the pixels where `rounded` (the exact image of
// the float-rounded scene, same camera and lights) sees another triangle at the centre, or a
// different count, or calls ambiguous a pixel `exact` does not: bit kInputRounding. Throws
// std::invalid_argument("mark_input_rounding: ...") when the images differ in size or lights.
void mark_input_rounding(ExactImage& exact, const ExactImage& rounded);

// The diff's reference: the exact image of the scene as given (its stats are this image's),
// marked by that of the scene as GL receives it (same pixels and options): moved into the eye's
// frame and rounded once to float (core/eye_frame.h, core/float_rounding.h). `rounded_seconds`, when
// given, receives the second image's time.
[[nodiscard]] ExactImage exact_image_of_float_input(const Soup& soup, std::span<const Light> lights,
                                                    const Camera& camera, const ExactImageOptions& options,
                                                    double* rounded_seconds = nullptr);

}  // namespace shadowcert
