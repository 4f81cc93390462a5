#pragma once
// A campaign reproducer (docs/campaign.md, tests/regressions/README.md): a failing soup, its light
// and the method run, in files that `shadowcert certify` replays bit for bit:
//   NAME.off     the soup (io/soup_file.h: 17 significant digits, read back bitwise equal)
//   NAME.points  for a count failure, the two points of a failing pair, "x y z" per line
//   NAME.json    the light, method, precision, failure, status, provenance and the command
// The command is `shadowcert certify NAME.off --light=X,Y,Z,W --method M --precision P`, plus
// `--samples 0 --points NAME.points` for a count failure: with exactly those two user points,
// certify_counts compares that one pair (both ways), as the campaign did.
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "core/light.h"
#include "core/soup.h"
#include "exact/edge_multiplicity.h"

namespace shadowcert {

struct CampaignReproducer {
  Soup soup;
  Light light;
  MultiplicityMethod method = MultiplicityMethod::exact;
  Precision precision = Precision::float64;
  std::string failure = "closure";  // "closure" (an open chain) or "counts" (a failing pair)
  std::vector<Vec3> points;         // counts: the failing pair; closure: empty
  // "open": a method that must not fail failed (a bug until fixed); "fixed": it did and was
  // fixed (the replay must now pass); "finding": a method allowed to fail (kim) fails here.
  std::string status = "open";
  // Provenance, for the record: the campaign seed, the case index and kind, the triangles
  // before shrinking.
  std::uint64_t seed = 0;
  std::uint64_t case_index = 0;
  std::string family;
  std::string placement;
  std::uint64_t original_triangles = 0;
};

// Writes DIR/NAME.off, .json and (counts) .points, creating DIR; returns the .json path.
// Throws std::runtime_error naming the file when a write fails.
std::filesystem::path write_reproducer(const std::filesystem::path& dir, const std::string& name,
                                            const CampaignReproducer& reproducer);

// Reads NAME.json and the files it names (relative to its folder). Bad content is an
// InputError naming the file (and the line for the JSON and points files).
[[nodiscard]] CampaignReproducer read_reproducer(const std::filesystem::path& json);

// The command line that replays it, with the mesh (and points) at these paths.
[[nodiscard]] std::string certify_command(const CampaignReproducer& reproducer, const std::filesystem::path& mesh,
                                          const std::filesystem::path& points);

struct ReproducerReplay {
  bool closed = false;
  std::uint64_t count_checks = 0;
  std::uint64_t count_failures = 0;
  // The recorded failure happens: an open chain for "closure", a failing check for "counts".
  bool reproduces = false;
};

// What `certify` computes for the reproducer (the same functions: canonical soup, edge table,
// multiplicities, chain, certify_closure, and certify_counts on the points alone).
[[nodiscard]] ReproducerReplay replay_reproducer(const CampaignReproducer& reproducer);

}  // namespace shadowcert
