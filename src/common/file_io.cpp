#include "common/file_io.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>

namespace wb {
namespace {

std::string kindOf(mode_t mode) {
  if (S_ISREG(mode)) return "a regular file";
  if (S_ISDIR(mode)) return "a directory";
  if (S_ISFIFO(mode)) return "a named pipe";
  if (S_ISCHR(mode)) return "a character device";
  if (S_ISBLK(mode)) return "a block device";
  if (S_ISSOCK(mode)) return "a socket";
  return "not a regular file";
}

}  // namespace

std::string describeFileKind(const std::filesystem::path& path) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) {
    const int err = errno;
    struct stat lst {};
    if (err == ENOENT && ::lstat(path.c_str(), &lst) == 0 && S_ISLNK(lst.st_mode)) {
      std::error_code ec;
      return "a symbolic link to '" + std::filesystem::read_symlink(path, ec).string() +
             "', which does not exist";
    }
    return err == ENOENT ? "missing" : std::strerror(err);
  }
  return kindOf(st.st_mode);
}

std::optional<std::string> readRegularFile(const std::filesystem::path& path, std::string* why,
                                           uint64_t maxBytes) {
  auto failed = [&](const std::string& reason) -> std::optional<std::string> {
    if (why) *why = reason;
    return std::nullopt;
  };
  // O_NONBLOCK: opening a named pipe for reading would otherwise wait for a writer.
  const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC | O_NOCTTY);
  if (fd < 0) return failed(std::strerror(errno));
  struct stat st {};
  if (::fstat(fd, &st) != 0) {
    const std::string reason = std::strerror(errno);
    ::close(fd);
    return failed(reason);
  }
  if (!S_ISREG(st.st_mode)) {
    ::close(fd);
    return failed("is " + kindOf(st.st_mode) + ", not a regular file");
  }
  if (static_cast<uint64_t>(st.st_size) > maxBytes) {
    ::close(fd);
    return failed("file too large (" + std::to_string(st.st_size) + " bytes, at most " +
                  std::to_string(maxBytes) + ")");
  }
  std::string data;
  data.reserve(static_cast<size_t>(st.st_size));
  char buffer[65536];
  while (true) {
    const ssize_t n = ::read(fd, buffer, sizeof buffer);
    if (n < 0) {
      if (errno == EINTR) continue;
      const std::string reason = std::strerror(errno);
      ::close(fd);
      return failed(reason);
    }
    if (n == 0) break;
    if (data.size() + static_cast<size_t>(n) > maxBytes) {
      ::close(fd);
      return failed("file too large (grew past " + std::to_string(maxBytes) + " bytes while read)");
    }
    data.append(buffer, static_cast<size_t>(n));
  }
  ::close(fd);
  return data;
}

void requireWritableFile(const std::filesystem::path& path, const std::string& what) {
  auto fail = [&](const std::string& reason) {
    throw std::runtime_error(what + ": cannot write '" + path.string() + "': " + reason);
  };
  if (path.empty()) fail("empty path");
  struct stat st {};
  const bool exists = ::stat(path.c_str(), &st) == 0;
  if (exists) {
    if (S_ISDIR(st.st_mode)) fail("is a directory");
    // An existing file: open it for writing without truncating it (non-blocking: never wait on a pipe).
    const int fd = ::open(path.c_str(), O_WRONLY | O_NONBLOCK | O_CLOEXEC | O_NOCTTY);
    if (fd < 0) fail(std::strerror(errno));
    ::close(fd);
    if (!S_ISREG(st.st_mode)) return;  // a pipe or a device is written in place (common/atomic_file.h)
  }
  // The file is written beside itself and renamed over (common/atomic_file.h): its folder must take a new
  // file. The probe is created exclusively and removed again.
  const auto parent = path.has_parent_path() ? path.parent_path() : std::filesystem::path(".");
  std::error_code ec;
  std::filesystem::create_directories(parent, ec);  // `--out out/x.png` on a fresh checkout makes out/
  struct stat pst {};
  if (::stat(parent.c_str(), &pst) != 0) fail("folder '" + parent.string() + "': " + std::strerror(errno));
  if (!S_ISDIR(pst.st_mode)) fail("'" + parent.string() + "' is not a folder");
  const auto probe =
      exists ? parent / ("." + path.filename().string() + ".wb_probe." + std::to_string(::getpid())) : path;
  const int fd = ::open(probe.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
  if (fd < 0) {
    fail(exists ? "cannot create a file in '" + parent.string() +
                      "' (it is replaced by a new file): " + std::strerror(errno)
                : std::strerror(errno));
  }
  ::close(fd);
  ::unlink(probe.c_str());
}

void requireWritableDirectory(const std::filesystem::path& dir, const std::string& what) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (!std::filesystem::is_directory(dir)) {
    const std::string kind = describeFileKind(dir);
    const bool dangling = kind.rfind("a symbolic link", 0) == 0;
    throw std::runtime_error(what + ": cannot create folder '" + dir.string() +
                             "': " + (ec && !dangling ? ec.message() : "it is " + kind));
  }
  requireWritableFile(dir / (".wb_write_probe." + std::to_string(::getpid())), what);
}

}  // namespace wb
