// corofem_bench: Google Benchmark driver. Adds the build's provenance to the JSON context so
// every record says what produced it; `--models DIR` names the bunny/horse/dragon folder.
#include <benchmark/benchmark.h>

#include <cstring>
#include <iostream>
#include <string>
#include <vector>

#include "bench_support.hpp"
#include "core/build_info.hpp"
#include "core/threads.hpp"
#include "io/run_context.hpp"

int main(int argc, char** argv) {
  std::vector<char*> args;
  std::string threads;  // --threads N: the kernels' thread count (default: all cores)
  for (int i = 0; i < argc; ++i) {
    if (std::strcmp(argv[i], "--models") == 0 && i + 1 < argc) {
      corofem::bench::set_models_dir(argv[++i]);
    } else if (std::strncmp(argv[i], "--models=", 9) == 0) {
      corofem::bench::set_models_dir(argv[i] + 9);
    } else if (std::strcmp(argv[i], "--threads") == 0 && i + 1 < argc) {
      threads = argv[++i];
    } else {
      args.push_back(argv[i]);
    }
  }
  try {
    if (!threads.empty()) corofem::set_thread_count(corofem::parse_thread_count(threads));
  } catch (const std::exception& e) {
    std::cerr << "corofem_bench: " << e.what() << "\n";
    return 2;
  }
  int count = static_cast<int>(args.size());
  benchmark::Initialize(&count, args.data());
  if (benchmark::ReportUnrecognizedArguments(count, args.data())) return 2;
  const auto context = corofem::run_context();
  for (const char* key : {"commit", "compiler", "flags", "build_type", "cpu"})
    benchmark::AddCustomContext(std::string("corofem_") + key, context[key].get<std::string>());
  benchmark::AddCustomContext("corofem_threads", std::to_string(corofem::thread_count()));
  benchmark::AddCustomContext("corofem_models", corofem::bench::models_dir().empty()
                                                    ? "procedural"
                                                    : corofem::bench::models_dir().string());
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
