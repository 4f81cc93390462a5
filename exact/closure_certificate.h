#pragma once
// Certificate 1 of docs/definitions.md#certificates: the chain is closed (watertight) iff every directed edge's
// signed count cancels: for each vertex pair {a, b}, uses a->b equal uses b->a over all faces.
#include <cstdint>
#include <vector>

#include "exact/shadow_volume_chain.h"

namespace shadowcert {

struct UnbalancedEdge {
  std::uint32_t from = 0, to = 0;  // chain vertex ids (far ids as in shadow_volume_chain.h), from < to
  std::int64_t excess = 0;         // uses from->to minus uses to->from; never zero here
};

struct ClosureCertificate {
  bool closed = false;
  std::vector<UnbalancedEdge> unbalanced;  // sorted by (from, to); empty iff closed
};

[[nodiscard]] ClosureCertificate certify_closure(const ShadowVolumeChain& chain);

}  // namespace shadowcert
