// pipeline/method_registry.h: one entry per method, the robust rule, --methods lists, the help,
// and the options each method reads.
#include "pipeline/method_registry.h"

#include <gtest/gtest.h>

#include <set>
#include <stdexcept>
#include <string>
#include <vector>

namespace shadowcert {
namespace {

using gpu::ShadowMethod;

TEST(MethodRegistry, EveryMethod_ExactlyOneEntry) {
  std::set<ShadowMethod> seen;
  for (const MethodEntry& e : method_registry()) {
    EXPECT_TRUE(seen.insert(e.method).second) << e.name();
    EXPECT_EQ(&method_entry(e.method), &e);
    EXPECT_EQ(find_method(e.name()), &e);
    EXPECT_FALSE(e.help.empty()) << e.name();
    // The help clause starts with the method's own name, so --help reads as a list of them.
    EXPECT_EQ(e.help.substr(0, e.name().size()), e.name());
    EXPECT_EQ(e.docs.substr(0, 5), "docs/") << e.name();
  }
  EXPECT_EQ(seen.size(), gpu::kShadowMethodTable.size());
  EXPECT_EQ(find_method("CPU"), nullptr);
}

// The robust rule (docs/definitions.md#pixel-protocol): the chain methods and discrete; never a
// shadow map, never a method that shadows the smooth surface.
TEST(MethodRegistry, Robust_TheChainMethodsAndDiscrete) {
  std::vector<ShadowMethod> robust_methods;
  for (const MethodEntry& e : method_registry())
    if (e.robust) robust_methods.push_back(e.method);
  EXPECT_EQ(robust_methods, (std::vector<ShadowMethod>{ShadowMethod::cpu, ShadowMethod::cs, ShadowMethod::gs,
                                                        ShadowMethod::ts, ShadowMethod::pertri, ShadowMethod::discrete}));
  for (const MethodEntry& e : method_registry()) {
    if (gpu::uses_shadow_map(e.method) || gpu::shadows_smooth_surface(e.method)) {
      EXPECT_FALSE(robust(e.method)) << e.name();
    }
  }
}

// What each method reads follows from what it is: every volume is counted with a stencil method
// and can be captured; only the GPU-built ones take --sign; only shadow maps take the map's options.
TEST(MethodRegistry, Options_FollowTheMethodsFamily) {
  for (const MethodEntry& e : method_registry()) {
    SCOPED_TRACE(std::string(e.name()));
    EXPECT_EQ(e.reads(MethodOption::stencil), gpu::draws_volume(e.method));
    EXPECT_EQ(e.reads(MethodOption::capture), gpu::draws_volume(e.method));
    EXPECT_EQ(e.reads(MethodOption::sign), gpu::builds_volume_on_gpu(e.method));
    EXPECT_EQ(e.reads(MethodOption::shadow_map), gpu::uses_shadow_map(e.method));
    EXPECT_EQ(e.reads(MethodOption::silhouette), gpu::is_silhouette_method(e.method));
  }
  EXPECT_EQ(methods_reading(MethodOption::pcf_kernel), "pcf");
  EXPECT_EQ(methods_reading(MethodOption::shadow_map), "shadowmap, pcf, pcss, smoothie");
  EXPECT_EQ(method_option_flags(MethodOption::shadow_map).front(), "--shadowmap-size");
}

TEST(ParseMethodList, AllAndEmpty_TheSixChainAndMapMethods) {
  const std::vector<ShadowMethod> all{ShadowMethod::cpu, ShadowMethod::cs, ShadowMethod::gs,
                                      ShadowMethod::ts,  ShadowMethod::pertri, ShadowMethod::shadowmap};
  EXPECT_EQ(parse_method_list(""), all);
  EXPECT_EQ(parse_method_list("all"), all);
  // "all" joins other names, each method once, in the list's order.
  std::vector<ShadowMethod> with_smooth{ShadowMethod::smooth};
  with_smooth.insert(with_smooth.end(), all.begin(), all.end());
  EXPECT_EQ(parse_method_list("smooth,all,cpu"), with_smooth);
}

TEST(ParseMethodList, UnknownName_ThrowsNamingItAndTheMethods) {
  try {
    (void)parse_method_list("cpu,bogus");
    FAIL() << "not rejected";
  } catch (const std::invalid_argument& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("'bogus'"), std::string::npos) << what;
    EXPECT_NE(what.find(method_names()), std::string::npos) << what;
  }
  EXPECT_THROW((void)parse_method_list("cpu,,cs"), std::invalid_argument);
}

TEST(MethodHelp, NamesEveryMethodInDisplayOrder) {
  const std::string help = method_help();
  std::size_t at = 0;
  for (const MethodEntry& e : method_registry()) {
    const std::size_t found = help.find(std::string(e.help), at);
    ASSERT_NE(found, std::string::npos) << e.name();
    at = found;
  }
  EXPECT_EQ(method_names("|"),
            "cpu|cs|gs|ts|pertri|shadowmap|pcf|pcss|smoothie|discrete|accurate|smooth|smooth-gpu|rt|rt-robust");
  for (const RayTracedEntry& e : ray_traced_registry()) {
    const std::size_t found = help.find(std::string(e.help), at);
    ASSERT_NE(found, std::string::npos) << e.name;
    at = found;
  }
}

// The ray-traced methods: one entry each, found by name, never robust, never in "all".
TEST(RayTracedRegistry, Entries_NamedModesNotRobust) {
  ASSERT_EQ(ray_traced_registry().size(), 2u);
  EXPECT_EQ(ray_traced_method_name(RayTracedMethod::rt), "rt");
  EXPECT_EQ(ray_traced_method_name(RayTracedMethod::rt_robust), "rt-robust");
  EXPECT_EQ(ray_traced_entry(RayTracedMethod::rt).mode, raytrace::BuildMode::fast);
  EXPECT_EQ(ray_traced_entry(RayTracedMethod::rt_robust).mode, raytrace::BuildMode::robust);
  for (const RayTracedEntry& e : ray_traced_registry()) {
    EXPECT_FALSE(e.robust) << e.name;
    EXPECT_EQ(find_ray_traced_method(e.name), &e);
    EXPECT_EQ(find_method(e.name), nullptr) << e.name << " is no GL method";
  }
  EXPECT_EQ(find_ray_traced_method("RT"), nullptr);
}

TEST(ParseMethodSelection, BothKinds_EachInItsListsOrder) {
  const MethodSelection s = parse_method_selection("rt-robust,cpu,rt,rt-robust,shadowmap");
  EXPECT_EQ(s.gl, (std::vector<ShadowMethod>{ShadowMethod::cpu, ShadowMethod::shadowmap}));
  EXPECT_EQ(s.ray_traced, (std::vector<RayTracedMethod>{RayTracedMethod::rt_robust, RayTracedMethod::rt}));
  const MethodSelection rt_only = parse_method_selection("rt");
  EXPECT_TRUE(rt_only.gl.empty());
  EXPECT_FALSE(rt_only.empty());
  EXPECT_TRUE(parse_method_selection("all").ray_traced.empty()) << "rt is asked for by name";
  EXPECT_EQ(parse_method_selection("all").gl, parse_method_list("all"));
  EXPECT_THROW((void)parse_method_selection("rt,bogus"), std::invalid_argument);
}

TEST(ParseMethodList, RayTracedName_ThrowsSayingItIsNoGlMethod) {
  try {
    (void)parse_method_list("cpu,rt");
    FAIL() << "not rejected";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("'rt' is traced on the CPU, not a GL method"), std::string::npos) << e.what();
  }
}

// Bench's sweeps: each label once per method, as many labels as values.
TEST(MethodRegistry, BenchSweeps_LabelledValues) {
  for (const MethodEntry& e : method_registry()) {
    SCOPED_TRACE(std::string(e.name()));
    EXPECT_EQ(e.sweep.parameter == SweptParameter::none, e.sweep.count == 0);
    std::set<std::string_view> labels;
    for (std::size_t i = 0; i < e.sweep.count; ++i) {
      EXPECT_FALSE(e.sweep.labels[i].empty());
      EXPECT_TRUE(labels.insert(e.sweep.labels[i]).second);
    }
  }
}

}  // namespace
}  // namespace shadowcert
