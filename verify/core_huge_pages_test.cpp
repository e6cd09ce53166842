// Large allocations on transparent huge pages (lib/core/huge_pages.cpp).
#include <gtest/gtest.h>

#include <cstdint>
#include <fstream>
#include <new>
#include <sstream>
#include <string>
#include <vector>

#include "core/huge_pages.hpp"

namespace corofem {
namespace {

constexpr std::uintptr_t kHugePage = std::uintptr_t{2} << 20;

/// /proc/self/smaps' THPeligible for the mapping holding `address` (-1: not found or unreadable).
int thp_eligible(const void* address) {
  std::ifstream smaps("/proc/self/smaps");
  const auto at = reinterpret_cast<std::uintptr_t>(address);
  std::string line;
  bool inside = false;
  while (std::getline(smaps, line)) {
    std::uintptr_t lo = 0, hi = 0;
    char dash = 0;
    std::istringstream range(line);
    if (range >> std::hex >> lo >> dash >> hi && dash == '-') {  // a mapping's header line
      inside = lo <= at && at < hi;
      continue;
    }
    if (inside && line.rfind("THPeligible:", 0) == 0) return std::stoi(line.substr(12));
  }
  return -1;
}

TEST(HugePages, LargeVectorsAreAlignedAndAdvisedSmallOnesAreNot) {
  const std::string setting = huge_pages_setting();
  if (setting.rfind("on", 0) != 0) GTEST_SKIP() << "huge pages " << setting;
  std::vector<double> large(3 << 18, 1.0);  // 6 MB
  EXPECT_EQ(reinterpret_cast<std::uintptr_t>(large.data()) % kHugePage, 0u);
  // Every entry usable (the allocation rounds up, never down).
  for (std::size_t i = 0; i < large.size(); ++i) large[i] = static_cast<double>(i);
  EXPECT_EQ(large.back(), static_cast<double>(large.size() - 1));
  const int eligible = thp_eligible(large.data());
  if (eligible >= 0) {
    EXPECT_EQ(eligible, 1) << "the mapping was not advised for huge pages";
  }
  // Below 2 MB, the ordinary allocator: no 2 MB alignment asked for (one in 512 would have it by
  // chance, so two allocations that both have it would point at the rule being wrong).
  std::vector<double> small_a(1000), small_b(3000);
  EXPECT_FALSE(reinterpret_cast<std::uintptr_t>(small_a.data()) % kHugePage == 0 &&
               reinterpret_cast<std::uintptr_t>(small_b.data()) % kHugePage == 0);
}

TEST(HugePages, AnImpossibleSizeThrowsBadAlloc) {
  // Rounding up to 2 MB must not wrap around to a small block. (A sanitizer's allocator, which
  // replaces this one there, reports such a size as an error instead.)
  if (huge_pages_setting().find("sanitizer") != std::string::npos)
    GTEST_SKIP() << "sanitizer build";
  volatile std::size_t huge = SIZE_MAX - 100;
  EXPECT_THROW(::operator delete(::operator new(huge)), std::bad_alloc);
  volatile std::size_t half = SIZE_MAX / 2;
  EXPECT_THROW(::operator delete(::operator new(half)), std::bad_alloc);
}

}  // namespace
}  // namespace corofem
