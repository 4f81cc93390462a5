// GL resources of the volume methods (the promise: "no GL error, no leak across 100 create/destroy
// cycles"), on llvmpipe or any EGL device, with a debug context (a GL error anywhere throws).
// Each method is driven as `render --method` drives it, by gpu/shadow_method_renderer.h:
//  1. per method (cpu, cs, gs, ts, pertri), 100 cycles in ONE context of: create the method's
//     renderer (upload receivers and soup, create the volume objects, compile the shaders),
//     build the volume and draw one frame, read it back, destroy. Every cycle draws the same
//     counts (re-created objects work alike); every GL name the cycle created is deleted when
//     its owners go (glIs* false), no other name stays alive; the resident set grows by less
//     than kMaxRssGrowthBytes from cycle 10 to cycle 100;
//     The shadow-map methods (shadowmap, pcf, pcss, smoothie: depth and smoothie maps, the
//     sampler, the light image target) run the same cycle kShadowMapCycles times each;
//  2. 100 cycles of the EGL context itself around one cs frame (context, renderer, target):
//     the same counts every time, every name created in the context deleted before it goes,
//     the same RSS bound (a leaked llvmpipe context costs about 2.6 MiB, so 90 of them would
//     exceed it). tests/gpu/gl_object_test.cpp cycles contexts around the plain GL object
//     owners.
#include <epoxy/gl.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <fstream>
#include <functional>
#include <iostream>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "core/camera.h"
#include "core/light.h"
#include "support/gl_test_support.h"
#include "gpu/egl_context.h"
#include "gpu/gl_error.h"
#include "gpu/offscreen_target.h"
#include "gpu/shadow_method_renderer.h"
#include "scene/merged_soup.h"
#include "scene/procedural_mesh.h"
#include "support/volume_test_support.h"

