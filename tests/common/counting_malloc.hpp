#pragma once
// Counts heap allocations: the executable that includes this header (in ONE
// of its translation units) interposes glibc's malloc family, which
// operator new and Eigen's aligned_malloc call too, with counting wrappers
// around __libc_malloc & co. Not for a sanitizer build: AddressSanitizer
// owns malloc (a target that includes this is built without sanitizers,
// or includes it only under !CNCLAB_COUNTING_MALLOC_UNAVAILABLE below).
#include <atomic>
#include <cstddef>

#if defined(__SANITIZE_ADDRESS__)
#define CNCLAB_COUNTING_MALLOC_UNAVAILABLE 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define CNCLAB_COUNTING_MALLOC_UNAVAILABLE 1
#endif
#endif

#ifndef CNCLAB_COUNTING_MALLOC_UNAVAILABLE
extern "C" {
void* __libc_malloc(std::size_t);
void* __libc_calloc(std::size_t, std::size_t);
void* __libc_realloc(void*, std::size_t);
void* __libc_memalign(std::size_t, std::size_t);
void __libc_free(void*);
}

namespace cnclab::testing {
inline std::atomic<long> g_heap_allocations{0};  // instrumentation only
}  // namespace cnclab::testing

extern "C" {
void* malloc(std::size_t size) {
  cnclab::testing::g_heap_allocations.fetch_add(1, std::memory_order_relaxed);
  return __libc_malloc(size);
}
void* calloc(std::size_t count, std::size_t size) {
  cnclab::testing::g_heap_allocations.fetch_add(1, std::memory_order_relaxed);
  return __libc_calloc(count, size);
}
void* realloc(void* p, std::size_t size) {
  cnclab::testing::g_heap_allocations.fetch_add(1, std::memory_order_relaxed);
  return __libc_realloc(p, size);
}
void* memalign(std::size_t alignment, std::size_t size) {
  cnclab::testing::g_heap_allocations.fetch_add(1, std::memory_order_relaxed);
  return __libc_memalign(alignment, size);
}
void* aligned_alloc(std::size_t alignment, std::size_t size) {
  cnclab::testing::g_heap_allocations.fetch_add(1, std::memory_order_relaxed);
  return __libc_memalign(alignment, size);
}
int posix_memalign(void** out, std::size_t alignment, std::size_t size) {
  cnclab::testing::g_heap_allocations.fetch_add(1, std::memory_order_relaxed);
  *out = __libc_memalign(alignment, size);
  return *out == nullptr ? 12 /* ENOMEM */ : 0;
}
void free(void* p) {
  __libc_free(p);
}
}
#endif

namespace cnclab::testing {
// Heap allocations so far; -1 where they cannot be counted (a sanitizer).
inline long heap_allocations() {
#ifdef CNCLAB_COUNTING_MALLOC_UNAVAILABLE
  return -1;
#else
  return g_heap_allocations.load(std::memory_order_relaxed);
#endif
}
}  // namespace cnclab::testing
