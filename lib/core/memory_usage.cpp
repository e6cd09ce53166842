#include "core/memory_usage.hpp"

#include <sys/resource.h>
#include <unistd.h>

#include <cmath>
#include <fstream>
#include <sstream>

#include "core/errors.hpp"

namespace corofem {

long peak_rss_kb() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return usage.ru_maxrss;  // kB on Linux
}

long current_rss_kb() {
  std::ifstream statm("/proc/self/statm");
  long pages = 0, resident = 0;
  if (!(statm >> pages >> resident)) return 0;
  return resident * (sysconf(_SC_PAGESIZE) / 1024);
}

double physical_memory_bytes() {
  const long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGESIZE);
  return pages > 0 && page > 0 ? static_cast<double>(pages) * page : 0.0;
}

void require_memory_for_tets(double tets, const std::string& what) {
  const double need = tets * kBytesPerTet, have = physical_memory_bytes();
  if (have <= 0 || need <= have) return;
  std::ostringstream message;
  message.precision(3);
  message << what << " would give about " << tets << " tets, which need about " << need / 1e9
          << " GB (" << kBytesPerTet / 1e3 << " kB per tet); this machine has " << have / 1e9
          << " GB";
  throw InputError(message.str());
}

}  // namespace corofem
