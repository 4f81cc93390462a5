// The edge-map score tables (docs/edge-maps.md#scores): each GL filter (diagonal, c1, sobel;
// gpu/edge_map.h) against the exact ground truth (reference/edge_ground_truth.h), per class
// (profile, inner, any) and tolerance (1 px, 2 px, the benchmark's bsds), printed as markdown
// for each --resolution (default 512x384 and 1024x768) and every scene: the SYNTHETIC scenes (a
// box, a cylinder of 32 sides, an L-shaped prism with a concave crease, a uv sphere 32x16, an
// icosphere, the box seen low over a wide floor (grazing), data/scenes/default.json) and the
// REAL ones (the meshes of ../shared/data/, each framed over a floor by scene/framed_scene.h's
// rule, and the Stanford bunny low over a wide floor). Thresholds are never tuned on the scene
// they score: per filter, class and tolerance the main figures leave one scene out (each scene
// scored at the threshold with the best F1 on all the others, counts summed); beside them the
// real scenes at the threshold best on the synthetic ones, and their own best (an oracle); the
// thresholds the folds chose, each with the scenes whose fold chose it when it is not the most
// chosen. Before them, every scene at the filters' default thresholds (`shadowcert edges`'s,
// fixed in advance: nothing fitted at all). Then F1 per scene, and the curve over thresholds of
// the real scenes.
// The passes' cost (G-buffer, filter, composite at 1024x768 and 1920x1080) is measured by
// bench/edge_map_bench.cpp (docs/edge-maps.md#timing): this program registers no benchmark; it
// takes Google Benchmark's flags only to report an unknown one. Progress and the ground truth's
// time per scene go to stderr.
//
//   edge_score_bench [--resolution=WxH ...] [--quick] [--pictures=DIR]
// --quick: the synthetic scenes and three real meshes only. --pictures=DIR: per scene the truth
// and each filter's intensities and verdicts (1 px, at the filter's default thresholds) as PNG.
#include <benchmark/benchmark.h>
#include <fmt/core.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <functional>
#include <iostream>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/near_plane.h"
#include "core/scene.h"
#include "gpu/egl_context.h"
#include "io/scene_input.h"
#include "gpu/png_image.h"
#include "io/soup_file.h"
#include "pipeline/edge_map_pictures.h"
#include "pipeline/edge_map_comparison.h"
#include "scene/framed_scene.h"
#include "scene/procedural_mesh.h"

#include "gl_bench_main.h"

