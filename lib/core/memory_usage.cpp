#include "core/memory_usage.hpp"

#include <sys/resource.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
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

int ranks_on_this_machine() {
  for (const char* name : {"OMPI_COMM_WORLD_LOCAL_SIZE", "MPI_LOCALNRANKS"})
    if (const char* value = std::getenv(name)) {
      const int ranks = std::atoi(value);
      if (ranks > 0) return ranks;
    }
  return 1;
}

void require_memory(double tets, double bytes, const std::string& what, const std::string& basis) {
  const int ranks = ranks_on_this_machine();
  const double need = bytes * ranks, have = physical_memory_bytes();
  if (have <= 0 || need <= have) return;
  std::ostringstream message;
  message.precision(3);
  message << what << " would give about " << tets << " tets, which need about " << need / 1e9
          << " GB (" << basis;
  if (ranks > 1) message << "; x " << ranks << " ranks on this machine";
  message << "); this machine has " << have / 1e9 << " GB";
  throw InputError(message.str());
}

}  // namespace corofem
