// Counts every heap allocation of the test program: malloc, calloc, realloc and the aligned
// allocators are interposed (Eigen and C code allocate through them, not through operator
// new), and operator new/delete go through malloc/free. The interposers forward to glibc's
// __libc_* entry points, which never call back into them.
//
// Under AddressSanitizer (CONTACTLAB_SANITIZE, CONTACTLAB_FUZZ) ASan owns malloc and free:
// memory from __libc_malloc handed to ASan's free would be reported as a bad free. There the
// count comes from ASan's own allocation hook instead, which sees the same calls (malloc,
// calloc, realloc, the aligned allocators and operator new all go through its allocator).
#include "allocation_counter.h"

#if defined(__SANITIZE_ADDRESS__)
#define CONTACTLAB_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define CONTACTLAB_ASAN 1
#endif
#endif

#if defined(CONTACTLAB_ASAN)

#include <atomic>
#include <cstddef>

// From <sanitizer/allocator_interface.h> (not shipped with every compiler's runtime).
extern "C" int __sanitizer_install_malloc_and_free_hooks(
    void (*malloc_hook)(const volatile void*, std::size_t), void (*free_hook)(const volatile void*));

namespace {
std::atomic<long> g_allocations{0};
void OnMalloc(const volatile void*, std::size_t) { g_allocations.fetch_add(1, std::memory_order_relaxed); }
void OnFree(const volatile void*) {}
// Installed before main(), so every allocation of the tests is seen.
const int g_hooks_installed = __sanitizer_install_malloc_and_free_hooks(OnMalloc, OnFree);
}  // namespace

namespace contactlab::testing {
long AllocationCount() {
  if (g_hooks_installed == 0) __builtin_trap();  // ASan refused the hook: the count would be 0
  return g_allocations.load(std::memory_order_relaxed);
}
}  // namespace contactlab::testing

#else  // the interposers

#include <atomic>
#include <cerrno>
#include <cstddef>
#include <cstdlib>
#include <new>

extern "C" void* __libc_malloc(std::size_t);
extern "C" void* __libc_calloc(std::size_t, std::size_t);
extern "C" void* __libc_realloc(void*, std::size_t);
extern "C" void* __libc_memalign(std::size_t, std::size_t);

namespace {
std::atomic<long> g_allocations{0};
void Count() { g_allocations.fetch_add(1, std::memory_order_relaxed); }
}  // namespace

extern "C" void* malloc(std::size_t n) {
  Count();
  return __libc_malloc(n);
}
extern "C" void* calloc(std::size_t count, std::size_t n) {
  Count();
  return __libc_calloc(count, n);
}
extern "C" void* realloc(void* p, std::size_t n) {
  Count();
  return __libc_realloc(p, n);
}
extern "C" void* memalign(std::size_t alignment, std::size_t n) {
  Count();
  return __libc_memalign(alignment, n);
}
extern "C" void* aligned_alloc(std::size_t alignment, std::size_t n) {
  Count();
  return __libc_memalign(alignment, n);
}
extern "C" int posix_memalign(void** out, std::size_t alignment, std::size_t n) {
  Count();
  if (alignment < sizeof(void*) || (alignment & (alignment - 1)) != 0) return EINVAL;
  void* p = __libc_memalign(alignment, n);
  if (p == nullptr && n != 0) return ENOMEM;
  *out = p;
  return 0;
}

void* operator new(std::size_t n) {
  if (void* p = std::malloc(n == 0 ? 1 : n)) return p;
  throw std::bad_alloc();
}
void* operator new[](std::size_t n) { return ::operator new(n); }
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }

namespace contactlab::testing {
long AllocationCount() { return g_allocations.load(std::memory_order_relaxed); }
}  // namespace contactlab::testing

#endif  // CONTACTLAB_ASAN