namespace {

using namespace shadowcert;
namespace fs = std::filesystem;

struct Settings {
  std::vector<std::array<std::uint32_t, 2>> resolutions;
  bool quick = false;
  std::string pictures;  // --pictures=DIR: per scene and resolution, the truth and each filter's verdicts
};

// A closed cylinder around y: `segments` side quads, caps as fans around their centres.
Soup cylinder(std::uint32_t segments, double radius, double height) {
  Soup s;
  constexpr double kPi = 3.14159265358979323846;
  for (std::uint32_t k = 0; k < segments; ++k) {
    const double a = 2.0 * kPi * k / segments;
    s.vertices.push_back({radius * std::cos(a), 0.0, radius * std::sin(a)});
    s.vertices.push_back({radius * std::cos(a), height, radius * std::sin(a)});
  }
  const auto bottom_centre = static_cast<std::uint32_t>(s.vertices.size());
  s.vertices.push_back({0.0, 0.0, 0.0});
  s.vertices.push_back({0.0, height, 0.0});
  for (std::uint32_t k = 0; k < segments; ++k) {
    const std::uint32_t a = 2 * k, b = 2 * ((k + 1) % segments);
    s.triangles.push_back({a, a + 1, b + 1});  // outward: counter-clockwise seen from outside
    s.triangles.push_back({a, b + 1, b});
    s.triangles.push_back({bottom_centre, a, b});
    s.triangles.push_back({bottom_centre + 1, b + 1, a + 1});
  }
  return s;
}

// A closed prism over an L-shaped polygon (six corners, one reflex): its sides meet at 90
// degrees, convex at five corners and concave at the sixth (a valley crease).
Soup l_prism() {
  const std::array<std::array<double, 2>, 6> l{{{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}}};
  Soup s;
  for (const auto& [x, z] : l) s.vertices.push_back({x, 0.0, z});
  for (const auto& [x, z] : l) s.vertices.push_back({x, 1.0, z});
  for (std::uint32_t k = 0; k < 6; ++k) {
    const std::uint32_t a = k, b = (k + 1) % 6;
    s.triangles.push_back({a, b, b + 6});
    s.triangles.push_back({a, b + 6, a + 6});
  }
  // Caps: the L split at the reflex corner (3) into quads (0, 1, 2, 3) and (0, 3, 4, 5).
  for (const Triangle& t : std::vector<Triangle>{{0, 2, 1}, {0, 3, 2}, {0, 5, 4}, {0, 4, 3}}) {
    s.triangles.push_back(t);
    s.triangles.push_back({t[0] + 6, t[2] + 6, t[1] + 6});
  }
  return s;
}

struct SceneCase {
  std::string name;
  bool training = false;
  std::function<Scene(std::uint32_t, std::uint32_t)> make;
};

std::vector<std::string> shared_meshes() {
  const fs::path root(SHADOWCERT_SHARED_DATA);
  std::vector<std::string> out;
  if (!fs::exists(root)) return out;
  for (const auto& entry : fs::recursive_directory_iterator(root)) {
    if (!entry.is_regular_file()) continue;
    const std::string ext = entry.path().extension().string();
    if (ext == ".obj" || ext == ".ply" || ext == ".stl" || ext == ".STL" || ext == ".off")
      out.push_back(fs::relative(entry.path(), root).string());
  }
  std::sort(out.begin(), out.end());
  return out;
}

Scene framed(const Soup& soup, const std::string& name, std::uint32_t w, std::uint32_t h) {
  FramedMeshOptions options;
  options.width = w;
  options.height = h;
  return framed_mesh_scene(soup, name, options);
}

// `mesh` on a floor 40 r wide (r its half diagonal), seen from 0.15 r above the floor, 2.4 r
// and 3.2 r off its centre: the floor beyond it at grazing angles (incidence above 80 degrees
// from about a mesh size away), where depth-based outlines are known to draw false edges.
Scene grazing_view(const Soup& mesh, const std::string& name, std::uint32_t w, std::uint32_t h) {
  Scene scene = framed(mesh, name, w, h);
  SceneMesh& floor = scene.meshes.back();
  const Vec3 c = scene.camera.target;
  const double y = floor.soup.vertices.front()[1];
  const double r = (floor.soup.vertices[2][0] - c[0]) / 3.0;
  floor.soup.vertices = {{c[0] - 20 * r, y, c[2] - 20 * r}, {c[0] - 20 * r, y, c[2] + 20 * r},
                         {c[0] + 20 * r, y, c[2] + 20 * r}, {c[0] + 20 * r, y, c[2] - 20 * r}};
  scene.camera.eye = {c[0] + 2.4 * r, y + 0.15 * r, c[2] + 3.2 * r};
  scene.camera = camera_fitted_to(scene);
  return scene;
}

std::vector<SceneCase> scene_cases(bool quick) {
  std::vector<SceneCase> cases;
  const auto synthetic = [&](std::string name, Soup soup) {
    cases.push_back({name, true, [soup, name](std::uint32_t w, std::uint32_t h) { return framed(soup, name, w, h); }});
  };
  synthetic("box", box({0.0, 0.0, 0.0}, {1.0, 0.75, 1.25}));
  synthetic("cylinder32", cylinder(32, 0.5, 1.0));
  synthetic("l_prism", l_prism());
  Soup sphere = uv_sphere({0.0, 0.0, 0.0}, 1.0, 32, 16);
  synthetic("uv_sphere32x16", sphere);
  synthetic("icosphere3", icosphere({0.0, 0.0, 0.0}, 1.0, 3));
  const Soup grazing_box = box({0.0, 0.0, 0.0}, {1.0, 0.75, 1.25});
  cases.push_back({"box, grazing floor", true, [grazing_box](std::uint32_t w, std::uint32_t h) {
                     return grazing_view(grazing_box, "box", w, h);
                   }});
  cases.push_back({"default.json", true, [](std::uint32_t w, std::uint32_t h) {
                     Scene s = load_scene_or_mesh(fs::path(SHADOWCERT_SOURCE_DIR) / "data/scenes/default.json");
                     s.camera.width = w;
                     s.camera.height = h;
                     return s;
                   }});
  std::vector<std::string> meshes = shared_meshes();
  if (quick) {
    std::vector<std::string> few;
    for (const std::string& m : meshes)
      if (m.find("stanford-bunny") != std::string::npos || m.find("spot") != std::string::npos ||
          m.find("featuretype") != std::string::npos)
        few.push_back(m);
    meshes = few;
  }
  for (const std::string& m : meshes) {
    cases.push_back({m, false, [m](std::uint32_t w, std::uint32_t h) {
                       return framed(read_soup(fs::path(SHADOWCERT_SHARED_DATA) / m), m, w, h);
                     }});
  }
  const fs::path bunny = fs::path(SHADOWCERT_SHARED_DATA) / "soups/stanford-bunny.obj";
  if (fs::exists(bunny))
    cases.push_back({"soups/stanford-bunny.obj, grazing floor", false, [bunny](std::uint32_t w, std::uint32_t h) {
                       return grazing_view(read_soup(bunny), "stanford-bunny", w, h);
                     }});
  return cases;
}

struct CaseResult {
  std::string name;
  bool training = false;
  std::size_t triangles = 0;
  EdgeGroundTruthStats truth_stats;
  std::uint64_t profile_pixels = 0, inner_pixels = 0, excluded_pixels = 0, grazing_pixels = 0;
  // curves[filter][class][tolerance][threshold]
  std::vector<std::array<std::vector<std::vector<EdgeMatchCounts>>, kEdgeClasses.size()>> curves;
  // at_default[filter][class][tolerance]: the counts at the filter's default thresholds, those
  // `shadowcert edges` draws with (default_edge_channel_thresholds: nothing fitted).
  std::vector<std::array<std::vector<EdgeMatchCounts>, kEdgeClasses.size()>> at_default;
};

std::string filter_name(gpu::EdgeFilter f) { return std::string(gpu::edge_filter_name(f)); }

EdgeMatchCounts summed(const std::vector<CaseResult>& results, bool training, std::size_t filter, std::size_t cls,
                       std::size_t tolerance, std::size_t threshold) {
  EdgeMatchCounts sum;
  for (const CaseResult& r : results)
    if (r.training == training) sum += r.curves[filter][cls][tolerance][threshold];
  return sum;
}

// Leave one scene out: each scene scored at the threshold best on all the others (counts summed
// over them), the sums over every scene.
std::size_t left_out_threshold(const std::vector<CaseResult>& results, std::size_t i, std::size_t filter,
                               std::size_t cls, std::size_t tolerance) {
  std::vector<std::vector<EdgeMatchCounts>> others;
  for (std::size_t j = 0; j < results.size(); ++j)
    if (j != i) others.push_back(results[j].curves[filter][cls][tolerance]);
  return others.empty() ? 0 : best_threshold(others);
}

EdgeMatchCounts leave_one_out(const std::vector<CaseResult>& results, std::size_t filter, std::size_t cls,
                              std::size_t tolerance) {
  EdgeMatchCounts sum;
  for (std::size_t i = 0; i < results.size(); ++i)
    sum += results[i].curves[filter][cls][tolerance][left_out_threshold(results, i, filter, cls, tolerance)];
  return sum;
}

// The threshold each leave-one-scene-out fold chose, every one with its count of folds, the most
// chosen first, and for the others the scenes whose folds chose them: "0.04 (26)", or
// "0.04 (25), 0.05 (1: box)".
std::string fold_thresholds(const std::vector<CaseResult>& results, std::size_t filter, std::size_t cls,
                            std::size_t tolerance, const std::vector<double>& thresholds) {
  std::vector<std::vector<std::string>> scenes(thresholds.size());
  for (std::size_t i = 0; i < results.size(); ++i)
    scenes[left_out_threshold(results, i, filter, cls, tolerance)].push_back(results[i].name);
  std::vector<std::size_t> order(thresholds.size());
  for (std::size_t k = 0; k < order.size(); ++k) order[k] = k;
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return scenes[a].size() > scenes[b].size(); });
  std::string out;
  for (std::size_t n = 0; n < order.size() && !scenes[order[n]].empty(); ++n) {
    const std::vector<std::string>& names = scenes[order[n]];
    out += fmt::format("{}{:g} ({}", n == 0 ? "" : ", ", thresholds[order[n]], names.size());
    if (n > 0)
      for (std::size_t j = 0; j < names.size(); ++j) out += (j == 0 ? ": " : "; ") + names[j];
    out += ")";
  }
  return out;
}