namespace shadowcert::gpu {
namespace {

using namespace test;

constexpr int kCycles = 100;
// RSS is compared between the end of this cycle and the end of the last: the first cycles fill
// the driver's caches (compiled shaders, llvmpipe's thread and allocator pools).
constexpr int kWarmUpCycles = 10;
// Resident-set growth allowed over the 90 measured cycles. It absorbs allocator fragmentation
// and driver bookkeeping (measured on llvmpipe: 0 to 3 MiB per method alone, up to 4.6 MiB for gs
// under a parallel ctest, since the exact-sign and far-split shader code compiles larger; printed per method). Keeping
// every cycle's renderer alive instead (a deliberate leak, tried once) grew it by 60 MiB (cpu),
// 117 MiB (cs), 182 MiB (ts), 257 MiB (pertri) and 338 MiB (gs) over the same cycles, so a
// leak of the method's buffers cannot hide under the bound; the name checks catch any GL
// object that outlives its owner, however small.
constexpr long kMaxRssGrowthBytes = 8L << 20;
// The shadow-map methods allocate a 2048^2 depth map (and smoothie a 2048^2 RG32F map) per
// cycle: fewer cycles keep the test short; a leaked map (16 MiB or more) still exceeds the RSS
// bound at once, and the name checks catch any object.
constexpr int kShadowMapCycles = 30;
// Their RSS bound absorbs the allocator keeping or returning map-sized blocks between the
// measured cycles (16 to 33 MiB measured both ways on llvmpipe with another test running; once
// past 64 MiB under a parallel ctest); a map leaked per cycle grows it by at least 20 x 16 MiB
// over those cycles, well past the bound.
constexpr long kMaxShadowMapRssGrowthBytes = 128L << 20;

long resident_bytes() {
  std::ifstream statm("/proc/self/statm");
  long size = 0, resident = 0;
  statm >> size >> resident;
  return resident * sysconf(_SC_PAGESIZE);
}

// ---- live GL names ---------------------------------------------------------------------------

// Every kind of GL object gpu/ creates (gl_object.h), with how to ask for a fresh name (to learn
// how far names go) and whether a name is alive. Programs and shaders share one namespace.
struct NameKind {
  const char* name;
  std::function<GLuint()> probe;  // creates and deletes one object, returns its name
  GLboolean (*alive)(GLuint);
};

// Creates and deletes one object of a kind made by glCreate*(1, &name): its name.
GLuint probe_name(void (*create)(GLsizei, GLuint*), void (*destroy)(GLsizei, const GLuint*)) {
  GLuint n = 0;
  create(1, &n);
  destroy(1, &n);
  return n;
}

const std::vector<NameKind>& name_kinds() {
  static const std::vector<NameKind> kinds{
      {"buffer", [] { return probe_name(glCreateBuffers, glDeleteBuffers); }, [](GLuint n) { return glIsBuffer(n); }},
      {"vertex array", [] { return probe_name(glCreateVertexArrays, glDeleteVertexArrays); },
       [](GLuint n) { return glIsVertexArray(n); }},
      {"program",
       [] {
         const GLuint n = glCreateProgram();
         glDeleteProgram(n);
         return n;
       },
       [](GLuint n) { return glIsProgram(n); }},
      {"shader",
       [] {
         const GLuint n = glCreateShader(GL_VERTEX_SHADER);
         glDeleteShader(n);
         return n;
       },
       [](GLuint n) { return glIsShader(n); }},
      {"framebuffer", [] { return probe_name(glCreateFramebuffers, glDeleteFramebuffers); },
       [](GLuint n) { return glIsFramebuffer(n); }},
      {"renderbuffer", [] { return probe_name(glCreateRenderbuffers, glDeleteRenderbuffers); },
       [](GLuint n) { return glIsRenderbuffer(n); }},
      {"texture",
       [] {
         GLuint n = 0;
         glCreateTextures(GL_TEXTURE_2D, 1, &n);
         glDeleteTextures(1, &n);
         return n;
       },
       [](GLuint n) { return glIsTexture(n); }},
      {"query",
       [] {
         GLuint n = 0;
         glCreateQueries(GL_PRIMITIVES_GENERATED, 1, &n);
         glDeleteQueries(1, &n);
         return n;
       },
       [](GLuint n) { return glIsQuery(n); }},
      {"transform feedback", [] { return probe_name(glCreateTransformFeedbacks, glDeleteTransformFeedbacks); },
       [](GLuint n) { return glIsTransformFeedback(n); }},
      {"sampler", [] { return probe_name(glCreateSamplers, glDeleteSamplers); },
       [](GLuint n) { return glIsSampler(n); }},
  };
  return kinds;
}

using LiveNames = std::map<std::string, std::vector<GLuint>>;  // kind -> sorted live names

// The live names of every kind. A driver hands out either the next unused name or the lowest
// free one, so a name created now (the probe) is above every live name: scanning up to it, and
// up to the largest name seen alive so far, finds them all.
class NameScanner {
 public:
  LiveNames scan() {
    LiveNames live;
    for (const NameKind& kind : name_kinds()) {
      GLuint& highest = highest_[kind.name];
      highest = std::max(highest, kind.probe());
      std::vector<GLuint>& names = live[kind.name];
      for (GLuint n = 1; n <= highest + kMargin; ++n)
        if (kind.alive(n) == GL_TRUE) names.push_back(n);
      if (!names.empty()) highest = std::max(highest, names.back());
    }
    check_gl_errors("NameScanner::scan");
    return live;
  }

