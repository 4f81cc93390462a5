#include "raytrace/ray_traced_image.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>

#include "core/pixel_ray.h"

namespace shadowcert::raytrace {
namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// The most rays one Embree call takes (RTCRayHit16).
constexpr unsigned kMaxPacket = 16;

// One ray for Embree: float origin and direction, its interval.
struct FloatRay {
  std::array<float, 3> origin{};
  std::array<float, 3> direction{};
  float tnear = 0.0f;
  float tfar = std::numeric_limits<float>::infinity();
};

// Embree's packet types by width, so that one loop serves 4, 8 and 16.
template <unsigned N> struct PacketTypes;
template <> struct PacketTypes<4> {
  using RayHit = RTCRayHit4;
  using Ray = RTCRay4;
  static void intersect(const int* valid, RTCScene s, RTCIntersectContext* c, RayHit* r) { rtcIntersect4(valid, s, c, r); }
  static void occluded(const int* valid, RTCScene s, RTCIntersectContext* c, Ray* r) { rtcOccluded4(valid, s, c, r); }
};
template <> struct PacketTypes<8> {
  using RayHit = RTCRayHit8;
  using Ray = RTCRay8;
  static void intersect(const int* valid, RTCScene s, RTCIntersectContext* c, RayHit* r) { rtcIntersect8(valid, s, c, r); }
  static void occluded(const int* valid, RTCScene s, RTCIntersectContext* c, Ray* r) { rtcOccluded8(valid, s, c, r); }
};
template <> struct PacketTypes<16> {
  using RayHit = RTCRayHit16;
  using Ray = RTCRay16;
  static void intersect(const int* valid, RTCScene s, RTCIntersectContext* c, RayHit* r) { rtcIntersect16(valid, s, c, r); }
  static void occluded(const int* valid, RTCScene s, RTCIntersectContext* c, Ray* r) { rtcOccluded16(valid, s, c, r); }
};

template <typename PacketRay>
void set_packet_ray(PacketRay& ray, unsigned i, const FloatRay& r) {
  ray.org_x[i] = r.origin[0];
  ray.org_y[i] = r.origin[1];
  ray.org_z[i] = r.origin[2];
  ray.dir_x[i] = r.direction[0];
  ray.dir_y[i] = r.direction[1];
  ray.dir_z[i] = r.direction[2];
  ray.tnear[i] = r.tnear;
  ray.tfar[i] = r.tfar;
  ray.time[i] = 0.0f;
  ray.mask[i] = 0xFFFFFFFFu;
  ray.id[i] = i;
  ray.flags[i] = 0;
}

void set_single_ray(RTCRay& ray, const FloatRay& r) {
  ray.org_x = r.origin[0];
  ray.org_y = r.origin[1];
  ray.org_z = r.origin[2];
  ray.dir_x = r.direction[0];
  ray.dir_y = r.direction[1];
  ray.dir_z = r.direction[2];
  ray.tnear = r.tnear;
  ray.tfar = r.tfar;
  ray.time = 0.0f;
  ray.mask = 0xFFFFFFFFu;
  ray.id = 0;
  ray.flags = 0;
}

// Up to kMaxPacket rays at once: their first hits (primitive or RTC_INVALID_GEOMETRY_ID, and
// the distance) or whether each is occluded. `active[i]` false: ray i is not traced.
class Tracer {
 public:
  Tracer(unsigned packet) : packet_(packet) {}

  // hits[i]: Embree's primitive or kNone; t[i] the distance.
  void first_hits(RTCScene scene, std::span<const FloatRay> rays, std::span<std::uint32_t> primitives,
                  std::span<float> t) const {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;  // neighbouring pixels' rays
    for (std::size_t start = 0; start < rays.size(); start += packet_) {
      const std::size_t n = std::min<std::size_t>(packet_, rays.size() - start);
      switch (packet_) {
        case 4: packet_hits<4>(scene, context, rays.subspan(start, n), primitives.subspan(start, n), t.subspan(start, n)); break;
        case 8: packet_hits<8>(scene, context, rays.subspan(start, n), primitives.subspan(start, n), t.subspan(start, n)); break;
        case 16: packet_hits<16>(scene, context, rays.subspan(start, n), primitives.subspan(start, n), t.subspan(start, n)); break;
        default:
          for (std::size_t i = 0; i < n; ++i) {
            RTCRayHit rayhit;
            set_single_ray(rayhit.ray, rays[start + i]);
            rayhit.hit.geomID = RTC_INVALID_GEOMETRY_ID;
            rayhit.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
            rtcIntersect1(scene, &context, &rayhit);
            primitives[start + i] = rayhit.hit.geomID == RTC_INVALID_GEOMETRY_ID ? kNone : rayhit.hit.primID;
            t[start + i] = rayhit.ray.tfar;
          }
      }
    }
  }

