// Recursive inotify watch on directories (never on files, so saves by rename/replace, truncate+write,
// delete+recreate and touch are all seen). New subdirectories are watched as they appear.
#pragma once
#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace wb::live {

namespace fs = std::filesystem;

class DirWatcher {
 public:
  struct Event {
    fs::path path;  // watched dir / name (the directory itself for IN_Q_OVERFLOW: empty)
    uint32_t mask;  // IN_* bits
    bool overflow() const;
    bool isDir() const;
  };
  explicit DirWatcher(const std::vector<fs::path>& roots);  // throws std::system_error if inotify fails
  ~DirWatcher();
  DirWatcher(const DirWatcher&) = delete;
  DirWatcher& operator=(const DirWatcher&) = delete;

  int fd() const { return fd_; }
  // Non-blocking: drains what the kernel has queued.
  std::vector<Event> read();
  size_t watchCount() const { return dirs_.size(); }

 private:
  void addRecursive(const fs::path& dir);
  int fd_ = -1;
  std::map<int, fs::path> dirs_;
};

}  // namespace wb::live
