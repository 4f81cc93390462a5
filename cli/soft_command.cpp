#include "cli/soft_command.h"

#include <fmt/core.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "cli/exit_code.h"
#include "cli/light_image_output.h"
#include "cli/option_values.h"
#include "core/input_error.h"
#include "gpu/png_image.h"
#include "gpu/shadow_map_renderer.h"
#include "io/output_file.h"
#include "io/scene_input.h"
#include "pipeline/soft_reference.h"
#include "pipeline/soft_shadow_comparison.h"
#include "pipeline/soft_shadow_pictures.h"
#include "scene/merged_soup.h"

namespace shadowcert::cli {
namespace {

struct SoftOptions {
  std::string input;
  std::optional<double> radius;  // empty: gpu::default_light_radius of the scene's bounds, as pcss
  double angle = gpu::kDefaultLightAngleDegrees;  // a directional light's angular radius, degrees
  std::uint32_t samples = kReferenceDiskSamples;
  std::uint64_t seed = kDefaultDiskSeed;
  std::size_t light = 0;
  std::string size;
  double contact_pixels = kContactPixels;
  std::string out;
  std::string regions;
  std::string json_file;
};

bool perfect_square(std::uint32_t k) {
  const auto n = static_cast<std::uint64_t>(std::llround(std::sqrt(static_cast<double>(k))));
  return k >= 1 && n * n == k;
}

nlohmann::json light_json(const Light& l) { return {l.position[0], l.position[1], l.position[2], l.position[3]}; }

int run_soft(const SoftOptions& options) {
  if (options.radius && !(std::isfinite(*options.radius) && *options.radius >= 0.0))
    throw CLI::ValidationError("--radius", fmt::format("must be finite and >= 0, got {}", *options.radius));
  check_light_angle(options.angle, true);
  if (!perfect_square(options.samples))
    throw CLI::ValidationError("--samples", fmt::format("must be a perfect square n x n >= 1 (64 = 8 x 8 is the "
                                                        "reference), got {}", options.samples));
  if (!(std::isfinite(options.contact_pixels) && options.contact_pixels >= 0.0))
    throw CLI::ValidationError("--contact-pixels", fmt::format("must be finite and >= 0, got {}", options.contact_pixels));
  Scene scene = load_image_scene(options.input);
  if (scene.lights.empty()) throw InputError(options.input, "the scene has no light");
  if (options.light >= scene.lights.size())
    throw CLI::ValidationError("--light", fmt::format("the scene has {} light(s), got {}", scene.lights.size(), options.light));
  apply_image_size(options.size, scene.camera);
  const Soup merged = merged_soup(scene);
  if (merged.triangles.empty()) throw InputError(options.input, "no triangle to image");
  const Light& light = scene.lights[options.light];
  // A point light at the centre of the bounds has no direction for its disk to face: its samples
  // fill the ball whose every projection is that disk (reference/disk_light.h).
  const bool ball = [&] {
    const Vec3 c = scene_bounds_centre(merged);
    return !light.directional() && c[0] == light.position[0] && c[1] == light.position[1] && c[2] == light.position[2];
  }();

  SoftReferenceOptions reference_options;
  reference_options.sampling.radius = options.radius.value_or(gpu::default_light_radius(gpu::soup_bounds(merged)));
  reference_options.sampling.angle_degrees = options.angle;
  reference_options.sampling.samples = options.samples;
  reference_options.sampling.seed = options.seed;
  reference_options.contact_pixels = options.contact_pixels;
  // A progress bar only on a terminal: logs and pipes get no carriage returns.
  reference_options.progress = isatty(fileno(stderr)) != 0;
  const SoftReference reference = soft_reference(scene, options.light, reference_options);
  const SoftShadowImage& image = reference.image;
  // A pixel's 95% half-width (pipeline/soft_shadow_comparison.h); 0 for a light without size.
  const double ci95 = reference.hard ? 0.0 : reference_half_width(static_cast<std::uint32_t>(image.samples.size()));

  std::array<std::uint64_t, 5> regions{};  // by SoftRegion
  std::uint64_t contact = 0, facing = 0;
  double light_sum = 0.0;
  for (std::size_t p = 0; p < image.pixels(); ++p) {
    regions[static_cast<std::size_t>(image.region(p))] += 1;
    contact += reference.contact[p];
    facing += image.faces_light[p];
    if (image.light[p] >= 0.0f) light_sum += image.light[p];
  }
  const std::uint64_t with_light = regions[2] + regions[3] + regions[4];
  const double mean_light = with_light == 0 ? 0.0 : light_sum / static_cast<double>(with_light);

  if (!options.out.empty()) write_light_image(options.out, image.width, image.height, image.light);
  if (!options.regions.empty()) {
    create_parent_directories(options.regions);
    gpu::write_png(options.regions, soft_region_image(reference));
  }
  if (!options.json_file.empty()) {
    nlohmann::json samples = nlohmann::json::array();
    for (const Light& s : image.samples) samples.push_back(light_json(s));
    const nlohmann::json summary{
        {"input", options.input},
        {"size", {image.width, image.height}},
        {"light", options.light},
        {"light_position", light_json(light)},
        {"radius", reference_options.sampling.radius},
        {"angle_degrees", reference_options.sampling.angle_degrees},
        {"light_shape", light.directional() ? "sun" : ball ? "ball" : "disk"},
        {"samples", image.samples.size()},
        {"ci95", ci95},
        {"seed", options.seed},
        {"sample_lights", samples},
        {"triangles", merged.triangles.size()},
        {"seconds", image.stats.seconds},
        {"exact_images", image.stats.exact_images},
        {"tree_seconds", image.stats.tree_seconds},
        {"hit_seconds", image.stats.hit_seconds},
        {"count_seconds", image.stats.count_seconds},
        {"contact_seconds", reference.contact_seconds},
        {"contact_pixels_distance", options.contact_pixels},
        {"pixels",
         {{"no_hit", regions[0]},
          {"undefined", regions[1]},
          {"umbra", regions[2]},
          {"penumbra", regions[3]},
          {"lit", regions[4]},
          {"contact", contact},
          {"faces_light", facing}}},
        {"mean_light", mean_light}};
    write_json_file(options.json_file, summary);
  }

  const std::string shape =
      light.directional() ? fmt::format("directional, a sun of angular radius {:.6g} degrees", options.angle)
      : ball ? fmt::format("point, at the bounds' centre: a ball of radius {:.6g} (every view of it the disk)",
                           reference_options.sampling.radius)
             : fmt::format("point, a disk of radius {:.6g}", reference_options.sampling.radius);
  fmt::print("{}: {} triangles, {}x{}, light {} ({}), {} sample{} (a pixel's 95% half-width {:.3f}; seed {})\n",
             options.input, merged.triangles.size(), image.width, image.height, options.light, shape,
             image.samples.size(), image.samples.size() == 1 ? "" : "s", ci95, options.seed);
  fmt::print("  exact soft reference: {:.2f} s (tree {:.2f}, hits {:.2f}, counts {:.2f}; {} exact image{}), contact "
             "{:.2f} s\n",
             image.stats.seconds, image.stats.tree_seconds, image.stats.hit_seconds, image.stats.count_seconds,
             image.stats.exact_images, image.stats.exact_images == 1 ? "" : "s", reference.contact_seconds);
  fmt::print("  pixels: {} umbra ({} at a contact), {} penumbra, {} lit, {} undefined, {} no hit; mean light {:.4f}\n",
             regions[2], contact, regions[3], regions[4], regions[1], regions[0], mean_light);
  return kExitOk;
}

}  // namespace

void add_soft_command(CLI::App& app, int& exit_code) {
  auto options = std::make_shared<SoftOptions>();
  CLI::App* cmd = app.add_subcommand(
      "soft",
      "The exact soft reference (docs/smoothies.md#the-exact-soft-reference): a disk light of radius R around a "
      "point light (of angular radius --light-angle about a directional one), K stratified samples on it, each "
      "receiver pixel's light the mean of their exact verdicts: an estimate whose 95% half-width per pixel is "
      "1.358 / sqrt(K) (0.170 at K = 64)");
  cmd->add_option("input", options->input, kImageInputHelp)->required();
  cmd->add_option("--radius,--light-radius", options->radius,
                  "A point light's disk radius R in world units, facing the centre of the scene's bounds (a light at "
                  "that centre: a ball of radius R); 0: the exact hard shadow; default 1% of the scene's bounding-box "
                  "diagonal, as render --method pcss");
  cmd->add_option("--light-angle", options->angle, std::string(kLightAngleHelp) + "; 0: the exact hard shadow")
      ->capture_default_str();
  cmd->add_option("--samples", options->samples, "K sample lights, a perfect square n x n (stratified)")
      ->capture_default_str();
  cmd->add_option("--seed", options->seed, "The samples' jitter stream")->capture_default_str();
  cmd->add_option("--light", options->light, "Which light of the scene (0-based)")->capture_default_str();
  cmd->add_option("--size", options->size, "Image size WxH (default: the scene camera's)");
  cmd->add_option("--contact-pixels", options->contact_pixels,
                  "Contact pixels (the leak figure's): umbra within this many pixel widths of a caster")
      ->capture_default_str();
  cmd->add_option("--out", options->out,
                  "Write the light per pixel: FILE.png (8-bit gray, round(255 light), 0 where no light) and FILE.pfm "
                  "beside it (32-bit floats, -1 where no light), as render --light-image");
  cmd->add_option("--regions", options->regions,
                  "Write the regions as a PNG: umbra black (contact red), penumbra gray, lit white, undefined "
                  "yellow, no hit transparent");
  cmd->add_option("--json", options->json_file,
                  "Write the figures (radius, samples and their positions, seconds, pixels per region) as JSON");
  cmd->callback([options, &exit_code] { exit_code = run_soft(*options); });
}

}  // namespace shadowcert::cli