  // occluded[i] for every active ray (inactive ones are left as they are).
  void occluded(RTCScene scene, std::span<const FloatRay> rays, std::span<const std::uint8_t> active,
                std::span<std::uint8_t> occluded) const {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    for (std::size_t start = 0; start < rays.size(); start += packet_) {
      const std::size_t n = std::min<std::size_t>(packet_, rays.size() - start);
      switch (packet_) {
        case 4: packet_occluded<4>(scene, context, rays.subspan(start, n), active.subspan(start, n), occluded.subspan(start, n)); break;
        case 8: packet_occluded<8>(scene, context, rays.subspan(start, n), active.subspan(start, n), occluded.subspan(start, n)); break;
        case 16: packet_occluded<16>(scene, context, rays.subspan(start, n), active.subspan(start, n), occluded.subspan(start, n)); break;
        default:
          for (std::size_t i = 0; i < n; ++i) {
            if (active[start + i] == 0) continue;
            RTCRay ray;
            set_single_ray(ray, rays[start + i]);
            rtcOccluded1(scene, &context, &ray);
            occluded[start + i] = ray.tfar < 0.0f ? 1 : 0;  // Embree sets tfar to -inf on a hit
          }
      }
    }
  }

  static constexpr std::uint32_t kNone = 0xFFFFFFFFu;

 private:
  template <unsigned N>
  static void packet_hits(RTCScene scene, RTCIntersectContext& context, std::span<const FloatRay> rays,
                          std::span<std::uint32_t> primitives, std::span<float> t) {
    alignas(64) typename PacketTypes<N>::RayHit rayhit;
    alignas(64) std::array<int, N> valid{};
    for (unsigned i = 0; i < N; ++i) {
      valid[i] = i < rays.size() ? -1 : 0;
      set_packet_ray(rayhit.ray, i, i < rays.size() ? rays[i] : FloatRay{});
      rayhit.hit.geomID[i] = RTC_INVALID_GEOMETRY_ID;
      rayhit.hit.instID[0][i] = RTC_INVALID_GEOMETRY_ID;
    }
    PacketTypes<N>::intersect(valid.data(), scene, &context, &rayhit);
    for (std::size_t i = 0; i < rays.size(); ++i) {
      primitives[i] = rayhit.hit.geomID[i] == RTC_INVALID_GEOMETRY_ID ? kNone : rayhit.hit.primID[i];
      t[i] = rayhit.ray.tfar[i];
    }
  }

  template <unsigned N>
  static void packet_occluded(RTCScene scene, RTCIntersectContext& context, std::span<const FloatRay> rays,
                              std::span<const std::uint8_t> active, std::span<std::uint8_t> occluded) {
    alignas(64) typename PacketTypes<N>::Ray ray;
    alignas(64) std::array<int, N> valid{};
    bool any = false;
    for (unsigned i = 0; i < N; ++i) {
      const bool on = i < rays.size() && active[i] != 0;
      valid[i] = on ? -1 : 0;
      any = any || on;
      set_packet_ray(ray, i, i < rays.size() ? rays[i] : FloatRay{});
    }
    if (!any) return;
    PacketTypes<N>::occluded(valid.data(), scene, &context, &ray);
    for (std::size_t i = 0; i < rays.size(); ++i)
      if (active[i] != 0) occluded[i] = ray.tfar[i] < 0.0f ? 1 : 0;
  }

