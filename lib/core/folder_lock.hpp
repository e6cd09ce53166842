#pragma once
// One writer per output folder: a process that writes a folder (a report) holds DIR/.writer
// locked (flock) for as long as it writes, and says in it who it is. A second writer refuses at
// its start, naming the folder and the first one's pid, instead of colliding with it mid-way (a
// resumed report found its checkpoint removed under it). The kernel releases the lock when the
// process ends, however it ends: no stale lock.
#include <filesystem>
#include <string>

namespace corofem {

class FolderLock {
 public:
  /// Locks `dir` (created if need be) for this process; InputError naming the folder and the
  /// holder's pid and start where another process holds it. `what` names the writer in the
  /// message ("corofem report").
  FolderLock(const std::filesystem::path& dir, const std::string& what);
  ~FolderLock();
  FolderLock(const FolderLock&) = delete;
  FolderLock& operator=(const FolderLock&) = delete;

 private:
  std::filesystem::path file_;
  int fd_ = -1;
};

}  // namespace corofem
