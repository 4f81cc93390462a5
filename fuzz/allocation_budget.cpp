#include "fuzz/allocation_budget.h"

#include <cstdlib>
#include <new>

namespace shadowcert::fuzz {
namespace {

// Per thread: libFuzzer's own threads (its RSS watcher) never see the budget.
thread_local bool armed = false;
thread_local std::size_t left = 0;

void* allocate(std::size_t size) {
  if (armed) {
    if (size > left) throw std::bad_alloc();
    left -= size;
  }
  // malloc, so that AddressSanitizer still tracks every block (and pairs it with free).
  if (void* block = std::malloc(size == 0 ? 1 : size)) return block;
  throw std::bad_alloc();
}

}  // namespace

AllocationBudget::AllocationBudget(std::size_t bytes) {
  armed = true;
  left = bytes;
}

AllocationBudget::~AllocationBudget() { armed = false; }

}  // namespace shadowcert::fuzz

// Every replaceable form that the plain and array forms reach; the aligned forms keep the
// runtime's own (nothing in scene/ over-aligns), and they pair with its own deletes.
void* operator new(std::size_t size) { return shadowcert::fuzz::allocate(size); }
void* operator new[](std::size_t size) { return shadowcert::fuzz::allocate(size); }
void* operator new(std::size_t size, const std::nothrow_t&) noexcept {
  try {
    return shadowcert::fuzz::allocate(size);
  } catch (const std::bad_alloc&) {
    return nullptr;
  }
}
void* operator new[](std::size_t size, const std::nothrow_t&) noexcept {
  try {
    return shadowcert::fuzz::allocate(size);
  } catch (const std::bad_alloc&) {
    return nullptr;
  }
}
void operator delete(void* block) noexcept { std::free(block); }
void operator delete[](void* block) noexcept { std::free(block); }
void operator delete(void* block, std::size_t) noexcept { std::free(block); }
void operator delete[](void* block, std::size_t) noexcept { std::free(block); }
void operator delete(void* block, const std::nothrow_t&) noexcept { std::free(block); }
void operator delete[](void* block, const std::nothrow_t&) noexcept { std::free(block); }
