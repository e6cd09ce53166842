#include "core/atomic_file.hpp"

#include <unistd.h>

#include <cstdio>
#include <fstream>

#include "core/errors.hpp"

namespace corofem {
namespace fs = std::filesystem;

namespace {
fs::path temporary_beside(const fs::path& path) {
  fs::path tmp = path;
  tmp += ".tmp." + std::to_string(::getpid());
  return tmp;
}
}  // namespace

void write_file_atomically(const fs::path& path, const std::function<void(std::ostream&)>& write) {
  const fs::path tmp = temporary_beside(path);
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

}  // namespace corofem