EdgeMatchCounts summed_at_default(const std::vector<CaseResult>& results, std::optional<bool> training,
                                  std::size_t filter, std::size_t cls, std::size_t tolerance) {
  EdgeMatchCounts sum;
  for (const CaseResult& r : results)
    if (!training || r.training == *training) sum += r.at_default[filter][cls][tolerance];
  return sum;
}

std::size_t best_on_all(const std::vector<CaseResult>& results, std::size_t filter, std::size_t cls,
                        std::size_t tolerance) {
  std::vector<std::vector<EdgeMatchCounts>> curves;
  for (const CaseResult& r : results) curves.push_back(r.curves[filter][cls][tolerance]);
  return best_threshold(curves);
}

std::size_t best_on(const std::vector<CaseResult>& results, bool training, std::size_t filter, std::size_t cls,
                    std::size_t tolerance) {
  std::vector<std::vector<EdgeMatchCounts>> curves;
  for (const CaseResult& r : results)
    if (r.training == training) curves.push_back(r.curves[filter][cls][tolerance]);
  return curves.empty() ? 0 : best_threshold(curves);
}

// The truth, and per filter and class the intensities and the verdicts at 1 px at the
// filter's default threshold (gpu/edge_map.h: a depth step of kDefaultEdgeDepthStep, a crease
// of kDefaultEdgeCreaseAngleDegrees), as PNG files in `dir`.
void write_pictures(const std::string& dir, const EdgeMapComparison& c, const std::string& scene, std::uint32_t w,
                    std::uint32_t h) {
  std::string stem = scene;
  for (char& ch : stem)
    if (!std::isalnum(static_cast<unsigned char>(ch)) && ch != '.' && ch != '-') ch = '_';
  stem = fmt::format("{}/{}_{}x{}", dir, stem, w, h);
  fs::create_directories(dir);
  gpu::write_png(stem + "_truth.png", edge_truth_picture(c.truth));
  for (const EdgeFilterRun& run : c.runs)
    for (const EdgeClass k : {EdgeClass::profile, EdgeClass::inner}) {
      const bool inner = k == EdgeClass::inner;
      const double threshold = inner ? gpu::inner_threshold(run.filter, gpu::kDefaultEdgeCreaseAngleDegrees)
                                     : gpu::profile_threshold(run.filter, gpu::kDefaultEdgeDepthStep);
      const EdgeClassImages images = edge_class_images(c.truth, run.map, k);
      const std::span<const float> intensity = images.intensity;
      const EdgeScoreInput input{c.truth.width, c.truth.height, images.truth, c.truth.grazing, intensity};
      const std::string name = fmt::format("{}_{}_{}", stem, filter_name(run.filter), edge_class_name(k));
      gpu::write_png(name + "_map.png", edge_intensity_picture(intensity, c.truth.width, c.truth.height));
      gpu::write_png(name + "_verdicts.png", edge_verdict_picture(c.truth, edge_verdicts(input, 1, threshold)));
    }
}

