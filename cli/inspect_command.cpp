#include "cli/inspect_command.h"

#include <fmt/core.h>

#include <algorithm>
#include <fstream>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>

#include "cli/exit_code.h"
#include "io/output_file.h"
#include "io/scene_input.h"
#include "core/input_error.h"
#include "exact/caster_diagnostics.h"
#include "scene/merged_soup.h"

namespace shadowcert::cli {
namespace {

struct InspectOptions {
  std::string input;
  std::string json_file;
};

nlohmann::json to_json(const CasterDiagnostics& d) {
  return {{"vertices", d.vertices},
          {"welded_vertices", d.welded_vertices},
          {"triangles", d.triangles},
          {"degenerate_triangles", d.degenerate_triangles},
          {"duplicate_triangles", d.duplicate_triangles},
          {"edges", d.edges},
          {"border_edges", d.border_edges},
          {"nonmanifold_edges", d.nonmanifold_edges},
          {"nonmanifold_vertices", d.nonmanifold_vertices},
          {"components", d.components},
          {"closed", d.closed},
          {"manifold", d.manifold},
          {"consistently_oriented", d.consistently_oriented},
          {"self_intersecting", d.self_intersecting},
          {"self_intersecting_pairs", d.self_intersecting_pairs},
          {"seconds", d.seconds}};
}

void print_table(const std::string& title, const CasterDiagnostics& d) {
  const auto yes_no = [](bool b) { return b ? "yes" : "no"; };
  fmt::print("{}\n", title);
  fmt::print("  {:<24}{:>14}\n", "vertices", d.vertices);
  fmt::print("  {:<24}{:>14}\n", "welded vertices", d.welded_vertices);
  fmt::print("  {:<24}{:>14}\n", "triangles", d.triangles);
  fmt::print("  {:<24}{:>14}\n", "degenerate triangles", d.degenerate_triangles);
  fmt::print("  {:<24}{:>14}\n", "duplicate triangles", d.duplicate_triangles);
  fmt::print("  {:<24}{:>14}\n", "edges", d.edges);
  fmt::print("  {:<24}{:>14}\n", "border edges", d.border_edges);
  fmt::print("  {:<24}{:>14}\n", "non-manifold edges", d.nonmanifold_edges);
  fmt::print("  {:<24}{:>14}\n", "non-manifold vertices", d.nonmanifold_vertices);
  fmt::print("  {:<24}{:>14}\n", "components", d.components);
  fmt::print("  {:<24}{:>14}\n", "closed", yes_no(d.closed));
  fmt::print("  {:<24}{:>14}\n", "manifold", yes_no(d.manifold));
  fmt::print("  {:<24}{:>14}\n", "consistently oriented", yes_no(d.consistently_oriented));
  fmt::print("  {:<24}{:>14}\n", "self-intersecting", yes_no(d.self_intersecting));
  fmt::print("  {:<24}{:>14}\n", "intersecting pairs", d.self_intersecting_pairs);
  fmt::print("  {:<24}{:>14.3f}\n", "seconds", d.seconds);
}

int run_inspect(const InspectOptions& options) {
  const Scene scene = load_scene_or_mesh(options.input);
  const Soup casters = merged_casters(scene);
  if (casters.triangles.empty()) throw InputError(options.input, "no casting triangle to inspect");

  // The casting meshes together are what a shadow-volume renderer extrudes (a mesh with
  // "casts": false is in no volume, so it is left out); each mesh is listed too so that a
  // defect can be traced to its source, and a receiver is named as such.
  const CasterDiagnostics all = diagnose_caster(casters);
  nlohmann::json report = to_json(all);
  report["input"] = options.input;
  const auto receivers = static_cast<std::size_t>(
      std::count_if(scene.meshes.begin(), scene.meshes.end(), [](const SceneMesh& m) { return !m.casts; }));
  print_table(fmt::format("{} ({} mesh{}{})", options.input, scene.meshes.size(), scene.meshes.size() == 1 ? "" : "es",
                          receivers == 0 ? std::string() : fmt::format(", {} receiving only", receivers)),
              all);
  if (scene.meshes.size() > 1) {
    nlohmann::json meshes = nlohmann::json::array();
    for (const SceneMesh& mesh : scene.meshes) {
      if (!mesh.casts) {
        fmt::print("mesh {}: receives only (\"casts\": false), not diagnosed\n", mesh.name);
        meshes.push_back({{"name", mesh.name}, {"casts", false}});
        continue;
      }
      const CasterDiagnostics d = diagnose_caster(mesh.soup);
      print_table("mesh " + mesh.name, d);
      nlohmann::json entry = to_json(d);
      entry["name"] = mesh.name;
      entry["casts"] = true;
      meshes.push_back(std::move(entry));
    }
    report["meshes"] = std::move(meshes);
  }
  if (!options.json_file.empty()) write_json_file(options.json_file, report);
  return kExitOk;
}

}  // namespace

void add_inspect_command(CLI::App& app, int& exit_code) {
  auto options = std::make_shared<InspectOptions>();
  CLI::App* cmd = app.add_subcommand("inspect", "Caster diagnostics of a mesh or scene (docs/definitions.md#caster-diagnostics)");
  cmd->add_option("input", options->input, "Mesh file (.obj .off .ply .stl) or scene (.json)")->required();
  cmd->add_option("--json", options->json_file, "Write the diagnostics as a JSON object to FILE");
  cmd->callback([options, &exit_code] { exit_code = run_inspect(*options); });
}

}  // namespace shadowcert::cli
