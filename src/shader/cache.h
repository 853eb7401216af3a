// On-disk SPIR-V cache. Two kinds of files in one flat directory, both written atomically (temp file in the
// same directory + rename, so concurrent processes are safe) and both checked on load:
//   <variant>.wbidx  index: variant key (path, stage, defines, entry, options, compiler) -> dependency list
//   <content>.wbspv  entry: content key (variant + contents of every dependency) -> SPIR-V + deps + warnings
// File layout of both: magic(4) formatVersion(u32) key(16) payloadSize(u64) xxh64(payload)(u64) payload.
// A truncated, empty, garbage, wrong-version or bad-checksum file, or anything that is not a regular file (a
// named pipe is never opened for a blocking read), is discarded with a warning.
#pragma once
#include "shader/hash.h"
#include "shader/types.h"

#include <functional>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

namespace wb::shader {

struct CacheEntry {
  Hash128 key;
  std::vector<uint32_t> spirv;
  std::vector<fs::path> files;
  std::vector<Diagnostic> warnings;
};

struct CachePruneLimits {
  int maxAgeDays = 30;                       // entries not used (mtime is touched on a hit) for longer go
  uint64_t maxBytes = 256ull * 1024 * 1024;  // then the least recently used beyond this size
};

class DiskCache {
 public:
  static constexpr uint32_t kFormatVersion = 1;
  using PruneLimits = CachePruneLimits;
  using WarnFn = std::function<void(const std::string&)>;

  // Empty dir = disabled. A directory that cannot be made disables the cache with a warning; one that exists
  // but takes no new files (read-only) is read from, with one warning, and never written.
  DiskCache(fs::path dir, WarnFn warn, PruneLimits limits = {});
  bool enabled() const { return enabled_; }
  bool writable() const { return writable_; }
  const fs::path& dir() const { return dir_; }

  std::optional<std::vector<fs::path>> loadIndex(const Hash128& variant);
  void storeIndex(const Hash128& variant, const std::vector<fs::path>& files);
  std::optional<CacheEntry> load(const Hash128& key);
  void store(const CacheEntry& e);

  fs::path entryPath(const Hash128& key) const { return dir_ / (key.hex() + ".wbspv"); }
  fs::path indexPath(const Hash128& variant) const { return dir_ / (variant.hex() + ".wbidx"); }
  void prune(const PruneLimits& limits);

 private:
  std::optional<std::string> readChecked(const fs::path& p, const char magic[4], const Hash128& key);
  bool writeAtomic(const fs::path& p, const char magic[4], const Hash128& key, const std::string& payload);
  void disable(const std::string& why);

  fs::path dir_;
  WarnFn warn_;
  bool enabled_ = false;
  bool writable_ = false;
  std::mutex mutex_;
};

}  // namespace wb::shader
