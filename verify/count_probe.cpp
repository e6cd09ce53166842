// A program whose sections do known work, for the counted gate's oracle test
// (core_section_counter_test.cpp): run under callgrind (or where perf has counters), each
// section's counts must be the work the code below does, known in closed form.
//   spin:          2 n + 1 instructions (the loop's decrement and branch, and its setup), n = 1e6
//   outer:         a spin of 1e5 of its own and the section inner, a spin of 3e5
//   stream:        reads one double per 64-byte line of a 64 MiB array that no cache holds:
//                  one D1 and one LL miss per line, 1,048,576 of each
//   allocate:      a spin of 1e6 and 1,000 malloc and free pairs of 16 B-64 KiB; under callgrind
//                  the allocator's calls are left out of the section and counted apart
//                  ("allocator_left_out")
// Usage: corofem_count_probe perf|callgrind[:FILE]   (prints the exclusive counts as JSON)
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "core/section_counter.hpp"

namespace {

/// Exactly 2 n + 1 instructions.
void spin(std::uint64_t n) {
  asm volatile(
      "mov %0, %%rcx\n"
      "1: dec %%rcx\n"
      "jnz 1b\n"
      :
      : "r"(n)
      : "rcx", "cc");
}

/// 1,000 malloc and free pairs, through a pointer the compiler cannot see through (it may remove
/// a pair it sees), of sizes 16 B to 64 KiB.
void allocate() {
  static void* (*volatile allocate_bytes)(std::size_t) = std::malloc;
  static void (*volatile release)(void*) = std::free;
  std::vector<void*> held(1000);
  for (std::size_t i = 0; i < held.size(); ++i) held[i] = allocate_bytes(16u << (i % 13));
  for (void* p : held) release(p);
}

/// One read per 64-byte line of `data`.
double stream(const std::vector<double>& data) {
  double sum = 0;
  for (std::size_t i = 0; i < data.size(); i += 8) sum += data[i];
  return sum;
}

}  // namespace

int main(int argc, char** argv) {
  using namespace corofem;
  if (argc != 2) {
    std::cerr << "usage: corofem_count_probe perf|callgrind[:FILE]\n";
    return 2;
  }
  const std::string arg = argv[1];
  const std::size_t colon = arg.find(':');
  const CountSource source = kCountSources.at(arg.substr(0, colon));
  // 64 MiB, written before counting starts: 16x the simulated LL, so none of it stays cached.
  std::vector<double> data(std::size_t{1} << 23, 1.0);
  std::string why_not;
  auto counter = SectionCounter::start(
      source, why_not, colon == std::string::npos ? std::string() : arg.substr(colon + 1));
  if (!counter) {
    std::cerr << "corofem_count_probe: " << why_not << "\n";
    return 3;
  }
  in_section(counter.get(), "spin", [] { spin(1000000); });
  in_section(counter.get(), "outer", [&] {
    spin(100000);
    in_section(counter.get(), "inner", [] { spin(300000); });
  });
  double sum = 0;
  in_section(counter.get(), "stream", [&] { sum = stream(data); });
  in_section(counter.get(), "allocate", [] {
    spin(1000000);
    allocate();
  });
  counter->finish();
  nlohmann::json out = nlohmann::json::object();
  for (const auto& [path, c] : counter->exclusive())
    out[path.empty() ? "-" : path] = {
        {"instructions", c.instructions}, {"d1_misses", c.d1_misses}, {"ll_misses", c.ll_misses}};
  const WorkCounts& a = counter->allocator_left_out();
  out["allocator_left_out"] = {{"instructions", a.instructions}};
  out["events"] = counter->event_definitions()["instructions"];
  std::cout << out.dump() << "\n" << (sum > 0 ? "" : "empty\n");
  return 0;
}
