#pragma once
// Per-edge multiplicities (docs/definitions.md#counts) by four methods, each a pure function over the same
// canonical soup and edge table:
//   m(u, v) = - sum over triangles {u, v, o} with s != 0 of sign D(u, v, o, L)
// together with the sign each triangle's caps use (zero: the triangle casts nothing).
//   exact   : D's exact sign (exact/light_orientation.h)
//   kim     : per-edge float evaluation of D(u, v, o) (Kim 2008); caps from D(a, b, c) in
//             input order. No consistency: closure can fail.
//   peciva  : per-triangle consistency (Pečiva 2013): a triangle whose three edge evaluations
//             disagree (or are partly zero) is discarded from edges and caps.
//   refedge : one evaluation per triangle on its vertices sorted by the canonical order, edge
//             signs by permutation parity, the same sign for caps (Milet 2014 §2.2, Alg. 2-4).
// Float methods evaluate core/light_side_formula.h in `float` or `double`, as a shader would.
// A triangle with a repeated index has no edge and s = 0 in every method. Sign convention:
// Milet 2014's Algorithm 3 sums +D, the opposite of m here. See docs/multiplicities.md.
// Every function below throws std::invalid_argument("<function>: ...") on a light with a
// non-finite coordinate, w not 0 or 1, or direction (0, 0, 0), and on a table whose sizes do
// not fit the soup. Precondition: `table` is build_edge_table(canonical).
#include <cstdint>
#include <string_view>
#include <vector>

#include "core/light.h"
#include "core/sign.h"
#include "core/soup.h"
#include "scene/edge_table.h"

namespace shadowcert {

enum class MultiplicityMethod { exact, kim, peciva, refedge };
enum class Precision { float32, float64 };  // the arithmetic of float methods

struct EdgeMultiplicities {
  std::vector<std::int32_t> multiplicity;  // per edge of the table
  std::vector<Sign> triangle_sign;         // per soup triangle: the cap sign s(t) actually used
};

[[nodiscard]] EdgeMultiplicities exact_multiplicities(const Soup& canonical, const EdgeTable& table,
                                                      const Light& light);
// The same into `out`, whose vectors are resized in place: a caller that computes many lights'
// multiplicities of one soup (volume/volume_workspace.h) keeps their capacity, so after the
// first call no array proportional to the soup is allocated again.
void exact_multiplicities(const Soup& canonical, const EdgeTable& table, const Light& light, EdgeMultiplicities& out);
// The exact multiplicities of the soup and the light rounded to float (every coordinate once,
// as the GL upload rounds them): the CPU twin of the GL volume methods under their default
// exact signs (gpu/sign_mode.h; docs/gpu.md "Exact signs"), which must equal it bit for bit.
[[nodiscard]] EdgeMultiplicities glsign_multiplicities(const Soup& canonical, const EdgeTable& table,
                                                       const Light& light);
[[nodiscard]] EdgeMultiplicities kim_multiplicities(const Soup& canonical, const EdgeTable& table, const Light& light,
                                                    Precision precision);
[[nodiscard]] EdgeMultiplicities peciva_multiplicities(const Soup& canonical, const EdgeTable& table,
                                                       const Light& light, Precision precision);
[[nodiscard]] EdgeMultiplicities refedge_multiplicities(const Soup& canonical, const EdgeTable& table,
                                                        const Light& light, Precision precision);

// Per entry of the table (the order of table.opposite_vertex): the sign the method adds for
// that opposite vertex o of edge (u, v), i.e. sign D(u, v, o, L) as the method evaluates it,
// zero where it excludes the triangle. multiplicity[e] = - (sum of edge e's entries), computed
// by the very same code path; for tests and diagnostics (precision is ignored by exact).
[[nodiscard]] std::vector<Sign> edge_entry_signs(MultiplicityMethod method, const Soup& canonical,
                                                 const EdgeTable& table, const Light& light, Precision precision);

// Dispatches on `method` (precision is ignored by exact).
[[nodiscard]] EdgeMultiplicities edge_multiplicities(MultiplicityMethod method, const Soup& canonical,
                                                     const EdgeTable& table, const Light& light, Precision precision);

[[nodiscard]] std::string_view method_name(MultiplicityMethod method);
// Throws std::invalid_argument("parse_method: ...") on an unknown name.
[[nodiscard]] MultiplicityMethod parse_method(std::string_view name);

}  // namespace shadowcert