  unsigned packet_;
};

std::array<float, 3> to_float(const Vec3& v) {
  return {static_cast<float>(v[0]), static_cast<float>(v[1]), static_cast<float>(v[2])};
}

// The camera's ray through image point (x, y), rounded to float.
FloatRay camera_ray(const CameraFrame& frame, double x, double y) {
  const PixelRay ray = pixel_ray(frame, x, y);
  FloatRay r;
  r.origin = to_float(ray.origin);
  r.direction = to_float(ray.direction);
  return r;
}

// The shadow ray from `p` towards `light`, starting `offset` world units along it.
FloatRay shadow_ray(const Vec3& p, const Light& light, double offset) {
  FloatRay r;
  r.origin = to_float(p);
  if (light.directional()) {
    const Vec3 l{light.position[0], light.position[1], light.position[2]};
    const Vec3 d = normalized(l);
    r.direction = to_float(d);
    r.tnear = static_cast<float>(offset);
    r.tfar = std::numeric_limits<float>::infinity();
  } else {
    // From the float origin the ray leaves from, so that t = 1 is the light.
    const Vec3 d{light.position[0] - r.origin[0], light.position[1] - r.origin[1], light.position[2] - r.origin[2]};
    r.direction = to_float(d);
    // The same offset at the light's end: a light on a triangle (at a vertex, on an edge, in a
    // face) must not occlude itself, as the exact count's open segment excludes its end.
    const double length = std::sqrt(dot(d, d));
    r.tnear = length > 0.0 ? static_cast<float>(offset / length) : 0.0f;
    r.tfar = length > 0.0 ? static_cast<float>(std::max(0.0, 1.0 - offset / length)) : 0.0f;
  }
  return r;
}

// The diagonal of the box of the vertices the soup's triangles use (0 for none).
double bounds_diagonal(const Soup& soup) {
  Vec3 lo{std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity(),
          std::numeric_limits<double>::infinity()};
  Vec3 hi{-lo[0], -lo[1], -lo[2]};
  bool any = false;
  for (const Triangle& t : soup.triangles)
    for (const std::uint32_t i : t)
      for (int k = 0; k < 3; ++k) {
        lo[k] = std::min(lo[k], soup.vertices[i][k]);
        hi[k] = std::max(hi[k], soup.vertices[i][k]);
        any = true;
      }
  if (!any) return 0.0;
  const Vec3 d{hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]};
  return std::sqrt(dot(d, d));
}

// What both images share: the checks, the device, the scenes, the arena and the first hits.
struct TraceSetup {
  CameraFrame frame;
  double offset = 0.0;  // world units
  std::optional<EmbreeDevice> device;
  std::optional<EmbreeScene> visible;
  std::optional<EmbreeScene> casters;  // only when some triangle does not cast
  [[nodiscard]] RTCScene occluders() const { return casters ? casters->get() : visible->get(); }
};

void check_inputs(const Soup& soup, std::span<const Light> lights, const Camera& camera,
                  const RayTracedImageOptions& options, const char* function) {
  require_indices_in_range(soup, function);
  require_finite_vertices(soup, function);
  for (const Light& light : lights) require_defined(light, function);
  (void)camera_frame(camera, function);
  if (!options.casts.empty() && options.casts.size() != soup.triangles.size())
    throw std::invalid_argument(std::string(function) + ": casts has " + std::to_string(options.casts.size()) +
                                " flags for " + std::to_string(soup.triangles.size()) + " triangles");
  if (options.packet != 1 && options.packet != 4 && options.packet != 8 && options.packet != 16)
    throw std::invalid_argument(std::string(function) + ": packet must be 1, 4, 8 or 16, got " +
                                std::to_string(options.packet));
  if (!std::isfinite(options.shadow_ray_offset) || options.shadow_ray_offset < 0.0)
    throw std::invalid_argument(std::string(function) + ": shadow_ray_offset must be finite and >= 0");
  for (const Vec3& v : soup.vertices)
    for (const double x : v)
      if (!std::isfinite(static_cast<float>(x)))
        throw std::invalid_argument(std::string(function) + ": a vertex coordinate is beyond float's range");
}

// Builds the scenes (in the arena the caller runs in) and records the build time.
void build(TraceSetup& setup, const Soup& soup, const RayTracedImageOptions& options, RayTracedStats& stats) {
  const auto start = Clock::now();
  setup.device.emplace();
  setup.visible.emplace(*setup.device, soup, options.mode);
  if (!options.casts.empty() &&
      std::any_of(options.casts.begin(), options.casts.end(), [](std::uint8_t c) { return c == 0; }))
    setup.casters.emplace(*setup.device, soup, options.mode, options.casts);
  stats.build_seconds = seconds_since(start);
}

// The largest magnitude of v's coordinates.
double max_abs(const std::array<float, 3>& v) {
  return std::max({std::abs(static_cast<double>(v[0])), std::abs(static_cast<double>(v[1])),
                   std::abs(static_cast<double>(v[2]))});
}

