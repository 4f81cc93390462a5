#include "exact/edge_multiplicity.h"

#include "core/float_rounding.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <cmath>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>

#include "core/huge_page_advice.h"
#include "core/light_side_formula.h"
#include "exact/light_orientation.h"
#include "exact/light_orientation_filter.h"

// Every method below is one "plan": a function giving the sign D(u, v, o, L) that the method
// adds for one edge entry (edge (u, v), u < v, opposite o, triangle t), and the cap sign of
// each triangle. multiplicity[e] = - sum of its entries (docs/definitions.md#counts; Milet 2014's Algorithm 3
// sums +D, the opposite convention). Multiplicities and edge_entry_signs both run a plan
// through the same loop, so what a test sees entry by entry is what the sums use.
//
// Vertex order: the soup is canonical (scene/canonical_soup.h), so index order is the strict
// lexicographic order of positions and "sort a triangle's vertices" means "sort its indices".

namespace shadowcert {
namespace {

// Grain of the parallel loops over edges and triangles: a task's overhead is noise against it.
constexpr std::size_t kEdgeGrain = std::size_t{1} << 14;

bool has_repeated_index(const Triangle& t) { return t[0] == t[1] || t[1] == t[2] || t[2] == t[0]; }

// +1 when (a, b, c) (distinct) is an even permutation of its ascending order, -1 when odd:
// the sign relating D(a, b, c) to D of the sorted triple, since D is alternating.
Sign order_parity(std::uint32_t a, std::uint32_t b, std::uint32_t c) {
  const int inversions = (a > b) + (a > c) + (b > c);
  return inversions % 2 == 0 ? Sign::positive : Sign::negative;
}

// The same for an edge entry (u, v, o) with u < v: only o between u and v makes it odd
// (the three cases of Milet 2014, Algorithm 3).
Sign entry_parity(std::uint32_t u, std::uint32_t v, std::uint32_t o) {
  return (u < o && o < v) ? Sign::negative : Sign::positive;
}

void require_valid(const char* function, const Soup& canonical, const EdgeTable& table, const Light& light) {
  require_defined(light, function);
  const std::size_t entries = table.opposite_vertex.size();
  if (table.first_opposite.size() != table.edges.size() + 1 || table.opposite_triangle.size() != entries ||
      table.first_opposite.back() != entries || entries > 3 * canonical.triangles.size())
    throw std::invalid_argument(std::string(function) + ": the edge table does not belong to this soup");
}

// ---- plans ---------------------------------------------------------------------------------
//
// A plan's entry(u, v, o, t) is called once per table entry, in table order (edges ascending);
// caps() afterwards. Table order visits a triangle {x < y < z} first at its entry
// (u, v, o) = (x, y, z), the only one with o > v: edge (x, y) precedes (x, z) and (y, z). So a
// plan may evaluate a triangle's sorted triple there, once, and reuse the value at the two
// later entries. Walking by ascending lower vertex also keeps the positions it reads within a
// narrow index window (the canonical order is spatial), which is what makes these loops fast.

// The sign D(x, y, z) of each triangle's sorted triple, and what follows from it. The signs
// live in the caller's `storage` (set to zero, one per triangle), so that a caller building
// many volumes of one soup reuses its capacity (exact_multiplicities' overload into an
// EdgeMultiplicities keeps them in its triangle_sign, then turns them into the caps in place).
class SortedSigns {
 public:
  SortedSigns(std::vector<Sign>& storage, std::size_t triangles) : sorted_(storage) {
    sorted_.assign(triangles, Sign::zero);
  }

