// One writer per output folder (core/folder_lock.hpp): a second writer of a folder refuses at its
// start, naming the folder and the first one's pid; the folder is free again when the first ends.
#include <gtest/gtest.h>
#include <unistd.h>

#include <optional>

#include "core/errors.hpp"
#include "core/folder_lock.hpp"
#include "test_support.hpp"

namespace corofem {
namespace {

TEST(FolderLock, ASecondWriterIsRefusedNamingTheFirst) {
  test::TempDir dir;
  const std::string pid = "pid " + std::to_string(::getpid());
  std::optional<FolderLock> first(std::in_place, dir.path(), "corofem report");
  try {
    FolderLock second(dir.path(), "corofem report");
    FAIL() << "two writers of one folder";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find(dir.path().string() + " is being written by another corofem report"),
              std::string::npos)
        << what;
    EXPECT_NE(what.find(pid), std::string::npos) << what;
  }
  // The report command refuses too, before it writes anything: exit 2, the message on stderr.
  const test::CliResult r =
      test::run_cli("report --smoke --no-render --out '" + dir.path().string() + "'");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find(pid), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "tables.json"));
  first.reset();  // the first writer ends: the folder is free
  EXPECT_NO_THROW(FolderLock(dir.path(), "corofem report"));
  EXPECT_FALSE(std::filesystem::exists(dir / ".writer"));  // and no note is left behind
}

}  // namespace
}  // namespace corofem
