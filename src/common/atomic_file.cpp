#include "common/atomic_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <system_error>

#include "common/env.h"

namespace fs = std::filesystem;

namespace wb {
namespace {

// WB_SIMULATE_DISK_FULL=1 (tests where no small filesystem can be mounted): writes of file contents through
// this file fail with ENOSPC after part of the data, as on a full disk.
bool simulateDiskFull() {
  static const bool on = env::enabled("WB_SIMULATE_DISK_FULL");
  return on;
}

// Writes all of data to fd; false with errno set on failure (a write that makes no progress is ENOSPC).
bool writeAll(int fd, std::string_view data) {
  size_t done = 0;
  if (simulateDiskFull() && !data.empty()) {
    const size_t part = data.size() / 2;
    while (done < part) {
      const ssize_t n = ::write(fd, data.data() + done, part - done);
      if (n <= 0) break;
      done += size_t(n);
    }
    errno = ENOSPC;
    return false;
  }
  while (done < data.size()) {
    const ssize_t n = ::write(fd, data.data() + done, data.size() - done);
    if (n < 0) {
      if (errno == EINTR) continue;
      return false;
    }
    if (n == 0) {
      errno = ENOSPC;
      return false;
    }
    done += size_t(n);
  }
  return true;
}

std::string tempNameFor(const fs::path& target) {
  static std::atomic<uint64_t> counter{0};
  return "." + target.filename().string() + ".tmp." + std::to_string(::getpid()) + "." +
         std::to_string(counter++);
}

[[noreturn]] void fail(const std::string& what, const fs::path& path, const std::string& reason) {
  throw std::runtime_error((what.empty() ? std::string() : what + ": ") + "cannot write '" + path.string() +
                           "': " + reason);
}

// A target that is not a regular file (a pipe, a device): written where it is, every write checked. Opened
// non-blocking (a named pipe without a reader fails at once instead of waiting for one), then written
// blocking.
void writeInPlace(const fs::path& path, std::string_view data, const std::string& what) {
  const int fd = ::open(path.c_str(), O_WRONLY | O_NONBLOCK | O_CLOEXEC | O_NOCTTY);
  if (fd < 0) fail(what, path, writeErrorText(errno));
  const int flags = ::fcntl(fd, F_GETFL);
  if (flags >= 0) ::fcntl(fd, F_SETFL, flags & ~O_NONBLOCK);
  if (!writeAll(fd, data)) {
    const int err = errno;
    ::close(fd);
    fail(what, path, writeErrorText(err));
  }
  if (::close(fd) != 0) fail(what, path, writeErrorText(errno));
}

}  // namespace

std::string writeErrorText(int err) {
  std::string text = std::strerror(err);
  if (err == ENOSPC || err == EDQUOT) text += " (the disk is full)";
  return text;
}

void writeFileAtomically(const fs::path& requested, std::string_view data, const std::string& what,
                         FileKind kind) {
  if (requested.empty()) fail(what, requested, "empty path");
  fs::path path = requested;
  std::error_code ec;
  if (fs::is_symlink(requested, ec)) path = fs::weakly_canonical(requested, ec);  // replace what it points to
  if (ec) path = requested;
  struct stat st {};
  const bool exists = ::stat(path.c_str(), &st) == 0;
  if (exists && S_ISDIR(st.st_mode)) fail(what, requested, "is a directory");
  if (exists && !S_ISREG(st.st_mode) && kind == FileKind::Output) return writeInPlace(path, data, what);

  const fs::path dir = path.has_parent_path() ? path.parent_path() : fs::path(".");
  const fs::path temp = dir / tempNameFor(path);
  const int fd = ::open(temp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC | O_NOCTTY, 0666);
  if (fd < 0) {
    fail(what, requested, "cannot create a file in '" + dir.string() + "': " + writeErrorText(errno));
  }
  auto abandon = [&](int err, const std::string& step) {
    ::close(fd);
    ::unlink(temp.c_str());
    fail(what, requested, step + writeErrorText(err));
  };
  // The new file keeps the permissions of the one it replaces (a new one gets the umask's).
  if (exists && S_ISREG(st.st_mode) && ::fchmod(fd, st.st_mode & 07777) != 0) abandon(errno, "");
  if (!writeAll(fd, data)) abandon(errno, "");
  // On the disk before the rename: a crash then leaves the old file or the new one, never an empty one.
  if (kind == FileKind::Output && ::fsync(fd) != 0 && errno != EINVAL && errno != EROFS) abandon(errno, "");
  if (::close(fd) != 0) {
    const int err = errno;
    ::unlink(temp.c_str());
    fail(what, requested, writeErrorText(err));
  }
  if (std::rename(temp.c_str(), path.c_str()) != 0) {
    const int err = errno;
    ::unlink(temp.c_str());
    fail(what, requested, "cannot replace it: " + writeErrorText(err));
  }
}

AppendLog::AppendLog(const fs::path& path, std::string what) : path_(path), what_(std::move(what)) {
  // Non-blocking open: a named pipe without a reader is an error, not a wait. Written blocking.
  fd_ = ::open(path.c_str(), O_WRONLY | O_CREAT | O_APPEND | O_NONBLOCK | O_CLOEXEC | O_NOCTTY, 0666);
  if (fd_ < 0) fail(what_, path_, writeErrorText(errno));
  if (const int flags = ::fcntl(fd_, F_GETFL); flags >= 0) ::fcntl(fd_, F_SETFL, flags & ~O_NONBLOCK);
}

AppendLog::~AppendLog() {
  if (fd_ >= 0) ::close(fd_);
}

AppendLog::AppendLog(AppendLog&& other) noexcept
    : fd_(other.fd_),
      path_(std::move(other.path_)),
      what_(std::move(other.what_)),
      error_(std::move(other.error_)) {
  other.fd_ = -1;
}

AppendLog& AppendLog::operator=(AppendLog&& other) noexcept {
  if (this != &other) {
    if (fd_ >= 0) ::close(fd_);
    fd_ = other.fd_;
    path_ = std::move(other.path_);
    what_ = std::move(other.what_);
    error_ = std::move(other.error_);
    other.fd_ = -1;
  }
  return *this;
}

bool AppendLog::writeLine(std::string_view line) {
  if (fd_ < 0 || failed()) return false;
  std::string text(line);
  text += '\n';
  struct stat st {};
  const bool sized = ::fstat(fd_, &st) == 0 && S_ISREG(st.st_mode);
  if (writeAll(fd_, text)) return true;
  const int err = errno;
  // A line half written is taken back: the log holds whole lines only.
  if (sized) (void)!::ftruncate(fd_, st.st_size);
  error_ = (what_.empty() ? std::string() : what_ + ": ") + "cannot append to '" + path_.string() +
           "': " + writeErrorText(err) + "; later lines are not written";
  std::fprintf(stderr, "workbench: error: %s\n", error_.c_str());
  std::fflush(stderr);
  return false;
}

}  // namespace wb
