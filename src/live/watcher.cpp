#include "live/watcher.h"

#include <sys/inotify.h>
#include <unistd.h>

#include <cerrno>
#include <system_error>

namespace wb::live {

namespace {
constexpr uint32_t kMask = IN_CLOSE_WRITE | IN_MOVED_TO | IN_MOVED_FROM | IN_CREATE | IN_DELETE | IN_ATTRIB |
                           IN_MODIFY | IN_DELETE_SELF | IN_MOVE_SELF | IN_ONLYDIR;
}

bool DirWatcher::Event::overflow() const {
  return mask & IN_Q_OVERFLOW;
}
bool DirWatcher::Event::isDir() const {
  return mask & IN_ISDIR;
}

DirWatcher::DirWatcher(const std::vector<fs::path>& roots) {
  fd_ = inotify_init1(IN_NONBLOCK | IN_CLOEXEC);
  if (fd_ < 0) throw std::system_error(errno, std::generic_category(), "inotify_init1");
  for (const auto& r : roots) addRecursive(r);
}

DirWatcher::~DirWatcher() {
  if (fd_ >= 0) ::close(fd_);
}

void DirWatcher::addRecursive(const fs::path& dir) {
  std::error_code ec;
  fs::path canon = fs::canonical(dir, ec);
  if (ec || !fs::is_directory(canon, ec)) return;
  const int wd = inotify_add_watch(fd_, canon.c_str(), kMask);
  if (wd < 0) return;
  dirs_[wd] = canon;
  for (auto it = fs::directory_iterator(canon, ec); !ec && it != fs::directory_iterator(); it.increment(ec)) {
    std::error_code e2;
    if (it->is_directory(e2) && !it->is_symlink(e2)) addRecursive(it->path());
  }
}

std::vector<DirWatcher::Event> DirWatcher::read() {
  std::vector<Event> out;
  alignas(inotify_event) char buf[16384];
  for (;;) {
    const ssize_t n = ::read(fd_, buf, sizeof buf);
    if (n <= 0) break;
    for (ssize_t off = 0; off < n;) {
      const auto* e = reinterpret_cast<const inotify_event*>(buf + off);
      off += static_cast<ssize_t>(sizeof(inotify_event) + e->len);
      if (e->mask & IN_Q_OVERFLOW) {
        out.push_back({{}, e->mask});
        continue;
      }
      auto it = dirs_.find(e->wd);
      if (it == dirs_.end()) continue;
      if (e->mask & IN_IGNORED) {
        dirs_.erase(it);
        continue;
      }
      fs::path p = e->len ? it->second / e->name : it->second;
      if ((e->mask & IN_ISDIR) && (e->mask & (IN_CREATE | IN_MOVED_TO))) addRecursive(p);
      out.push_back({std::move(p), e->mask});
    }
  }
  return out;
}

}  // namespace wb::live