// Row r's centre rays: primitives -> soup triangles in `hits`, hit points in `points`, and each
// hit's shadow-ray offset in `offsets` (world units: the scene's part plus kHitPointErrorUlps
// float ulps of the distance travelled and of P's coordinates).
void trace_row(const TraceSetup& setup, const Tracer& tracer, std::uint32_t row, std::span<std::uint32_t> hits,
               std::vector<FloatRay>& rays, std::vector<std::uint32_t>& primitives, std::vector<float>& t,
               std::vector<Vec3>& points, std::vector<double>& offsets) {
  const std::uint32_t width = setup.frame.width;
  rays.resize(width);
  primitives.resize(width);
  t.resize(width);
  points.resize(width);
  offsets.resize(width);
  for (std::uint32_t i = 0; i < width; ++i) rays[i] = camera_ray(setup.frame, i + 0.5, row + 0.5);
  tracer.first_hits(setup.visible->get(), rays, primitives, t);
  for (std::uint32_t i = 0; i < width; ++i) {
    hits[i] = primitives[i] == Tracer::kNone ? kMissed : setup.visible->triangle(primitives[i]);
    if (hits[i] == kMissed) continue;
    for (int k = 0; k < 3; ++k)
      points[i][k] = static_cast<double>(rays[i].origin[k]) +
                     static_cast<double>(t[i]) * static_cast<double>(rays[i].direction[k]);
    constexpr double kFloatUlp = 0x1p-24;  // half an ulp of 1 in float: float's unit roundoff
    const double travelled = static_cast<double>(t[i]) * max_abs(rays[i].direction);
    const double p_magnitude = std::max({std::abs(points[i][0]), std::abs(points[i][1]), std::abs(points[i][2])});
    offsets[i] = setup.offset + kHitPointErrorUlps * kFloatUlp * (travelled + p_magnitude);
  }
}

// The corner rays' first hits, (width + 1) x (height + 1).
std::vector<std::uint32_t> corner_hits(const TraceSetup& setup, const Tracer& tracer) {
  const std::uint32_t columns = setup.frame.width + 1;
  std::vector<std::uint32_t> hits(std::size_t{columns} * (setup.frame.height + 1));
  tbb::parallel_for(tbb::blocked_range<std::uint32_t>(0, setup.frame.height + 1),
                    [&](const tbb::blocked_range<std::uint32_t>& rows) {
                      std::vector<FloatRay> rays(columns);
                      std::vector<std::uint32_t> primitives(columns);
                      std::vector<float> t(columns);
                      for (std::uint32_t r = rows.begin(); r != rows.end(); ++r) {
                        for (std::uint32_t i = 0; i < columns; ++i) rays[i] = camera_ray(setup.frame, i, r);
                        tracer.first_hits(setup.visible->get(), rays, primitives, t);
                        for (std::uint32_t i = 0; i < columns; ++i)
                          hits[std::size_t{r} * columns + i] =
                              primitives[i] == Tracer::kNone ? kMissed : setup.visible->triangle(primitives[i]);
                      }
                    });
  return hits;
}

tbb::task_arena make_arena(unsigned threads) {
  return threads == 0 ? tbb::task_arena() : tbb::task_arena(static_cast<int>(threads));
}

// Per pixel of a row, the shadow rays towards each of `lights`; visit(light, pixel, occluded).
template <typename Visit>
void shadow_rays(const TraceSetup& setup, const Tracer& tracer, std::span<const Light> lights,
                 std::span<const std::uint32_t> hits, std::span<const Vec3> points, std::span<const double> offsets,
                 std::vector<FloatRay>& rays,
                 std::vector<std::uint8_t>& active, std::vector<std::uint8_t>& occluded, Visit&& visit) {
  const std::size_t width = hits.size();
  rays.resize(width);
  active.resize(width);
  occluded.resize(width);
  for (std::size_t i = 0; i < width; ++i) active[i] = hits[i] != kMissed ? 1 : 0;
  for (std::size_t k = 0; k < lights.size(); ++k) {
    for (std::size_t i = 0; i < width; ++i) {
      occluded[i] = 0;
      if (active[i] != 0) rays[i] = shadow_ray(points[i], lights[k], offsets[i]);
    }
    tracer.occluded(setup.occluders(), rays, active, occluded);
    for (std::size_t i = 0; i < width; ++i)
      if (active[i] != 0) visit(k, i, occluded[i] != 0);
  }
}

}  // namespace

