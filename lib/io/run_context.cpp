#include "io/run_context.hpp"

#include <unistd.h>

#include <chrono>
#include <ctime>
#include <fstream>
#include <string>
#include <thread>

#include "core/build_info.hpp"
#include "core/core_latency.hpp"
#include "core/huge_pages.hpp"
#include "core/threads.hpp"
#include "sparse/block_kernels.hpp"

namespace corofem {
namespace {

std::string cpu_model() {
  std::ifstream in("/proc/cpuinfo");
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind("model name", 0) == 0) {
      auto colon = line.find(':');
      if (colon != std::string::npos) return line.substr(colon + 2);
    }
  }
  return "unknown";
}

nlohmann::json cache_sizes() {
  nlohmann::json caches = nlohmann::json::object();
  const struct {
    int name;
    const char* key;
  } levels[] = {{_SC_LEVEL1_DCACHE_SIZE, "l1d_bytes"},
                {_SC_LEVEL2_CACHE_SIZE, "l2_bytes"},
                {_SC_LEVEL3_CACHE_SIZE, "l3_bytes"}};
  for (const auto& level : levels) {
    long bytes = sysconf(level.name);
    if (bytes > 0) caches[level.key] = bytes;
  }
  return caches;
}

std::string utc_now() {
  std::time_t now = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
  char buffer[32];
  std::strftime(buffer, sizeof buffer, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&now));
  return buffer;
}

}  // namespace

nlohmann::json run_context() {
  char host[256] = {0};
  gethostname(host, sizeof host - 1);
  // Where the host put the two cores of a two-thread run (core/core_latency.hpp): null at one.
  const double core_to_core_ns = thread_count() > 1 ? measure_core_to_core_ns() : 0;
  return {{"commit", build_commit()},
          {"version", build_version()},
          {"compiler", build_compiler()},
          {"flags", build_flags()},
          {"build_type", build_type()},
          {"cpu", cpu_model()},
          {"caches", cache_sizes()},
          {"hardware_threads", std::thread::hardware_concurrency()},
          {"threads_used", thread_count()},
          {"items_per_thread",
           {{"entries", items_per_thread(LoopItems::Entries)},
            {"blocks", items_per_thread(LoopItems::Blocks)}}},
          {"openmp", have_openmp()},
          {"block_kernels", block_kernels_name()},
          {"huge_pages", huge_pages_setting()},
          {"core_to_core_ns",
           core_to_core_ns > 0 ? nlohmann::json(core_to_core_ns) : nlohmann::json(nullptr)},
          {"host", host},
          {"date", utc_now()}};
}

}  // namespace corofem