  void set(std::uint32_t t, Sign s) { sorted_[t] = s; }
  [[nodiscard]] Sign entry(std::uint32_t u, std::uint32_t v, std::uint32_t o, std::uint32_t t) const {
    return sorted_[t] * entry_parity(u, v, o);
  }
  // s(t) = D(a, b, c) in the triangle's own order (zero for repeated indices: no table entry),
  // into `caps`; `caps` may be the storage itself: entry t reads and writes only entry t.
  void caps_into(const Soup& canonical, std::vector<Sign>& caps) const {
    if (&caps != &sorted_) caps.assign(canonical.triangles.size(), Sign::zero);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, caps.size(), kEdgeGrain),
                      [&](const tbb::blocked_range<std::size_t>& r) {
                        for (std::size_t t = r.begin(); t < r.end(); ++t) {
                          const Triangle& tri = canonical.triangles[t];
                          caps[t] = has_repeated_index(tri) ? Sign::zero
                                                            : sorted_[t] * order_parity(tri[0], tri[1], tri[2]);
                        }
                      });
  }
  [[nodiscard]] std::vector<Sign> caps(const Soup& canonical) const {
    std::vector<Sign> caps;
    caps_into(canonical, caps);
    return caps;
  }

 private:
  std::vector<Sign>& sorted_;
};

// Exact: each triangle's exact sign, evaluated once on its sorted triple; every entry and the
// caps derive from it by parity, so the chain is closed by construction (docs/definitions.md#counts). The
// semi-static stage is inlined, so the FPU rounding mode is switched only for the rare
// triangles it cannot certify. The signs are all evaluated first, in parallel, at each
// triangle's entry with o > v (the sorted triple; one per triangle, so each thread writes its
// own triangles' signs): then entries may be read in any order, by any thread.
class ExactPlan {
 public:
  ExactPlan(const Soup& canonical, const EdgeTable& table, const Light& light, std::vector<Sign>& storage)
      : canonical_(canonical), light_(light), signs_(storage, canonical.triangles.size()) {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, table.size(), kEdgeGrain),
                      [&](const tbb::blocked_range<std::size_t>& r) {
                        for (std::size_t e = r.begin(); e < r.end(); ++e) {
                          const std::uint32_t u = table.edges[e][0], v = table.edges[e][1];
                          for (std::uint32_t i = table.first_opposite[e]; i < table.first_opposite[e + 1]; ++i)
                            if (const std::uint32_t o = table.opposite_vertex[i]; o > v)
                              signs_.set(table.opposite_triangle[i], exact_sign(u, v, o));
                        }
                      });
  }

  [[nodiscard]] Sign entry(std::uint32_t u, std::uint32_t v, std::uint32_t o, std::uint32_t t) const {
    return signs_.entry(u, v, o, t);
  }
  [[nodiscard]] std::vector<Sign> caps() const { return signs_.caps(canonical_); }
  void caps_into(std::vector<Sign>& caps) const { signs_.caps_into(canonical_, caps); }

 private:
  [[nodiscard]] Sign exact_sign(std::uint32_t a, std::uint32_t b, std::uint32_t c) const {
    const Vec3 &pa = canonical_.vertices[a], &pb = canonical_.vertices[b], &pc = canonical_.vertices[c];
    const std::optional<Sign> quick = detail::semi_static_light_orientation(pa, pb, pc, light_.position);
    return quick ? *quick : light_orientation(pa, pb, pc, light_);
  }

  const Soup& canonical_;
  const Light& light_;
  SortedSigns signs_;
};

// Float evaluation of core/light_side_formula.h on positions and light rounded to Real, as a
// shader reads them from its buffers.
template <typename Real>
struct FloatSide {
  const std::vector<Vec3>& positions;
  std::array<Real, 4> light;

  FloatSide(const Soup& canonical, const Light& l)
      : positions(canonical.vertices),
        light{static_cast<Real>(l.position[0]), static_cast<Real>(l.position[1]), static_cast<Real>(l.position[2]),
              static_cast<Real>(l.position[3])} {}

  [[nodiscard]] Sign operator()(std::uint32_t a, std::uint32_t b, std::uint32_t c) const {
    return light_side_sign(to_precision<Real>(positions[a]), to_precision<Real>(positions[b]),
                           to_precision<Real>(positions[c]), light);
  }
};

