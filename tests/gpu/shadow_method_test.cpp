// The GL-free part of gpu/shadow_method_renderer.h: method names and the stages of a frame
// (the renderer itself is tested with a context in shadow_method_renderer_test).
#include <gtest/gtest.h>

#include <vector>

#include "gpu/frame_timing.h"
#include "gpu/shadow_method_renderer.h"

namespace shadowcert::gpu {
namespace {

TEST(ShadowMethodName, EveryMethod_RoundTripsAndOthersAreRejected) {
  for (ShadowMethod m : kShadowMethods) EXPECT_EQ(parse_shadow_method(shadow_method_name(m)), m);
  EXPECT_EQ(shadow_method_name(ShadowMethod::pertri), "pertri");
  EXPECT_FALSE(parse_shadow_method("CS").has_value());
  EXPECT_FALSE(parse_shadow_method("").has_value());
}

TEST(MethodStages, VolumeMethodsAndShadowMap_TheirStagesInFrameOrder) {
  const std::vector<RenderStage> volume{RenderStage::volume, RenderStage::depth, RenderStage::stencil,
                                        RenderStage::lit};
  for (ShadowMethod m : kShadowMethods)
    if (draws_volume(m)) {
      EXPECT_EQ(method_stages(m), volume) << shadow_method_name(m);
    }
  EXPECT_EQ(method_stages(ShadowMethod::shadowmap),
            (std::vector<RenderStage>{RenderStage::depth, RenderStage::shadow_map, RenderStage::lit}));
}

TEST(SoftShadowMethods, NamesFiltersAndStages) {
  for (ShadowMethod m : kSoftShadowMethods) {
    EXPECT_EQ(parse_shadow_method(shadow_method_name(m)), m);
    EXPECT_TRUE(uses_shadow_map(m));
    EXPECT_FALSE(draws_volume(m));
  }
  EXPECT_EQ(shadow_filter(ShadowMethod::shadowmap), ShadowFilter::hard);
  EXPECT_EQ(shadow_filter(ShadowMethod::pcf), ShadowFilter::pcf);
  EXPECT_EQ(shadow_filter(ShadowMethod::pcss), ShadowFilter::pcss);
  EXPECT_EQ(shadow_filter(ShadowMethod::smoothie), ShadowFilter::smoothie);
  EXPECT_EQ(method_stages(ShadowMethod::pcf), method_stages(ShadowMethod::shadowmap));
  EXPECT_EQ(method_stages(ShadowMethod::smoothie),
            (std::vector<RenderStage>{RenderStage::depth, RenderStage::shadow_map, RenderStage::smoothie_map,
                                      RenderStage::lit}));
}

}  // namespace
}  // namespace shadowcert::gpu
