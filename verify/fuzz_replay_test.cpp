// Replays the fuzz corpus (verify/fuzz/corpus/<target>/*) through the same entries as the
// libFuzzer targets: every file must end in a result or an InputError, never a crash or hang.
#include <gtest/gtest.h>

#include <chrono>
#include <fstream>
#include <iterator>

#include "fuzz/fuzz_entries.hpp"
#include "test_support.hpp"

namespace corofem {
namespace {

void replay(const std::string& target, void (*entry)(const std::uint8_t*, std::size_t)) {
  const auto dir = test::source_dir() / "verify/fuzz/corpus" / target;
  int files = 0;
  for (const auto& file : std::filesystem::directory_iterator(dir)) {
    std::ifstream in(file.path(), std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const auto start = std::chrono::steady_clock::now();
    EXPECT_NO_THROW(entry(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size()))
        << file.path();
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    EXPECT_LT(seconds, 10.0) << file.path() << " took too long";
    ++files;
  }
  EXPECT_GT(files, 0) << "empty corpus " << dir;
}

TEST(FuzzReplay, SceneCorpus) {
  replay("scene", &fuzz::scene_input);
}
TEST(FuzzReplay, MshCorpus) {
  replay("msh", &fuzz::msh_input);
}
TEST(FuzzReplay, StlCorpus) {
  replay("stl", &fuzz::stl_input);
}

}  // namespace
}  // namespace corofem