// Kim 2008: every entry evaluated on its own, (u, v, o) with u < v; caps from the triangle in
// input order. Nothing ties the four evaluations of a triangle together.
template <typename Real>
class KimPlan {
 public:
  KimPlan(const Soup& canonical, const Light& light) : side_(canonical, light), caps_(canonical.triangles.size()) {
    for (std::size_t t = 0; t < caps_.size(); ++t) {
      const Triangle& tri = canonical.triangles[t];
      caps_[t] = has_repeated_index(tri) ? Sign::zero : side_(tri[0], tri[1], tri[2]);
    }
  }
  [[nodiscard]] Sign entry(std::uint32_t u, std::uint32_t v, std::uint32_t o, std::uint32_t) const {
    return side_(u, v, o);
  }
  [[nodiscard]] std::vector<Sign> caps() const { return caps_; }

 private:
  FloatSide<Real> side_;
  std::vector<Sign> caps_;
};

// Pečiva 2013: a triangle's three edge evaluations, exactly as kim computes them, turned into
// one common orientation (the sorted triple's) by parity, must all agree: all the same sign,
// or all zero. Otherwise the triangle is discarded from edges and caps (s = 0). Agreement in
// the sorted orientation is agreement in the triangle's own (both differ by one parity).
template <typename Real>
class PecivaPlan {
 public:
  PecivaPlan(const Soup& canonical, const EdgeTable& table, const Light& light)
      : canonical_(canonical), signs_(storage_, canonical.triangles.size()) {
    const FloatSide<Real> side(canonical, light);
    // Per triangle: kUnset, then the first converted value, then kDisagree on a mismatch.
    constexpr std::int8_t kUnset = 2, kDisagree = 3;
    std::vector<std::int8_t> state(canonical.triangles.size(), kUnset);
    for (std::size_t e = 0; e < table.size(); ++e) {
      const std::uint32_t u = table.edges[e][0], v = table.edges[e][1];
      for (std::uint32_t i = table.first_opposite[e]; i < table.first_opposite[e + 1]; ++i) {
        const std::uint32_t o = table.opposite_vertex[i];
        const auto value = static_cast<std::int8_t>(to_int(side(u, v, o) * entry_parity(u, v, o)));
        std::int8_t& s = state[table.opposite_triangle[i]];
        s = s == kUnset ? value : (s == value ? s : kDisagree);
      }
    }
    for (std::size_t t = 0; t < state.size(); ++t)
      signs_.set(static_cast<std::uint32_t>(t), (state[t] == kUnset || state[t] == kDisagree)
                                                     ? Sign::zero
                                                     : static_cast<Sign>(state[t]));
  }
  [[nodiscard]] Sign entry(std::uint32_t u, std::uint32_t v, std::uint32_t o, std::uint32_t t) const {
    return signs_.entry(u, v, o, t);
  }
  [[nodiscard]] std::vector<Sign> caps() const { return signs_.caps(canonical_); }

 private:
  const Soup& canonical_;
  std::vector<Sign> storage_;  // before signs_, which refers to it
  SortedSigns signs_;
};

// Milet 2014, Algorithms 3 and 4: every entry sorts {u, v, o}, evaluates the shared formula on
// the sorted triple and undoes the permutation. The triple is the same at a triangle's three
// entries, so the three values agree bit for bit (tested); the caps use the value of the entry
// where o > v, i.e. the one evaluation of the sorted triple.
template <typename Real>
class RefedgePlan {
 public:
  RefedgePlan(const Soup& canonical, const Light& light)
      : canonical_(canonical), side_(canonical, light), signs_(storage_, canonical.triangles.size()) {}

