// Content hashes (xxHash) and a thread-safe file-content hash cache whose fast path is a stat() check.
#pragma once
#include <deque>
#include <array>
#include <cstdint>
#include <filesystem>
#include <mutex>
#include <optional>
#include <string>
#include <string_view>
#include <unordered_map>

namespace wb::shader {

namespace fs = std::filesystem;

struct Hash128 {
  uint64_t lo = 0, hi = 0;
  bool operator==(const Hash128&) const = default;
  std::string hex() const;  // 32 hex digits
};

uint64_t hash64(const void* data, size_t size);
inline uint64_t hash64(std::string_view s) {
  return hash64(s.data(), s.size());
}

// Streaming xxh3-128.
class Hasher {
 public:
  Hasher();
  ~Hasher();
  Hasher(const Hasher&) = delete;
  Hasher& operator=(const Hasher&) = delete;
  Hasher& add(const void* data, size_t size);
  Hasher& add(std::string_view s);  // length-prefixed
  Hasher& add(uint64_t v) { return add(&v, sizeof v); }
  Hash128 finish() const;

 private:
  void* state_;
};

// The whole file; nullopt when it is missing, unreadable or not a regular file (common/file_io.h).
std::optional<std::string> readFile(const fs::path& p);

// Maps a path to the xxh3-64 of its contents. A cached hash is reused while (mtime, ctime, size, inode) are
// unchanged and the file was already older than the timestamp granularity when it was hashed ("racy" files
// are always re-read), so an edit within the same clock tick is never missed.
class FileHashCache {
 public:
  std::optional<uint64_t> hash(const fs::path& canonicalPath);
  // The text of a file that hashed to `hash` when hash() read it: the last kKeptTexts versions of each file.
  std::optional<std::string> text(const fs::path& canonicalPath, uint64_t hash) const;
  void invalidate(const fs::path& p);
  void clear();
  static constexpr size_t kKeptTexts = 8;

 private:
  struct Entry {
    int64_t mtimeNs, ctimeNs, size;
    uint64_t ino;
    uint64_t hash;
    bool trusted;
  };
  mutable std::mutex mutex_;
  std::unordered_map<std::string, Entry> entries_;
  std::unordered_map<std::string, std::deque<std::pair<uint64_t, std::string>>> texts_;  // newest last
};

}  // namespace wb::shader
