// report/units_side_by_side.hpp: every unit runs once, at one thread, whole progress lines, and a
// failing unit's exception comes out only after every other unit has run.
#include <gtest/gtest.h>

#include <atomic>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/threads.hpp"
#include "report/units_side_by_side.hpp"

namespace corofem {
namespace {

TEST(UnitsSideBySide, EveryUnitRunsOnceAtOneThreadAndItsLinesStayWhole) {
  const ScopedThreadCount two(have_openmp() ? 2 : 1);
  std::vector<std::atomic<int>> runs(40);
  std::atomic<int> wider{0};
  std::ostringstream out;
  run_units_side_by_side(40, thread_count(), &out, [&](int k, std::ostream* lines) {
    ++runs[static_cast<std::size_t>(k)];
    if (thread_count() != 1) ++wider;
    *lines << "unit " << k << " of " << 40 << std::endl;
  });
  for (const auto& r : runs) EXPECT_EQ(r.load(), 1);
  EXPECT_EQ(wider.load(), 0);
  std::istringstream written(out.str());
  int count = 0;
  for (std::string line; std::getline(written, line); ++count)
    EXPECT_EQ(line.rfind("unit ", 0), 0u)
        << line;  // a line mixed from two units would not begin so
  EXPECT_EQ(count, 40);
}

TEST(UnitsSideBySide, TheFirstFailingUnitsExceptionComesOutAfterEveryUnitRan) {
  std::atomic<int> ran{0};
  try {
    run_units_side_by_side(12, thread_count(), nullptr, [&](int k, std::ostream* lines) {
      EXPECT_EQ(lines, nullptr);
      ++ran;
      if (k == 3 || k == 7) throw std::runtime_error("unit " + std::to_string(k));
    });
    ADD_FAILURE() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_STREQ(e.what(), "unit 3");
  }
  EXPECT_EQ(ran.load(), 12);
}

}  // namespace
}  // namespace corofem