  Sign entry(std::uint32_t u, std::uint32_t v, std::uint32_t o, std::uint32_t t) {
    if (o < u) return side_(o, u, v);   // (u, v, o) is a rotation of (o, u, v): even
    if (o < v) return -side_(u, o, v);  // one transposition: odd
    const Sign sorted = side_(u, v, o);
    signs_.set(t, sorted);
    return sorted;
  }
  [[nodiscard]] std::vector<Sign> caps() const { return signs_.caps(canonical_); }

 private:
  const Soup& canonical_;
  FloatSide<Real> side_;
  std::vector<Sign> storage_;  // before signs_, which refers to it
  SortedSigns signs_;
};

// ---- running a plan -----------------------------------------------------------------------

// Every plan's entry() may run on any thread in any order: it reads what the plan's
// constructor prepared, or (refedge) writes only its own triangle's sorted sign, at the one
// entry of that triangle with o > v.
template <typename Plan>
// Into `m`, whose capacity is reused (resize_huge advises only new storage).
void sum_entries_into(const EdgeTable& table, Plan& plan, std::vector<std::int32_t>& m) {
  m.clear();
  resize_huge(m, table.size());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, table.size(), kEdgeGrain),
                    [&](const tbb::blocked_range<std::size_t>& r) {
                      for (std::size_t e = r.begin(); e < r.end(); ++e) {
                        const std::uint32_t u = table.edges[e][0], v = table.edges[e][1];
                        std::int32_t sum = 0;
                        for (std::uint32_t i = table.first_opposite[e]; i < table.first_opposite[e + 1]; ++i)
                          sum += to_int(plan.entry(u, v, table.opposite_vertex[i], table.opposite_triangle[i]));
                        m[e] = -sum;  // docs/definitions.md#counts: m = - sum D(u, v, o)
                      }
                    });
}

template <typename Plan>
std::vector<std::int32_t> sum_entries(const EdgeTable& table, Plan& plan) {
  std::vector<std::int32_t> m;
  sum_entries_into(table, plan, m);
  return m;
}

template <typename Plan>
std::vector<Sign> list_entries(const EdgeTable& table, Plan& plan) {
  std::vector<Sign> signs;
  resize_huge(signs, table.opposite_vertex.size());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, table.size(), kEdgeGrain),
                    [&](const tbb::blocked_range<std::size_t>& r) {
                      for (std::size_t e = r.begin(); e < r.end(); ++e) {
                        const std::uint32_t u = table.edges[e][0], v = table.edges[e][1];
                        for (std::uint32_t i = table.first_opposite[e]; i < table.first_opposite[e + 1]; ++i)
                          signs[i] = plan.entry(u, v, table.opposite_vertex[i], table.opposite_triangle[i]);
                      }
                    });
  return signs;
}

template <typename Plan>
EdgeMultiplicities run(const EdgeTable& table, Plan& plan) {
  EdgeMultiplicities out;
  out.multiplicity = sum_entries(table, plan);
  out.triangle_sign = plan.caps();
  return out;
}

// Calls `f` with the plan of (method, precision): the one place that maps names to plans.
template <typename F>
decltype(auto) with_plan(MultiplicityMethod method, Precision precision, const Soup& canonical,
                         const EdgeTable& table, const Light& light, F&& f) {
  const bool single = precision == Precision::float32;
  switch (method) {
    case MultiplicityMethod::exact: {
      std::vector<Sign> storage;
      ExactPlan plan(canonical, table, light, storage);
      return f(plan);
    }
    case MultiplicityMethod::kim: {
      if (single) {
        KimPlan<float> plan(canonical, light);
        return f(plan);
      }
      KimPlan<double> plan(canonical, light);
      return f(plan);
    }
    case MultiplicityMethod::peciva: {
      if (single) {
        PecivaPlan<float> plan(canonical, table, light);
        return f(plan);
      }
      PecivaPlan<double> plan(canonical, table, light);
      return f(plan);
    }
    case MultiplicityMethod::refedge: {
      if (single) {
        RefedgePlan<float> plan(canonical, light);
        return f(plan);
      }
      RefedgePlan<double> plan(canonical, light);
      return f(plan);
    }
  }
  throw std::invalid_argument("edge_multiplicities: unknown method");
}

