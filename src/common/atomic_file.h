// Every file the workbench writes is written whole or not at all: the one way outputs reach the disk (images,
// JSON, reports, caches) and the one way logs are appended to.
#pragma once
#include <filesystem>
#include <string>
#include <string_view>

namespace wb {

// Writes `data` to `path` whole or not at all: into a temporary file beside it (the same folder, so that the
// rename is atomic), every write and the close checked, flushed to the disk (fsync), then renamed over
// `path`. On failure the temporary file is removed, `path` keeps what it held, and std::runtime_error says
// what failed, naming `what` (the flag or the kind of file, e.g. "--stats") and the path: "--stats: cannot
// write 'out/x.json': No space left on device (the disk is full)". A missing folder is not created here
// (requireWritableFile() checks outputs, and makes their folders, before the work).
// A symbolic link is followed: the file it points to is replaced, the link stays.
//
// An output (FileKind::Output) that exists and is not a regular file (a named pipe, /dev/stdout, a terminal)
// is written in place, every write checked: there is nothing to replace atomically there; a pipe without a
// reader is an error, not a wait. A cache file (FileKind::Cache: its entries are checked when read and cost
// a recompile when lost) is not flushed to the disk, so that a compile on the hot-reload path does not wait
// for it, and anything but a folder in its place is replaced.
enum class FileKind { Output, Cache };
void writeFileAtomically(const std::filesystem::path& path, std::string_view data, const std::string& what,
                         FileKind kind = FileKind::Output);

// An append-only log file (`watch --log`): each line goes out in one write(2) of its own (O_APPEND), checked.
// The first failure is reported once on stderr, naming `what` and the path, and failed() stays true so that
// the command can exit non-zero; later lines are not attempted.
class AppendLog {
 public:
  AppendLog() = default;
  // Opens (creating) `path` for appending; throws std::runtime_error naming `what`, the path and the reason.
  AppendLog(const std::filesystem::path& path, std::string what);
  ~AppendLog();
  AppendLog(AppendLog&& other) noexcept;
  AppendLog& operator=(AppendLog&& other) noexcept;
  AppendLog(const AppendLog&) = delete;
  AppendLog& operator=(const AppendLog&) = delete;

  bool isOpen() const { return fd_ >= 0; }
  // Appends `line` and a newline. False when this or an earlier write failed.
  bool writeLine(std::string_view line);
  bool failed() const { return !error_.empty(); }
  const std::string& error() const { return error_; }  // the first failure, as reported

 private:
  int fd_ = -1;
  std::filesystem::path path_;
  std::string what_;
  std::string error_;
};

// The reason for a failed write, as the messages above give it: strerror, plus what it means where that helps
// ("(the disk is full)" for ENOSPC and EDQUOT).
std::string writeErrorText(int err);

}  // namespace wb
