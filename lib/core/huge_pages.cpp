#include "core/huge_pages.hpp"

// Every operator new of 2 MB or more (std::vector's storage: the BRC matrices' values and
// columns, the Galerkin streams, the element arrays) is 2 MB-aligned and advised for transparent
// huge pages (MADV_HUGEPAGE) before anything touches it.
// Why: a step's working set (the dragon's, 62 MB) is read with scattered accesses (the K blocks
// an element adds into, the A blocks a Galerkin pair reads, a row's x_j). Over 4 KB pages that is
// some 15000 pages, more than the second-level TLB maps, so such accesses walk the page tables.
// Debian's default THP mode, "madvise", gives 2 MB pages only where asked. Measured effect: see
// README ("Huge pages"). COROFEM_HUGE_PAGES=0 turns it off (for comparisons); sanitizer builds
// keep their own allocator.
#include <sys/mman.h>

#include <cstdint>
#include <cstdlib>
#include <fstream>
#include <new>

#if defined(__SANITIZE_ADDRESS__)
#define COROFEM_OWN_ALLOCATOR 0
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define COROFEM_OWN_ALLOCATOR 0
#endif
#endif
#ifndef COROFEM_OWN_ALLOCATOR
#define COROFEM_OWN_ALLOCATOR 1
#endif

namespace {

constexpr std::size_t kHugePage = std::size_t{2} << 20;

bool huge_pages_wanted() {
  static const bool wanted = [] {
    const char* value = std::getenv("COROFEM_HUGE_PAGES");
    return !(value && value[0] == '0');
  }();
  return wanted;
}

#if COROFEM_OWN_ALLOCATOR
void* try_allocate(std::size_t bytes) {
  if (bytes >= kHugePage && huge_pages_wanted()) {
    if (bytes > SIZE_MAX - kHugePage) return nullptr;
    const std::size_t rounded = (bytes + kHugePage - 1) & ~(kHugePage - 1);
    void* p = nullptr;
    if (posix_memalign(&p, kHugePage, rounded) != 0) return nullptr;
    madvise(p, rounded, MADV_HUGEPAGE);  // advice: where the kernel cannot, 4 KB pages remain
    return p;
  }
  return std::malloc(bytes ? bytes : 1);
}

/// The standard's operator new: the new-handler, if any, gets to free memory before each retry.
void* allocate(std::size_t bytes) {
  for (;;) {
    if (void* p = try_allocate(bytes)) return p;
    const std::new_handler handler = std::get_new_handler();
    if (!handler) throw std::bad_alloc();
    handler();
  }
}
#endif

}  // namespace

#if COROFEM_OWN_ALLOCATOR
void* operator new(std::size_t bytes) {
  return allocate(bytes);
}
void* operator new[](std::size_t bytes) {
  return allocate(bytes);
}
void operator delete(void* p) noexcept {
  std::free(p);
}
void operator delete[](void* p) noexcept {
  std::free(p);
}
void operator delete(void* p, std::size_t) noexcept {
  std::free(p);
}
void operator delete[](void* p, std::size_t) noexcept {
  std::free(p);
}
#endif

namespace corofem {

std::string huge_pages_setting() {
  if (!COROFEM_OWN_ALLOCATOR) return "off (sanitizer build)";
  if (!huge_pages_wanted()) return "off (COROFEM_HUGE_PAGES=0)";
  std::ifstream in("/sys/kernel/mm/transparent_hugepage/enabled");
  std::string modes, mode = "unknown";
  std::getline(in, modes);
  const std::size_t open = modes.find('['), close = modes.find(']');
  if (open != std::string::npos && close != std::string::npos && close > open)
    mode = modes.substr(open + 1, close - open - 1);
  return (mode == "never" ? "off (THP: " : "on (THP: ") + mode + ")";
}

}  // namespace corofem