 private:
  static constexpr GLuint kMargin = 16;
  std::map<std::string, GLuint> highest_;
};

// Names in `after` that are not in `before`, "kind name" each.
std::vector<std::string> added(const LiveNames& before, const LiveNames& after) {
  std::vector<std::string> out;
  for (const auto& [kind, list] : after) {
    const std::vector<GLuint>& old = before.count(kind) ? before.at(kind) : std::vector<GLuint>{};
    for (GLuint n : list)
      if (!std::binary_search(old.begin(), old.end(), n)) out.push_back(kind + " " + std::to_string(n));
  }
  return out;
}

std::string joined(const std::vector<std::string>& names) {
  std::string out;
  for (const std::string& n : names) out += (out.empty() ? "" : ", ") + n;
  return out;
}

// ---- the scene ---------------------------------------------------------------------------------

// A 32 x 16 UV sphere (960 triangles) over a floor, lit from above: volume buffers of a few
// hundred KiB per cycle (see kMaxRssGrowthBytes), a shadow in view of a small image.
Soup resource_soup() {
  Soup soup = floor_quad(4.0);
  append_soup(soup, uv_sphere({0.0, 1.5, 0.0}, 1.0, 32, 16));
  soup.normals.clear();  // face normals for shading; no decision reads them
  return soup;
}

const Light kLight{{0.5, 6.0, 0.25, 1.0}};

Camera resource_camera() {
  Camera camera;
  camera.eye = {0.0, 5.0, 7.0};
  camera.target = {0.0, 0.5, 0.0};
  camera.width = 64;
  camera.height = 48;
  return camera;
}

std::size_t shadowed_pixels(const GrayImage& stencil) {
  return static_cast<std::size_t>(
      std::count_if(stencil.pixels.begin(), stencil.pixels.end(), [](std::uint8_t c) { return c != 0; }));
}

// What the cycles of one method measured.
struct CycleReport {
  std::size_t names_per_cycle = 0;  // names one cycle created (largest over the cycles)
  long rss_growth = 0;
  double seconds = 0.0;
};

// ---- 1. object cycles in one context -----------------------------------------------------------

class GlResourceTest : public GlTest {};

// The scene of every cycle: the soup, its canonical form and edge table, and cpu's volume (the
// exact chain, computed once: a cycle uploads it).
struct ResourceScene {
  Soup soup = resource_soup();
  Prepared prepared = prepare(soup);
  HomogeneousMesh cpu = cpu_volume(prepared, kLight);
};

// One cycle: the method's renderer (every GL object it draws with) created, built, drawn, read
// back, destroyed; checks that every name it created died with it. Returns the stencil.
// `live` holds the names alive before the cycle and, on return, those alive after it (the next
// cycle's "before").
GrayImage object_cycle(ShadowMethod method, const ResourceScene& scene, const OffscreenTarget& target,
                       NameScanner& scanner, LiveNames& live, CycleReport& report) {
  const LiveNames before = live;
  GrayImage stencil;
  std::vector<std::string> created;
  {
    ShadowMethodRenderer renderer = one_light_renderer(method, scene.soup, scene.prepared, kLight, &scene.cpu);
    stencil = renderer.render(target, resource_camera()).first_stencil;
    EXPECT_NO_THROW(renderer.check_capacity());
    created = added(before, scanner.scan());
    EXPECT_FALSE(created.empty()) << "the method should own GL objects";
    report.names_per_cycle = std::max(report.names_per_cycle, created.size());
  }
  live = scanner.scan();
  const std::vector<std::string> left = added(before, live);
  EXPECT_TRUE(left.empty()) << left.size() << " names outlived their owners: " << joined(left) << " (the cycle created "
                            << joined(created) << ")";
  check_gl_errors("object cycle");
  return stencil;
}

TEST_F(GlResourceTest, HundredObjectCyclesPerMethod_NoGlErrorNoLeak) {
  const ResourceScene scene;
  const OffscreenTarget target(resource_camera().width, resource_camera().height);
  NameScanner scanner;
  LiveNames live = scanner.scan();
  for (ShadowMethod method : kVolumeMethods) {
    SCOPED_TRACE(std::string(shadow_method_name(method)));
    CycleReport report;
    const auto start = std::chrono::steady_clock::now();
    const GrayImage first = object_cycle(method, scene, target, scanner, live, report);
    ASSERT_GT(shadowed_pixels(first), 100u) << "the sphere's shadow should be in view";
    long rss_after_warm_up = 0;
    for (int cycle = 1; cycle < kCycles; ++cycle) {
      const GrayImage stencil = object_cycle(method, scene, target, scanner, live, report);
      ASSERT_FALSE(HasFailure()) << "cycle " << cycle;
      ASSERT_EQ(stencil.pixels, first.pixels) << "cycle " << cycle << " drew other counts";
      if (cycle + 1 == kWarmUpCycles) rss_after_warm_up = resident_bytes();
    }
    report.rss_growth = resident_bytes() - rss_after_warm_up;
    report.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::cout << shadow_method_name(method) << ": " << kCycles << " cycles in " << report.seconds << " s, "
              << report.names_per_cycle << " GL names per cycle, RSS growth from cycle " << kWarmUpCycles << " to "
              << kCycles << ": " << report.rss_growth / 1024 << " KiB\n";
    EXPECT_LT(report.rss_growth, kMaxRssGrowthBytes);
  }
}

// The resource scene with its smoothies, for the shadow-map methods.
struct ShadowMapResourceScene : ResourceScene {
  ShadowMapResourceScene() { add_smoothies(prepared, std::span(&kLight, 1), soup_bounds(soup)); }
};

TEST_F(GlResourceTest, ObjectCyclesPerShadowMapMethod_NoGlErrorNoLeak) {
  const ShadowMapResourceScene scene;
  const OffscreenTarget target(resource_camera().width, resource_camera().height);
  NameScanner scanner;
  LiveNames live = scanner.scan();
  for (ShadowMethod method : {ShadowMethod::shadowmap, ShadowMethod::pcf, ShadowMethod::pcss, ShadowMethod::smoothie}) {
    SCOPED_TRACE(std::string(shadow_method_name(method)));
    CycleReport report;
    const GrayImage first = object_cycle(method, scene, target, scanner, live, report);
    ASSERT_GT(shadowed_pixels(first), 100u) << "the sphere's shadow should be in view";
    long rss_after_warm_up = 0;
    for (int cycle = 1; cycle < kShadowMapCycles; ++cycle) {
      const GrayImage stencil = object_cycle(method, scene, target, scanner, live, report);
      ASSERT_FALSE(HasFailure()) << "cycle " << cycle;
      ASSERT_EQ(stencil.pixels, first.pixels) << "cycle " << cycle << " drew other marks";
      if (cycle + 1 == kWarmUpCycles) rss_after_warm_up = resident_bytes();
    }
    report.rss_growth = resident_bytes() - rss_after_warm_up;
    std::cout << shadow_method_name(method) << ": " << report.names_per_cycle << " GL names per cycle, RSS growth "
              << report.rss_growth / 1024 << " KiB\n";
    EXPECT_LT(report.rss_growth, kMaxShadowMapRssGrowthBytes);
  }
}

// ---- 2. context cycles -------------------------------------------------------------------------

TEST(GlContextCycles, HundredContextsWithAComputeVolumeFrame_NoGlErrorNoLeak) {
  const ResourceScene scene;
  std::optional<GrayImage> first;
  long rss_after_warm_up = 0;
  const auto start = std::chrono::steady_clock::now();
  for (int cycle = 0; cycle < kCycles; ++cycle) {
    std::optional<EglContext> context;
    try {
      context.emplace(EglContextOptions{std::nullopt, true});
    } catch (const NoGlDeviceError& error) {
      if (gl_required()) FAIL() << "SHADOWCERT_REQUIRE_GL=1 but: " << error.what();
      GTEST_SKIP() << "no EGL device: " << error.what();
    }
    NameScanner scanner;
    const LiveNames before = scanner.scan();
    GrayImage stencil;
    {
      const OffscreenTarget target(resource_camera().width, resource_camera().height);
      ShadowMethodRenderer renderer = one_light_renderer(ShadowMethod::cs, scene.soup, scene.prepared, kLight, nullptr);
      stencil = renderer.render(target, resource_camera()).first_stencil;
    }
    const std::vector<std::string> left = added(before, scanner.scan());
    ASSERT_TRUE(left.empty()) << "cycle " << cycle << ": names outlived their owners: " << joined(left);
    check_gl_errors("context cycle");
    if (!first) {
      first = stencil;
      ASSERT_GT(shadowed_pixels(stencil), 100u);
    }
    ASSERT_EQ(stencil.pixels, first->pixels) << "cycle " << cycle << " drew other counts";
    if (cycle + 1 == kWarmUpCycles) rss_after_warm_up = resident_bytes();
  }
  const long growth = resident_bytes() - rss_after_warm_up;
  std::cout << kCycles << " context cycles with a cs frame in "
            << std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count()
            << " s, RSS growth from cycle " << kWarmUpCycles << " to " << kCycles << ": " << growth / 1024 << " KiB\n";
  EXPECT_LT(growth, kMaxRssGrowthBytes);
}

}  // namespace
}  // namespace shadowcert::gpu
