#include "core/atomic_file.hpp"

#include <unistd.h>

#include <csignal>
#include <cstdio>
#include <cstring>
#include <fstream>

#include "core/errors.hpp"

namespace corofem {
namespace fs = std::filesystem;

namespace {

// Temporary files being written, for the signal handler (fixed storage: handlers cannot allocate).
constexpr int kSlots = 8;
constexpr std::size_t kPathMax = 4096;
char g_partial[kSlots][kPathMax];
volatile std::sig_atomic_t g_used[kSlots];

int register_partial(const fs::path& tmp) {
  const std::string s = tmp.string();
  if (s.size() >= kPathMax) return -1;
  for (int i = 0; i < kSlots; ++i)
    if (!g_used[i]) {
      std::memcpy(g_partial[i], s.c_str(), s.size() + 1);
      g_used[i] = 1;
      return i;
    }
  return -1;
}

void unregister_partial(int slot) {
  if (slot >= 0) g_used[slot] = 0;
}

extern "C" void remove_partials_and_exit(int signal) {
  for (int i = 0; i < kSlots; ++i)
    if (g_used[i]) ::unlink(g_partial[i]);
  std::signal(signal, SIG_DFL);
  std::raise(signal);
}

fs::path temporary_beside(const fs::path& path) {
  fs::path tmp = path;
  tmp += ".tmp." + std::to_string(::getpid());
  return tmp;
}
}  // namespace

void remove_partial_outputs_on_interrupt() {
  std::signal(SIGINT, remove_partials_and_exit);
  std::signal(SIGTERM, remove_partials_and_exit);
}

void write_file_atomically(const fs::path& path, const std::function<void(std::ostream&)>& write) {
  const fs::path tmp = temporary_beside(path);
  const int slot = register_partial(tmp);
  struct Unregister {
    int slot;
    ~Unregister() { unregister_partial(slot); }
  } unregister{slot};
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) throw InputError("cannot write output file '" + path.string() + "'");
    try {
      write(out);
    } catch (...) {
      out.close();
      std::error_code ignored;
      fs::remove(tmp, ignored);
      throw;
    }
    out.flush();
    if (!out) {
      out.close();
      std::error_code ignored;
      fs::remove(tmp, ignored);
      throw InputError("failed while writing output file '" + path.string() +
                       "' (disk full or I/O error)");
    }
  }
  std::error_code ec;
  fs::rename(tmp, path, ec);
  if (ec) {
    std::error_code ignored;
    fs::remove(tmp, ignored);
    throw InputError("cannot move output into place at '" + path.string() + "': " + ec.message());
  }
}

void check_writable(const fs::path& path) {
  const fs::path tmp = temporary_beside(path);
  std::ofstream probe(tmp);
  if (!probe) throw InputError("cannot write output file '" + path.string() + "'");
  probe.close();
  std::error_code ignored;
  fs::remove(tmp, ignored);
}

void prepare_output_folder(const fs::path& dir, const std::string& file) {
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec)
    throw InputError("cannot create the output folder '" + dir.string() + "': " + ec.message());
  check_writable(dir / file);
}

}  // namespace corofem