void print_tables(const Settings& settings) {
  const EdgeMapComparisonOptions options;
  const std::vector<SceneCase> cases = scene_cases(settings.quick);
  for (const auto& [w, h] : settings.resolutions) {
    std::vector<CaseResult> results;
    for (const SceneCase& c : cases) {
      const auto start = std::chrono::steady_clock::now();
      Scene scene;
      try {
        scene = c.make(w, h);
      } catch (const std::exception& e) {
        std::cerr << "edge_score_bench: " << c.name << ": " << e.what() << '\n';
        continue;
      }
      EdgeMapComparison comparison = compare_edge_maps(scene, options);
      CaseResult r;
      r.name = c.name;
      r.training = c.training;
      for (const SceneMesh& m : scene.meshes) r.triangles += m.soup.triangles.size();
      r.truth_stats = comparison.truth.stats;
      for (std::size_t p = 0; p < comparison.truth.profile.size(); ++p) {
        r.profile_pixels += comparison.truth.profile[p] == EdgeTruth::edge;
        r.inner_pixels += comparison.truth.inner[p] == EdgeTruth::edge;
        r.excluded_pixels +=
            comparison.truth.profile[p] == EdgeTruth::excluded || comparison.truth.inner[p] == EdgeTruth::excluded;
        r.grazing_pixels += comparison.truth.grazing[p];
      }
      if (!settings.pictures.empty()) write_pictures(settings.pictures, comparison, c.name, w, h);
      for (EdgeFilterRun& run : comparison.runs) {
        const EdgeChannelThresholds fixed = default_edge_channel_thresholds(run.filter, options.crease_degrees);
        auto& at = r.at_default.emplace_back();
        for (std::size_t k = 0; k < kEdgeClasses.size(); ++k)
          at[k] = score_at_thresholds(comparison.truth, run.map, kEdgeClasses[k], fixed, options.tolerances);
        r.curves.push_back(std::move(run.curves));
      }
      const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      std::cerr << fmt::format("{}x{} {:<48} truth {:6.2f} s (classes {:.2f}, hits {:.2f}, visibility {:.2f}), all {:6.2f} s\n", w, h,
                               c.name, r.truth_stats.seconds, r.truth_stats.class_seconds, r.truth_stats.image_seconds,
                               r.truth_stats.visibility_seconds, seconds);
      results.push_back(std::move(r));
    }
    const std::vector<double>& t = options.thresholds;
    const std::vector<EdgeTolerance>& tol = options.tolerances;
    std::cout << fmt::format("\n### {}x{}\n\n", w, h);
    // The scenes.
    std::cout << "| scene | set | triangles | profile px | inner px | excluded px | grazing px | truth s |\n";
    std::cout << "| --- | --- | --- | --- | --- | --- | --- | --- |\n";
    for (const CaseResult& r : results)
      std::cout << fmt::format("| {} | {} | {} | {} | {} | {} | {} | {:.2f} |\n", r.name, r.training ? "train" : "test",
                               r.triangles, r.profile_pixels, r.inner_pixels, r.excluded_pixels, r.grazing_pixels,
                               r.truth_stats.seconds);
    // At the default thresholds: nothing fitted, every scene out of sample.
    std::cout << "\nAt the default thresholds (`shadowcert edges`'s: a 2 % depth step, a 30-degree crease; "
                 "nothing fitted), counts summed over every scene:\n\n"
                 "| filter | class | thresholds (profile, inner) | tolerance | P | R | F1 | real F1 | "
                 "grazing false / grazing px |\n";
    std::cout << "| --- | --- | --- | --- | --- | --- | --- | --- | --- |\n";
    for (std::size_t f = 0; f < options.filters.size(); ++f) {
      const EdgeChannelThresholds fixed = default_edge_channel_thresholds(options.filters[f], options.crease_degrees);
      for (std::size_t c = 0; c < kEdgeClasses.size(); ++c)
        for (std::size_t k = 0; k < tol.size(); ++k) {
          const EdgeMatchCounts all = summed_at_default(results, std::nullopt, f, c, k);
          const EdgeMatchCounts real = summed_at_default(results, false, f, c, k);
          const std::string used = kEdgeClasses[c] == EdgeClass::profile ? fmt::format("{:.4g}", fixed.profile)
                                   : kEdgeClasses[c] == EdgeClass::inner
                                       ? fmt::format("{:.4g}", fixed.inner)
                                       : fmt::format("{:.4g}, {:.4g}", fixed.profile, fixed.inner);
          std::cout << fmt::format("| {} | {} | {} | {} | {:.3f} | {:.3f} | {:.3f} | {:.3f} | {} / {} |\n",
                                   filter_name(options.filters[f]), edge_class_name(kEdgeClasses[c]), used,
                                   tol[k].name(), all.precision(), all.recall(), all.f1(), real.f1(), all.grazing_false,
                                   all.grazing_pixels);
        }
    }
    // Leave one scene out over every scene; the synthetic -> real split; the oracle.
    std::cout << "\nLeave one scene out (each scene at the threshold best on all the others, counts summed):\n\n"
                 "| filter | class | tolerance | P | R | F1 | detections / truth px | threshold (all scenes) | "
                 "thresholds the folds chose (folds) | "
                 "real F1, threshold from synthetic | real F1, best threshold (oracle) | grazing false / grazing px |\n";
    std::cout << "| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |\n";
    for (std::size_t f = 0; f < options.filters.size(); ++f)
      for (std::size_t c = 0; c < kEdgeClasses.size(); ++c)
        for (std::size_t k = 0; k < tol.size(); ++k) {
          const EdgeMatchCounts loo = leave_one_out(results, f, c, k);
          const std::size_t all = best_on_all(results, f, c, k);
          const std::size_t best = best_on(results, true, f, c, k);
          const EdgeMatchCounts test = summed(results, false, f, c, k, best);
          const std::size_t oracle = best_on(results, false, f, c, k);
          const EdgeMatchCounts test_best = summed(results, false, f, c, k, oracle);
          std::cout << fmt::format(
              "| {} | {} | {} | {:.3f} | {:.3f} | {:.3f} | {:.2f} | {:g} | {} | {:.3f} ({:g}) | {:.3f} ({:g}) | {} / {} |\n",
              filter_name(options.filters[f]), edge_class_name(kEdgeClasses[c]), tol[k].name(), loo.precision(),
              loo.recall(), loo.f1(),
              loo.truth == 0 ? 0.0 : static_cast<double>(loo.detections) / static_cast<double>(loo.truth), t[all],
              fold_thresholds(results, f, c, k, t), test.f1(), t[best], test_best.f1(), t[oracle], loo.grazing_false,
              loo.grazing_pixels);
        }
    // Per scene, F1 at 1 px at the threshold best on the other scenes: profile / inner / any.
    std::cout << "\nF1 per scene at 1 px, each filter at the thresholds best on the other scenes (profile / inner / "
                 "any; - : no truth and no detection):\n\n| scene |";
    for (const gpu::EdgeFilter f : options.filters) std::cout << fmt::format(" {} |", filter_name(f));
    std::cout << "\n| --- |";
    for (std::size_t f = 0; f < options.filters.size(); ++f) std::cout << " --- |";
    std::cout << '\n';
    for (std::size_t i = 0; i < results.size(); ++i) {
      const CaseResult& r = results[i];
      std::cout << "| " << r.name << " |";
      for (std::size_t f = 0; f < options.filters.size(); ++f) {
        std::string cell;
        for (std::size_t c = 0; c < kEdgeClasses.size(); ++c) {
          const std::size_t best = left_out_threshold(results, i, f, c, 0);
          const EdgeMatchCounts& m = r.curves[f][c][0][best];
          cell += (c == 0 ? " " : " / ") + (m.truth == 0 && m.detections == 0 ? std::string("-") : fmt::format("{:.2f}", m.f1()));
        }
        std::cout << cell << " |";
      }
      std::cout << '\n';
    }
    // The test set's curves at 1 px: F1 per threshold.
    std::cout << "\nTest set, 1 px, F1 per threshold (counts summed over the test scenes):\n\n| threshold |";
    for (const gpu::EdgeFilter f : options.filters)
      for (const EdgeClass k : kEdgeClasses) std::cout << fmt::format(" {} {} |", filter_name(f), edge_class_name(k));
    std::cout << "\n| --- |";
    for (std::size_t f = 0; f < options.filters.size() * kEdgeClasses.size(); ++f) std::cout << " --- |";
    std::cout << '\n';
    for (std::size_t i = 0; i < t.size(); ++i) {
      std::cout << fmt::format("| {:g} |", t[i]);
      for (std::size_t f = 0; f < options.filters.size(); ++f)
        for (std::size_t c = 0; c < kEdgeClasses.size(); ++c)
          std::cout << fmt::format(" {:.3f} |", summed(results, false, f, c, 0, i).f1());
      std::cout << '\n';
    }
    std::cout.flush();
  }
}

