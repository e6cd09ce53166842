#pragma once
// Large allocations on transparent huge pages (see huge_pages.cpp).
#include <string>

namespace corofem {

/// Whether allocations of 2 MB or more ask for 2 MB pages, and the kernel's THP mode, for the
/// records: "on (THP: madvise)", "off (COROFEM_HUGE_PAGES=0)", "off (sanitizer build)".
std::string huge_pages_setting();

}  // namespace corofem
