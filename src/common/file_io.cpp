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
  if (::stat(path.c_str(), &st) != 0) return errno == ENOENT ? "missing" : std::strerror(errno);
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
  if (::stat(path.c_str(), &st) == 0) {
    if (S_ISDIR(st.st_mode)) fail("is a directory");
    // An existing file: open it for writing without truncating it (non-blocking: never wait on a pipe).
    const int fd = ::open(path.c_str(), O_WRONLY | O_NONBLOCK | O_CLOEXEC | O_NOCTTY);
    if (fd < 0) fail(std::strerror(errno));
    ::close(fd);
    return;
  }
  const auto parent = path.has_parent_path() ? path.parent_path() : std::filesystem::path(".");
  std::error_code ec;
  std::filesystem::create_directories(parent, ec);  // `--out out/x.png` on a fresh checkout makes out/
  struct stat pst {};
  if (::stat(parent.c_str(), &pst) != 0) fail("folder '" + parent.string() + "': " + std::strerror(errno));
  if (!S_ISDIR(pst.st_mode)) fail("'" + parent.string() + "' is not a folder");
  // Create it (exclusively: the file did not exist) and remove it again.
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
  if (fd < 0) fail(std::strerror(errno));
  ::close(fd);
  ::unlink(path.c_str());
}

void requireWritableDirectory(const std::filesystem::path& dir, const std::string& what) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (!std::filesystem::is_directory(dir)) {
    throw std::runtime_error(what + ": cannot create folder '" + dir.string() +
                             "': " + (ec ? ec.message() : "is " + describeFileKind(dir)));
  }
  requireWritableFile(dir / (".wb_write_probe." + std::to_string(::getpid())), what);
}

}  // namespace wb