Settings take_settings(int& argc, char** argv) {
  Settings settings;
  int kept = 1;
  for (int i = 1; i < argc; ++i) {
    const std::string_view arg = argv[i];
    if (const auto size = bench::flag_value(arg, "--resolution=")) {
      settings.resolutions.push_back(bench::image_size(*size, "--resolution"));
    } else if (const auto pictures = bench::flag_value(arg, "--pictures=")) {
      settings.pictures = *pictures;
    } else if (arg == "--quick") {
      settings.quick = true;
    } else {
      argv[kept++] = argv[i];
    }
  }
  argc = kept;
  if (settings.resolutions.empty()) settings.resolutions = {{512, 384}, {1024, 768}};
  return settings;
}

}  // namespace

int main(int argc, char** argv) {
  Settings settings;
  if (!bench::take_command_line("edge_score_bench", argc, argv, settings, take_settings)) return 2;
  const std::optional<gpu::EglContext> context = bench::open_bench_context("edge_score_bench");
  if (!context) return 2;
  std::cerr << "renderer: " << context->renderer() << '\n';
  try {
    print_tables(settings);
  } catch (const std::exception& e) {
    std::cerr << "edge_score_bench: " << e.what() << '\n';
    return 1;
  }
  benchmark::Shutdown();
  return 0;
}
