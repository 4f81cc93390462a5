// pipeline/bench_suite.h's bench_scene_into with GL: when a run throws, what finished before it
// is kept and the run that threw is named, so that `shadowcert bench` records the failure and
// goes on (docs/bench.md, "A scene that fails"; tests/cli/bench_command_test.cpp runs that).
#include <gtest/gtest.h>

#include <algorithm>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/input_error.h"
#include "pipeline/bench_suite.h"
#include "support/gl_test_support.h"

namespace shadowcert {
namespace {

class BenchSceneInto : public gpu::test::GlTest {
 protected:
  BenchSceneInto() {
    spec_ = bench_scene_files({std::string(SHADOWCERT_SOURCE_DIR) + "/data/scenes/default.json"}, false).front();
    options_.frames = 1;
    options_.images = false;
  }
  static BenchVariant variant(const std::string& id) {
    const std::vector<BenchVariant> all = bench_variants();
    const auto at = std::find_if(all.begin(), all.end(), [&](const BenchVariant& v) { return v.id == id; });
    if (at == all.end()) throw std::logic_error("no run " + id);
    return *at;
  }
  BenchSceneSpec spec_;
  BenchOptions options_;
};

TEST_F(BenchSceneInto, EveryRunDone_NothingRunning) {
  const Scene scene = load_bench_scene(spec_, 32, 24);
  BenchSceneResult result;
  result.running = "left over";  // reset on entry
  bench_scene_into(result, scene, spec_, {variant("cpu"), variant("cs/exact")}, options_);
  ASSERT_EQ(result.runs.size(), 2u);
  EXPECT_EQ(result.runs[1].variant.id, "cs/exact");
  EXPECT_TRUE(result.running.empty());
  EXPECT_EQ(result.triangles, 56u);
}

// A pcf kernel of 2 is misuse of the renderer (odd kernels only): its run throws after cpu's
// finished. The caller keeps cpu's run and learns which run threw.
TEST_F(BenchSceneInto, ARunThrows_TheRunsBeforeItKeptAndItNamed) {
  const Scene scene = load_bench_scene(spec_, 32, 24);
  BenchVariant even = variant("pcf/3");
  even.id = "pcf/2";
  even.pcf_kernel = 2;
  BenchSceneResult result;
  EXPECT_THROW(bench_scene_into(result, scene, spec_, {variant("cpu"), even, variant("cs/exact")}, options_),
               std::invalid_argument);
  ASSERT_EQ(result.runs.size(), 1u);
  EXPECT_EQ(result.runs[0].variant.id, "cpu");
  EXPECT_EQ(result.runs[0].run.sum(&PixelComparison::hard_errors), 0u);
  EXPECT_EQ(result.running, "pcf/2");
  EXPECT_EQ(result.width, 32u);  // the scene's figures were set before the runs
}

// The scene's own checks throw before any run: nothing is running.
TEST_F(BenchSceneInto, NoLight_ThrowsBeforeAnyRun) {
  Scene scene = load_bench_scene(spec_, 32, 24);
  scene.lights.clear();
  BenchSceneResult result;
  EXPECT_THROW(bench_scene_into(result, scene, spec_, {variant("cpu")}, options_), InputError);
  EXPECT_TRUE(result.runs.empty());
  EXPECT_TRUE(result.running.empty());
  EXPECT_EQ(result.width, 0u);
}

}  // namespace
}  // namespace shadowcert
