#pragma once
// Large arrays filled once by the exact pipeline (the weld's records, the edge table, the
// chain, the closure's keys) are asked to be backed by transparent huge pages. Linux grants
// them only on request in its default "madvise" mode, and the request must come before the
// first touch: on the 2-core virtual machine we measure on, a first touch of a 4 KiB page
// costs about 8 us (its page fault traps to the hypervisor), so the 150 MB of fresh buffers of
// the 1M-triangle pipeline spent over half its time in page faults, 163k of them
// (docs/certificates.md, "Measured figures"). One fault per 2 MiB page instead removes nearly
// all of that. Only speed changes: the memory holds the same bytes either way, and where the
// kernel refuses (no THP, another OS) nothing happens.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <memory>
#include <new>
#include <type_traits>
#include <utility>
#include <vector>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace shadowcert {

// A huge page covers only 2 MiB-aligned ranges inside the array, so a vector (whose storage
// malloc places anywhere) of less than 2 MiB gains nothing, and one of more keeps 4 KiB pages at
// its two ends; HugePageBuffer below, aligned, has none.
inline constexpr std::size_t kHugePageBytes = std::size_t{2} << 20;
inline constexpr std::size_t kHugePageAdviceMinBytes = kHugePageBytes;
// Below this an array is left to fault on first touch: a few dozen faults cost less than the
// call. Above it, storage no huge page fits in is faulted in by one populate call (issue 24's
// 1M pipeline: the weld's 2 MB canonical_id alone took 489 faults, 5.4 ms, on first touch).
inline constexpr std::size_t kPopulateMinBytes = std::size_t{64} << 10;

// Asks for huge pages over the 2 MiB-aligned part of [data, data + bytes), and faults in the
// 4 KiB pages at its two ends (which no huge page can cover) in one call each, or the whole
// range when no huge page fits in it: the kernel then walks them in a loop, at about 40% of the
// cost of trapping once per page on first touch (measured: 64 MiB in 92-111 ms populated
// against 241-254 ms touched; 3.8 ms as huge pages). For storage about to be written in full.
// Advice only: a refusal (an older kernel, no THP) is ignored, as the memory works the same
// without it.
inline void advise_huge_pages(const void* data, std::size_t bytes) {
#if defined(__linux__) && defined(MADV_HUGEPAGE)
  if (data == nullptr || bytes < kPopulateMinBytes) return;
  constexpr std::uintptr_t kHuge = kHugePageBytes, kPage = 4096;
  const auto begin = reinterpret_cast<std::uintptr_t>(data);
  const std::uintptr_t end = begin + bytes;
  const std::uintptr_t head = begin & ~(kPage - 1);               // the page holding `data`
  const std::uintptr_t tail_end = (end + kPage - 1) & ~(kPage - 1);  // past the page of the last byte
  const std::uintptr_t first = (begin + kHuge - 1) & ~(kHuge - 1);
  const std::uintptr_t last = end & ~(kHuge - 1);
  [[maybe_unused]] const auto populate = [](std::uintptr_t from, std::uintptr_t to) {
#if defined(MADV_POPULATE_WRITE)
    if (to > from) (void)madvise(reinterpret_cast<void*>(from), to - from, MADV_POPULATE_WRITE);
#endif
  };
  if (last <= first) {
    populate(head, tail_end);
    return;
  }
  (void)madvise(reinterpret_cast<void*>(first), last - first, MADV_HUGEPAGE);
  populate(head, first);
  populate(last, tail_end);
#else
  (void)data;
  (void)bytes;
#endif
}

// v.reserve(n), with the new storage advised before anything touches it. Call it on a vector
// about to be filled: a vector that already holds its capacity keeps its (touched) storage.
template <typename T>
void reserve_huge(std::vector<T>& v, std::size_t n) {
  if (n <= v.capacity()) return;
  v.reserve(n);
  advise_huge_pages(v.data(), v.capacity() * sizeof(T));
}

// v.resize(n) of an empty vector through reserve_huge: the zero fill is the first touch.
template <typename T>
void resize_huge(std::vector<T>& v, std::size_t n) {
  reserve_huge(v, n);
  v.resize(n);
}

// A fixed-size scratch array of trivial T, left uninitialised (every user writes each entry
// before reading it), 2 MiB-aligned and advised when large, so every page of it is huge.
template <typename T>
class HugePageBuffer {
  static_assert(std::is_trivially_copyable_v<T> && std::is_trivially_destructible_v<T>);

 public:
  HugePageBuffer() = default;
  explicit HugePageBuffer(std::size_t size) : size_(size) {
    const std::size_t bytes = size * sizeof(T);
    if (bytes >= kHugePageBytes) {
      const std::size_t rounded = (bytes + kHugePageBytes - 1) / kHugePageBytes * kHugePageBytes;
      data_.reset(static_cast<T*>(std::aligned_alloc(kHugePageBytes, rounded)));
      advise_huge_pages(data_.get(), rounded);
    } else if (bytes > 0) {
      data_.reset(static_cast<T*>(std::malloc(bytes)));
    }
    if (bytes > 0 && data_ == nullptr) throw std::bad_alloc();
  }

  [[nodiscard]] T* data() { return data_.get(); }
  [[nodiscard]] const T* data() const { return data_.get(); }
  [[nodiscard]] std::size_t size() const { return size_; }
  T& operator[](std::size_t i) { return data_.get()[i]; }
  const T& operator[](std::size_t i) const { return data_.get()[i]; }
  void swap(HugePageBuffer& other) noexcept {
    data_.swap(other.data_);
    std::swap(size_, other.size_);
  }

 private:
  struct Free {
    void operator()(T* p) const { std::free(p); }
  };
  std::unique_ptr<T, Free> data_;
  std::size_t size_ = 0;
};

}  // namespace shadowcert
