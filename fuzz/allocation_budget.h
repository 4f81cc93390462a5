#pragma once
// A cap on what one fuzz input may allocate (scene_file_fuzzer only).
//
// A scene of 60 bytes may rightly ask for 100 million generated triangles
// (docs/scene-format.md: sphere_grid, random_soup, uv_sphere...), which is not a parser bug
// but would make each such input take seconds and gigabytes. Within a budget scope, this
// executable's replaced global operator new counts the bytes the current thread allocates
// and throws std::bad_alloc past the budget: generators reserve before they compute, so an
// oversized request fails at once, and the unwinding that follows is itself under test
// (LeakSanitizer reports what a throw would leak).
#include <cstddef>

namespace shadowcert::fuzz {

class AllocationBudget {
 public:
  // Arms the budget for the calling thread; only one scope at a time.
  explicit AllocationBudget(std::size_t bytes);
  ~AllocationBudget();
  AllocationBudget(const AllocationBudget&) = delete;
  AllocationBudget& operator=(const AllocationBudget&) = delete;
};

}  // namespace shadowcert::fuzz
