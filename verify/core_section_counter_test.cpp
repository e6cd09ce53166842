// Work counted per section (core/section_counter.hpp): each stretch between two marks goes to
// the innermost open section; parents hold their parts; callgrind's counts of a program whose
// sections do known work are that work; where a source cannot count, it says why.
#include <gtest/gtest.h>

#include <cstdlib>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "core/section_counter.hpp"
#include "test_support.hpp"

namespace corofem {
namespace {

/// A reader whose counts the test advances by hand: instructions, D1 and LL misses.
struct HandCounts {
  WorkCounts now{};
  std::unique_ptr<SectionCounter> counter() {
    return SectionCounter::reading([this] { return now; }, "by hand");
  }
  void work(std::uint64_t instructions, std::uint64_t d1 = 0, std::uint64_t ll = 0) {
    now += WorkCounts{instructions, d1, ll};
  }
};

TEST(SectionCounter, EachStretchGoesToTheInnermostOpenSection) {
  HandCounts hand;
  auto counter = hand.counter();
  hand.work(7);  // before any section: outside
  in_section(counter.get(), "update", [&] {
    hand.work(100, 10, 1);
    in_section(counter.get(), "galerkin", [&] { hand.work(1000, 100, 10); });
    hand.work(20, 2);
    in_section(counter.get(), "smoothers", [&] { hand.work(300, 30, 3); });
  });
  in_section(counter.get(), "solve", [&] { hand.work(5000, 500, 50); });
  in_section(counter.get(), "update",
             [&] { in_section(counter.get(), "galerkin", [&] { hand.work(1000, 100, 10); }); });
  hand.work(3);
  counter->finish();
  const auto& own = counter->exclusive();
  EXPECT_EQ(own.at("").instructions, 10u);
  EXPECT_EQ(own.at("update").instructions, 120u);
  EXPECT_EQ(own.at("update").d1_misses, 12u);
  EXPECT_EQ(own.at("update/galerkin").instructions, 2000u);
  EXPECT_EQ(own.at("update/galerkin").ll_misses, 20u);
  EXPECT_EQ(own.at("update/smoothers").instructions, 300u);
  EXPECT_EQ(own.at("solve").d1_misses, 500u);
  const auto all = inclusive(own);
  EXPECT_EQ(all.at("update").instructions, 120u + 2000 + 300);
  EXPECT_EQ(all.at("update").d1_misses, 12u + 200 + 30);
  EXPECT_EQ(all.at("update/galerkin").instructions, 2000u);
  EXPECT_EQ(all.count(""), 0u);  // the stretches outside are no section
  // Every mark closed a stretch: 2 per section, 1 at finish.
  EXPECT_EQ(counter->marks(), 2 * 6 + 1);
}

TEST(SectionCounter, ASectionEndedOutOfOrderIsReportedAtFinish) {
  HandCounts hand;
  auto counter = hand.counter();
  counter->begin("update");
  counter->begin("galerkin");
  counter->end("update");  // a caller's bug: galerkin is still open
  try {
    counter->finish();
    FAIL() << "finish accepted sections ended out of order";
  } catch (const std::logic_error& e) {
    EXPECT_NE(std::string(e.what()).find("'update' ended while 'update/galerkin'"),
              std::string::npos)
        << e.what();
  }
}

TEST(SectionCounter, PerfWithoutCountersSaysWhyAndCountsNothing) {
  // An event no PMU has (an unknown type) cannot open anywhere: the path every VM without a
  // virtual PMU takes, checked on every machine.
  std::string why;
  const PerfCounters::Event impossible[3] = {{0xffff, 0}, {0xffff, 0}, {0xffff, 0}};
  EXPECT_FALSE(PerfCounters::open(impossible, why).has_value());
  EXPECT_NE(why.find("perf_event_open(instructions)"), std::string::npos) << why;
  // The real events: counted where the machine has counters, else refused with a reason.
  why.clear();
  auto counter = SectionCounter::start(CountSource::Perf, why);
  if (counter) {
    in_section(counter.get(), "a", [] {});
    counter->finish();
    EXPECT_GT(counter->exclusive().at("a").instructions, 0u);
  } else {
    EXPECT_NE(why.find("perf_event_open"), std::string::npos) << why;
  }
}

TEST(SectionCounter, CallgrindOutsideValgrindSaysHowToRunIt) {
  std::string why;
  EXPECT_EQ(SectionCounter::start(CountSource::Callgrind, why), nullptr);
  EXPECT_NE(why.find("valgrind --tool=callgrind"), std::string::npos) << why;
}

/// The probe's exclusive counts, counted by `source` ("perf", or callgrind's command line).
nlohmann::json probe_counts(const std::string& command) {
  const test::CliResult r = test::run_command(command);
  if (r.exit_code != 0)
    throw std::runtime_error("exit " + std::to_string(r.exit_code) + ": " + r.err);
  return nlohmann::json::parse(r.out.substr(0, r.out.find('\n')));
}

TEST(SectionCounter, CallgrindCountsTheKnownWorkOfEachSection) {
#ifdef COROFEM_ASAN_BUILD
  GTEST_SKIP() << "valgrind cannot run a sanitized binary (ci/test runs this gate)";
#endif
  if (std::system("valgrind --version > /dev/null 2>&1") != 0)
    GTEST_SKIP() << "valgrind is not installed (ci/setup installs it)";
  test::TempDir dir;
  const std::string out = (dir / "callgrind.out").string();
  const nlohmann::json c = probe_counts(
      "valgrind --tool=callgrind --instr-atstart=no --combine-dumps=yes --cache-sim=yes "
      "--I1=32768,8,64 --D1=32768,8,64 --LL=4194304,16,64 --callgrind-out-file='" +
      out + "' '" + COROFEM_COUNT_PROBE + "' callgrind:'" + out + "'");
  // Instructions: the spins' 2 n + 1, plus the share of the marks' own work that falls in each
  // section (a map look-up and a vector's append around callgrind's request: measured 1,000-2,500
  // instructions a section here, where each path is new; 3,000 bounds it).
  const auto holds = [](const nlohmann::json& counted, double known) {
    return counted.get<double>() >= known && counted.get<double>() <= known + 3000;
  };
  EXPECT_TRUE(holds(c["spin"]["instructions"], 2e6 + 1)) << c.dump();
  EXPECT_TRUE(holds(c["outer"]["instructions"], 2e5 + 1)) << c.dump();
  EXPECT_TRUE(holds(c["outer/inner"]["instructions"], 6e5 + 1)) << c.dump();
  const auto near = [](double counted, double known, double slack) {
    return std::abs(counted - known) <= slack * known;
  };
  // Misses: one per 64-byte line of 64 MiB that the simulated caches (32 KiB, 4 MiB) cannot hold;
  // no prefetcher is simulated. 0.2%: the loop's stack and the marks touch a few more lines.
  EXPECT_TRUE(near(c["stream"]["d1_misses"], 1 << 20, 2e-3)) << c.dump();
  EXPECT_TRUE(near(c["stream"]["ll_misses"], 1 << 20, 2e-3)) << c.dump();
  // The spins touch no data: their misses are the marks' alone.
  EXPECT_LT(c["spin"]["d1_misses"].get<double>(), 100) << c.dump();
  // The allocator's calls are left out of their section: what stays is the spin and the loops
  // around the calls (about 20 instructions a call, 2,000 calls: 40,000 bounds them). The 2,000
  // calls themselves cost at least the fast path's 25 instructions each. Leaving them out needs
  // the C library's debug information for its file names (ci/setup installs libc6-dbg).
  ASSERT_NE(c["events"].get<std::string>().find("outside the C library's allocator"),
            std::string::npos)
      << "the allocator was not found by name: is libc6-dbg installed? " << c.dump();
  EXPECT_GE(c["allocate"]["instructions"].get<double>(), 2e6 + 1) << c.dump();
  EXPECT_LE(c["allocate"]["instructions"].get<double>(), 2e6 + 1 + 3000 + 40000) << c.dump();
  EXPECT_GE(c["allocator_left_out"]["instructions"].get<double>(), 2000 * 25) << c.dump();
}

TEST(SectionCounter, PerfCountsTheKnownInstructionsWhereTheMachineHasCounters) {
  const test::CliResult r = test::run_command(std::string("'") + COROFEM_COUNT_PROBE + "' perf");
  if (r.exit_code == 3) GTEST_SKIP() << "no hardware counters here: " << r.err;
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json c = nlohmann::json::parse(r.out.substr(0, r.out.find('\n')));
  // Real hardware: interrupts add a little user-space work around the spin; 1%.
  EXPECT_NEAR(c["spin"]["instructions"].get<double>(), 2e6, 2e4) << c.dump();
  EXPECT_NEAR(c["outer/inner"]["instructions"].get<double>(), 6e5, 6e3) << c.dump();
}

}  // namespace
}  // namespace corofem