EdgeMultiplicities multiplicities(const char* function, MultiplicityMethod method, const Soup& canonical,
                                  const EdgeTable& table, const Light& light, Precision precision) {
  require_valid(function, canonical, table, light);
  return with_plan(method, precision, canonical, table, light, [&table](auto& plan) { return run(table, plan); });
}

}  // namespace

EdgeMultiplicities exact_multiplicities(const Soup& canonical, const EdgeTable& table, const Light& light) {
  return multiplicities("exact_multiplicities", MultiplicityMethod::exact, canonical, table, light,
                        Precision::float64);
}

void exact_multiplicities(const Soup& canonical, const EdgeTable& table, const Light& light, EdgeMultiplicities& out) {
  require_valid("exact_multiplicities", canonical, table, light);
  // The sorted signs are kept in out.triangle_sign and become the caps there, in place.
  ExactPlan plan(canonical, table, light, out.triangle_sign);
  sum_entries_into(table, plan, out.multiplicity);
  plan.caps_into(out.triangle_sign);
}

EdgeMultiplicities glsign_multiplicities(const Soup& canonical, const EdgeTable& table, const Light& light) {
  require_valid("glsign_multiplicities", canonical, table, light);
  // Rounding may merge two vertices' positions, never their indices: the table still fits.
  return multiplicities("glsign_multiplicities", MultiplicityMethod::exact, float_rounded(canonical), table,
                        float_rounded(light), Precision::float64);
}

EdgeMultiplicities kim_multiplicities(const Soup& canonical, const EdgeTable& table, const Light& light,
                                      Precision precision) {
  return multiplicities("kim_multiplicities", MultiplicityMethod::kim, canonical, table, light, precision);
}

EdgeMultiplicities peciva_multiplicities(const Soup& canonical, const EdgeTable& table, const Light& light,
                                         Precision precision) {
  return multiplicities("peciva_multiplicities", MultiplicityMethod::peciva, canonical, table, light, precision);
}

EdgeMultiplicities refedge_multiplicities(const Soup& canonical, const EdgeTable& table, const Light& light,
                                          Precision precision) {
  return multiplicities("refedge_multiplicities", MultiplicityMethod::refedge, canonical, table, light, precision);
}

EdgeMultiplicities edge_multiplicities(MultiplicityMethod method, const Soup& canonical, const EdgeTable& table,
                                       const Light& light, Precision precision) {
  return multiplicities("edge_multiplicities", method, canonical, table, light, precision);
}

std::vector<Sign> edge_entry_signs(MultiplicityMethod method, const Soup& canonical, const EdgeTable& table,
                                   const Light& light, Precision precision) {
  require_valid("edge_entry_signs", canonical, table, light);
  return with_plan(method, precision, canonical, table, light,
                   [&table](auto& plan) { return list_entries(table, plan); });
}

std::string_view method_name(MultiplicityMethod method) {
  switch (method) {
    case MultiplicityMethod::exact:
      return "exact";
    case MultiplicityMethod::kim:
      return "kim";
    case MultiplicityMethod::peciva:
      return "peciva";
    case MultiplicityMethod::refedge:
      return "refedge";
  }
  throw std::invalid_argument("method_name: unknown method");
}

MultiplicityMethod parse_method(std::string_view name) {
  for (MultiplicityMethod m :
       {MultiplicityMethod::exact, MultiplicityMethod::kim, MultiplicityMethod::peciva, MultiplicityMethod::refedge})
    if (method_name(m) == name) return m;
  throw std::invalid_argument("parse_method: unknown method '" + std::string(name) +
                              "' (expected exact, kim, peciva or refedge)");
}

}  // namespace shadowcert
