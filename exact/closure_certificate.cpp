#include "exact/closure_certificate.h"

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>

#include "core/huge_page_advice.h"

namespace shadowcert {
namespace {

// Chain vertex ids in use (shadow_volume_chain.h): n finite, then n far (point light) or one.
std::uint64_t id_count(const ShadowVolumeChain& chain) {
  const std::uint64_t n = chain.finite_vertices;
  return chain.directional ? n + 1 : 2 * n;
}

// Faces are numbered triangles first, then quads. Calls f(from, to) for every directed
// boundary edge (right-hand order) of faces [first, last).
template <typename F>
void for_each_directed_edge(const ShadowVolumeChain& chain, std::size_t first, std::size_t last, F&& f) {
  const std::size_t triangles = chain.triangles.size();
  for (std::size_t i = first; i < std::min(last, triangles); ++i) {
    const auto& t = chain.triangles[i];
    f(t[0], t[1]);
    f(t[1], t[2]);
    f(t[2], t[0]);
  }
  for (std::size_t i = std::max(first, triangles); i < last; ++i) {
    const auto& q = chain.quads[i - triangles];
    f(q[0], q[1]);
    f(q[1], q[2]);
    f(q[2], q[3]);
    f(q[3], q[0]);
  }
}

std::size_t face_count(const ShadowVolumeChain& chain) { return chain.triangles.size() + chain.quads.size(); }

// The directed edges (those left once nearby reverse pairs cancel: ChunkKeys below) are sorted
// as packed 64-bit keys
//   (lower id << 33) | (upper id << 1) | (1 if the edge runs upper -> lower),
// by a two-level radix sort whose every pass stays in cache: first into blocks of
// kBlockIds consecutive lower ids (a few hundred sequential output streams), then, block
// by block, by lower id (a counting sort in L1) and by the rest (tiny sorts per vertex).
// Every run of one (lower, upper) is an undirected edge whose uses in each direction must
// balance (docs/definitions.md#closure). A self-loop (a == b, from a face with a repeated vertex) is no
// edge: it bounds nothing.
constexpr unsigned kBlockBits = 12;
constexpr std::uint64_t kBlockIds = std::uint64_t{1} << kBlockBits;

std::uint64_t edge_key(std::uint32_t a, std::uint32_t b) {
  return std::uint64_t{std::min(a, b)} << 33 | std::uint64_t{std::max(a, b)} << 1 | (a > b ? 1u : 0u);
}

// The block of a key's lower id.
std::size_t block_of(std::uint64_t key) { return static_cast<std::size_t>(key >> (33 + kBlockBits)); }

[[noreturn, gnu::noinline, gnu::cold]] void throw_out_of_range(std::uint64_t id, std::uint64_t ids) {
  throw std::invalid_argument("certify_closure: vertex id " + std::to_string(id) + " but the chain has " +
                              std::to_string(ids) + " ids");
}

// In parallel: the faces are cut into fixed chunks (their number depends on the chain, not on
// the threads). Each chunk lists its directed edges' keys, with the pairs a -> b, b -> a it
// meets close together cancelled (ChunkKeys); counts them per block; and chunk c's keys of block
// b go after those of chunks before c, so the key array is the same on any number of threads.
// Blocks are then sorted and reported independently, their reports concatenated in block order.
constexpr std::size_t kChunkFaces = std::size_t{1} << 16;

// A use a -> b and a use b -> a of one edge add nothing to its excess: dropping both changes no
// edge's balance, so the certificate is the same. A chunk's faces mostly come in mesh order (a
// cap's triangles, then its sides), where an edge's two uses by neighbouring faces are close
// together: a small direct-mapped table of the uses not yet matched finds most pairs as they
// come, and only the rest are written, laid out and sorted (on the 1M-triangle sphere grid's
// chain, 2.0M faces: 496K of its 6.1M uses; the closure 30-35 ms -> 14 ms, docs/certificates.md).
// A use whose slot is taken evicts the one there (which is kept), so every use is either
// cancelled with its reverse or kept: nothing is lost. The slot is a hash of the undirected
// edge (key >> 1), which a use and its reverse share.
constexpr unsigned kCancelBits = 12;
constexpr std::uint64_t kNoKey = 0;  // no key is 0: that would be the self-loop 0 -> 0

std::size_t chunk_count(const ShadowVolumeChain& chain) { return (face_count(chain) + kChunkFaces - 1) / kChunkFaces; }

struct ChunkKeys {
  std::vector<std::uint64_t> keys;  // the uses left, in no particular order
  bool out_of_range = false;        // some face holds an id >= the chain's ids
};

ChunkKeys chunk_keys(const ShadowVolumeChain& chain, std::size_t first, std::size_t last, std::uint64_t ids) {
  ChunkKeys out;
  std::array<std::uint64_t, std::size_t{1} << kCancelBits> pending{};
  const auto keep = [&](std::uint64_t key) { out.keys.push_back(key); };
  for_each_directed_edge(chain, first, last, [&](std::uint32_t a, std::uint32_t b) {
    if (std::max(a, b) >= ids) {
      out.out_of_range = true;
      return;
    }
    if (a == b) return;
    const std::uint64_t key = edge_key(a, b);
    std::uint64_t& slot = pending[((key >> 1) * 0x9e3779b97f4a7c15u) >> (64 - kCancelBits)];
    if (slot == (key ^ 1u)) {
      slot = kNoKey;  // the reverse use: the pair cancels
      return;
    }
    if (slot != kNoKey) keep(slot);
    slot = key;
  });
  for (const std::uint64_t key : pending)
    if (key != kNoKey) keep(key);
  return out;
}

struct BlockLayout {
  std::size_t blocks = 0;
  std::vector<std::size_t> start;   // offsets of the blocks in the key array, size blocks + 1
  std::vector<std::size_t> cursor;  // cursor[c * blocks + b]: where chunk c writes its first key of block b
};

BlockLayout block_layout(const std::vector<ChunkKeys>& chunks, std::uint64_t ids) {
  BlockLayout layout;
  layout.blocks = static_cast<std::size_t>((ids >> kBlockBits) + 1);
  layout.cursor.assign(chunks.size() * layout.blocks, 0);
  tbb::parallel_for(std::size_t{0}, chunks.size(), [&](std::size_t c) {
    std::size_t* count = layout.cursor.data() + c * layout.blocks;
    for (const std::uint64_t key : chunks[c].keys) ++count[block_of(key)];
  });
  layout.start.assign(layout.blocks + 1, 0);
  std::size_t offset = 0;
  for (std::size_t b = 0; b < layout.blocks; ++b) {
    layout.start[b] = offset;
    for (std::size_t c = 0; c < chunks.size(); ++c) offset += std::exchange(layout.cursor[c * layout.blocks + b], offset);
  }
  layout.start[layout.blocks] = offset;
  return layout;
}

// Uninitialised, not zeroed: the scatter writes every entry.
HugePageBuffer<std::uint64_t> keys_by_block(const std::vector<ChunkKeys>& chunks, BlockLayout& layout) {
  HugePageBuffer<std::uint64_t> keys(layout.start.back());
  tbb::parallel_for(std::size_t{0}, chunks.size(), [&](std::size_t c) {
    std::size_t* cursor = layout.cursor.data() + c * layout.blocks;
    for (const std::uint64_t key : chunks[c].keys) keys[cursor[block_of(key)]++] = key;
  });
  return keys;
}

void sort_run(std::uint64_t* first, std::uint64_t* last) {
  constexpr std::ptrdiff_t kInsertionLimit = 32;
  if (last - first > kInsertionLimit) {
    std::sort(first, last);
    return;
  }
  // From `first`, not `first + 1`: an empty run may be (nullptr, nullptr), where + 1 is
  // undefined behaviour (UBSan, tools/dev.sh sanitize); i = first moves nothing.
  for (std::uint64_t* i = first; i < last; ++i) {
    const std::uint64_t moving = *i;
    std::uint64_t* j = i;
    for (; j > first && moving < *(j - 1); --j) *j = *(j - 1);
    *j = moving;
  }
}

// A sorted run of keys with one lower id.
void report_run(const std::uint64_t* first, const std::uint64_t* last, std::vector<UnbalancedEdge>& unbalanced) {
  while (first < last) {
    const std::uint64_t edge = *first >> 1;
    std::int64_t excess = 0;
    for (; first < last && (*first >> 1) == edge; ++first) excess += (*first & 1u) ? -1 : 1;
    if (excess != 0)
      unbalanced.push_back(
          {static_cast<std::uint32_t>(edge >> 32), static_cast<std::uint32_t>(edge & 0xffffffffu), excess});
  }
}

// One block: counting sort by lower id into `scratch`, then each vertex's run.
void report_block(std::uint64_t* first, std::uint64_t* last, std::vector<std::uint64_t>& scratch,
                  std::vector<UnbalancedEdge>& unbalanced) {
  std::array<std::uint32_t, kBlockIds + 1> start{};
  for (const std::uint64_t* k = first; k < last; ++k) ++start[((*k >> 33) & (kBlockIds - 1)) + 1];
  for (std::size_t i = 1; i < start.size(); ++i) start[i] += start[i - 1];
  scratch.resize(static_cast<std::size_t>(last - first));
  std::array<std::uint32_t, kBlockIds + 1> cursor = start;
  for (const std::uint64_t* k = first; k < last; ++k) scratch[cursor[(*k >> 33) & (kBlockIds - 1)]++] = *k;
  for (std::size_t v = 0; v < kBlockIds; ++v) {
    std::uint64_t* const run_first = scratch.data() + start[v];
    std::uint64_t* const run_last = scratch.data() + start[v + 1];
    sort_run(run_first, run_last);
    report_run(run_first, run_last, unbalanced);
  }
}

}  // namespace

ClosureCertificate certify_closure(const ShadowVolumeChain& chain) {
  const std::uint64_t ids = id_count(chain);
  const std::size_t faces = face_count(chain);
  std::vector<ChunkKeys> chunks(chunk_count(chain));
  tbb::parallel_for(std::size_t{0}, chunks.size(), [&](std::size_t c) {
    chunks[c] = chunk_keys(chain, c * kChunkFaces, std::min(faces, (c + 1) * kChunkFaces), ids);
  });
  // The first bad id in face order, as a sequential pass meets it.
  for (std::size_t c = 0; c < chunks.size(); ++c)
    if (chunks[c].out_of_range)
      for_each_directed_edge(chain, c * kChunkFaces, std::min(faces, (c + 1) * kChunkFaces),
                             [&](std::uint32_t a, std::uint32_t b) {
                               if (std::max(a, b) >= ids) throw_out_of_range(std::max(a, b), ids);
                             });
  BlockLayout layout = block_layout(chunks, ids);
  HugePageBuffer<std::uint64_t> keys = keys_by_block(chunks, layout);
  chunks = {};  // their memory back before the sort
  std::vector<std::vector<UnbalancedEdge>> by_block(layout.blocks);
  tbb::enumerable_thread_specific<std::vector<std::uint64_t>> scratch;
  tbb::parallel_for(std::size_t{0}, layout.blocks, [&](std::size_t b) {
    report_block(keys.data() + layout.start[b], keys.data() + layout.start[b + 1], scratch.local(), by_block[b]);
  });
  ClosureCertificate certificate;
  for (const std::vector<UnbalancedEdge>& block : by_block)
    certificate.unbalanced.insert(certificate.unbalanced.end(), block.begin(), block.end());
  certificate.closed = certificate.unbalanced.empty();
  return certificate;
}

}  // namespace shadowcert
