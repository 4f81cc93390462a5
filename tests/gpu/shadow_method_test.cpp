// gpu/shadow_method.h, GL-free: the method table, names and the stages of a frame (the renderer
// itself is tested with a context in shadow_method_renderer_test).
#include <gtest/gtest.h>

#include <cstddef>
#include <vector>

#include "gpu/frame_timing.h"
#include "gpu/shadow_method.h"

namespace shadowcert::gpu {
namespace {

// The table is indexed by the enum: each row at its method's index, each name once.
TEST(ShadowMethodTable, EveryRow_AtItsMethodsIndexWithAUniqueName) {
  for (std::size_t i = 0; i < kShadowMethodTable.size(); ++i) {
    EXPECT_EQ(static_cast<std::size_t>(kShadowMethodTable[i].method), i);
    for (std::size_t j = i + 1; j < kShadowMethodTable.size(); ++j)
      EXPECT_NE(kShadowMethodTable[i].name, kShadowMethodTable[j].name);
    EXPECT_EQ(parse_shadow_method(kShadowMethodTable[i].name), kShadowMethodTable[i].method);
  }
}

// The lists the CLI and the comparison use are the table's rows, in its order.
TEST(ShadowMethodTable, Lists_AreTheTablesFamilies) {
  EXPECT_EQ(std::vector<ShadowMethod>(kShadowMethods.begin(), kShadowMethods.end()),
            (std::vector<ShadowMethod>{ShadowMethod::cpu, ShadowMethod::cs, ShadowMethod::gs, ShadowMethod::ts,
                                       ShadowMethod::pertri, ShadowMethod::shadowmap}));
  EXPECT_EQ(std::vector<ShadowMethod>(kSilhouetteMethods.begin(), kSilhouetteMethods.end()),
            (std::vector<ShadowMethod>{ShadowMethod::discrete, ShadowMethod::accurate, ShadowMethod::smooth,
                                       ShadowMethod::smooth_gpu}));
  EXPECT_EQ(std::vector<ShadowMethod>(kSoftShadowMethods.begin(), kSoftShadowMethods.end()),
            (std::vector<ShadowMethod>{ShadowMethod::pcf, ShadowMethod::pcss, ShadowMethod::smoothie}));
  for (const ShadowMethodTraits& t : kShadowMethodTable) {
    SCOPED_TRACE(t.name);
    EXPECT_EQ(builds_volume_on_gpu(t.method), t.family == MethodFamily::gpu_volume);
    EXPECT_EQ(draws_given_volume(t.method), t.method == ShadowMethod::cpu || is_silhouette_method(t.method));
    EXPECT_EQ(draws_volume(t.method), !uses_shadow_map(t.method));
    // Only shadow maps filter, and only silhouette methods shadow a smooth surface.
    if (t.filter != ShadowFilter::hard) {
      EXPECT_TRUE(uses_shadow_map(t.method));
    }
    if (t.smooth_surface) {
      EXPECT_TRUE(is_silhouette_method(t.method));
    }
  }
}

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
