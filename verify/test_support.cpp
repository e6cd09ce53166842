#include "test_support.hpp"

#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <fstream>
#include <random>
#include <sstream>
#include <stdexcept>

namespace corofem::test {
namespace fs = std::filesystem;

TempDir::TempDir() {
  std::random_device rd;
  path_ = fs::temp_directory_path() /
          ("corofem-test-" + std::to_string(::getpid()) + "-" + std::to_string(rd()));
  fs::create_directories(path_);
}

TempDir::~TempDir() {
  std::error_code ignored;
  fs::remove_all(path_, ignored);
}

void write_text(const fs::path& file, const std::string& text) {
  std::ofstream out(file, std::ios::binary);
  out << text;
}

std::string read_text(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

CliResult run_cli(const std::string& args) {
  TempDir dir;
  const std::string command = std::string("'") + COROFEM_CLI + "' " + args + " > '" +
                              (dir / "out").string() + "' 2> '" + (dir / "err").string() + "'";
  const int status = std::system(command.c_str());
  CliResult result;
  result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  result.out = read_text(dir / "out");
  result.err = read_text(dir / "err");
  return result;
}

fs::path source_dir() { return COROFEM_SOURCE_DIR; }

fs::path models_dir() {
  if (const char* env = std::getenv("COROFEM_MODELS"); env && *env)
    return fs::is_directory(env) ? fs::path(env) : fs::path();
  const fs::path shared = source_dir().parent_path() / "shared" / "models";
  return fs::is_directory(shared) ? shared : fs::path();
}

bool full_sweep() {
  const char* env = std::getenv("COROFEM_FULL");
  return env && std::string(env) == "1";
}

}  // namespace corofem::test
