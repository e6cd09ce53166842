#include "core/folder_lock.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstring>
#include <ctime>
#include <fstream>
#include <sstream>

#include "core/errors.hpp"

namespace corofem {

namespace {

std::string now_text() {
  const std::time_t t = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&t));
  return text;
}

}  // namespace

FolderLock::FolderLock(const std::filesystem::path& dir, const std::string& what)
    : file_(dir / ".writer") {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  fd_ = ::open(file_.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  if (fd_ < 0)
    throw InputError(dir.string() + ": cannot open " + file_.string() + " (" +
                     std::strerror(errno) + ")");
  if (::flock(fd_, LOCK_EX | LOCK_NB) != 0) {
    std::ifstream in(file_);
    std::string holder;
    std::getline(in, holder);
    ::close(fd_);
    fd_ = -1;
    throw InputError(dir.string() + " is being written by another " + what + " (" +
                     (holder.empty() ? std::string("its pid unknown") : holder) +
                     "): wait for it to end, or give another --out");
  }
  std::ostringstream self;
  self << "pid " << ::getpid() << ", since " << now_text() << "\n";
  const std::string text = self.str();
  if (::ftruncate(fd_, 0) != 0 || ::write(fd_, text.data(), text.size()) < 0) {
    // The lock holds without the note; a refused writer then cannot name this one.
  }
}

FolderLock::~FolderLock() {
  if (fd_ < 0) return;
  std::error_code ec;
  std::filesystem::remove(file_, ec);  // before the unlock: no next writer's note is removed
  ::flock(fd_, LOCK_UN);
  ::close(fd_);
}

}  // namespace corofem