RayTracedImage ray_traced_image(const Soup& soup, std::span<const Light> lights, const Camera& camera,
                                const RayTracedImageOptions& options) {
  constexpr const char* kFunction = "ray_traced_image";
  const auto start = Clock::now();
  check_inputs(soup, lights, camera, options, kFunction);
  TraceSetup setup;
  setup.frame = camera_frame(camera, kFunction);
  setup.offset = options.shadow_ray_offset * bounds_diagonal(soup);
  RayTracedImage image;
  image.width = setup.frame.width;
  image.height = setup.frame.height;
  const std::size_t pixels = std::size_t{image.width} * image.height;
  image.hit_triangles.assign(pixels, kMissed);
  image.lit.assign(lights.size(), std::vector<std::uint8_t>(pixels, 0));
  const Tracer tracer(options.packet);
  tbb::task_arena arena = make_arena(options.threads);
  arena.execute([&] {
    build(setup, soup, options, image.stats);
    const auto trace_start = Clock::now();
    if (options.corner_rays) image.corner_hits = corner_hits(setup, tracer);
    tbb::parallel_for(tbb::blocked_range<std::uint32_t>(0, image.height), [&](const tbb::blocked_range<std::uint32_t>& rows) {
      std::vector<FloatRay> rays;
      std::vector<std::uint32_t> primitives;
      std::vector<float> t;
      std::vector<Vec3> points;
      std::vector<double> offsets;
      std::vector<std::uint8_t> active, occluded;
      for (std::uint32_t r = rows.begin(); r != rows.end(); ++r) {
        const std::size_t base = std::size_t{r} * image.width;
        const std::span<std::uint32_t> hits(image.hit_triangles.data() + base, image.width);
        trace_row(setup, tracer, r, hits, rays, primitives, t, points, offsets);
        shadow_rays(setup, tracer, lights, hits, points, offsets, rays, active, occluded,
                    [&](std::size_t k, std::size_t i, bool blocked) { image.lit[k][base + i] = blocked ? 0 : 255; });
      }
    });
    image.stats.trace_seconds = seconds_since(trace_start);
  });
  setup.device->check(kFunction);
  const std::uint64_t hit_pixels =
      pixels - static_cast<std::uint64_t>(std::count(image.hit_triangles.begin(), image.hit_triangles.end(), kMissed));
  image.stats.rays = pixels + image.corner_hits.size();
  image.stats.shadow_rays = hit_pixels * lights.size();
  image.stats.seconds = seconds_since(start);
  return image;
}

RayTracedSoftImage ray_traced_soft_image(const Soup& soup, std::span<const Light> samples, const Camera& camera,
                                         const RayTracedImageOptions& options) {
  constexpr const char* kFunction = "ray_traced_soft_image";
  const auto start = Clock::now();
  if (samples.empty()) throw std::invalid_argument(std::string(kFunction) + ": no sample light");
  check_inputs(soup, samples, camera, options, kFunction);
  TraceSetup setup;
  setup.frame = camera_frame(camera, kFunction);
  setup.offset = options.shadow_ray_offset * bounds_diagonal(soup);
  RayTracedSoftImage image;
  image.width = setup.frame.width;
  image.height = setup.frame.height;
  image.samples = static_cast<std::uint32_t>(samples.size());
  const std::size_t pixels = std::size_t{image.width} * image.height;
  image.hit_triangles.assign(pixels, kMissed);
  image.lit_samples.assign(pixels, 0);
  image.light.assign(pixels, kNoLight);
  const Tracer tracer(options.packet);
  tbb::task_arena arena = make_arena(options.threads);
  arena.execute([&] {
    build(setup, soup, options, image.stats);
    const auto trace_start = Clock::now();
    tbb::parallel_for(tbb::blocked_range<std::uint32_t>(0, image.height), [&](const tbb::blocked_range<std::uint32_t>& rows) {
      std::vector<FloatRay> rays;
      std::vector<std::uint32_t> primitives;
      std::vector<float> t;
      std::vector<Vec3> points;
      std::vector<double> offsets;
      std::vector<std::uint8_t> active, occluded;
      for (std::uint32_t r = rows.begin(); r != rows.end(); ++r) {
        const std::size_t base = std::size_t{r} * image.width;
        const std::span<std::uint32_t> hits(image.hit_triangles.data() + base, image.width);
        trace_row(setup, tracer, r, hits, rays, primitives, t, points, offsets);
        shadow_rays(setup, tracer, samples, hits, points, offsets, rays, active, occluded,
                    [&](std::size_t, std::size_t i, bool blocked) { image.lit_samples[base + i] += blocked ? 0 : 1; });
        for (std::uint32_t i = 0; i < image.width; ++i)
          if (hits[i] != kMissed)
            image.light[base + i] = static_cast<float>(image.lit_samples[base + i]) / static_cast<float>(image.samples);
      }
    });
    image.stats.trace_seconds = seconds_since(trace_start);
  });
  setup.device->check(kFunction);
  const std::uint64_t hit_pixels =
      pixels - static_cast<std::uint64_t>(std::count(image.hit_triangles.begin(), image.hit_triangles.end(), kMissed));
  image.stats.rays = pixels;
  image.stats.shadow_rays = hit_pixels * samples.size();
  image.stats.seconds = seconds_since(start);
  return image;
}

}  // namespace shadowcert::raytrace
