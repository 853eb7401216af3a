#include "shader/cache.h"

#include "common/atomic_file.h"
#include "common/file_io.h"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstring>
#include <fstream>
#include <thread>

namespace wb::shader {

namespace {

constexpr char kEntryMagic[4] = {'W', 'B', 'S', 'C'};
constexpr char kIndexMagic[4] = {'W', 'B', 'S', 'I'};
constexpr size_t kHeaderSize = 4 + 4 + 16 + 8 + 8;

class Writer {
 public:
  void u32(uint32_t v) { raw(&v, 4); }
  void u64(uint64_t v) { raw(&v, 8); }
  void str(const std::string& s) {
    u32(static_cast<uint32_t>(s.size()));
    raw(s.data(), s.size());
  }
  void raw(const void* p, size_t n) { out.append(static_cast<const char*>(p), n); }
  std::string out;
};

class Reader {
 public:
  explicit Reader(const std::string& s) : s_(s) {}
  bool u32(uint32_t& v) { return raw(&v, 4); }
  bool u64(uint64_t& v) { return raw(&v, 8); }
  bool str(std::string& v) {
    uint32_t n = 0;
    if (!u32(n) || n > s_.size() - pos_) return false;
    v.assign(s_.data() + pos_, n);
    pos_ += n;
    return true;
  }
  bool raw(void* p, size_t n) {
    if (n > s_.size() - pos_) return false;
    std::memcpy(p, s_.data() + pos_, n);
    pos_ += n;
    return true;
  }
  bool done() const { return pos_ == s_.size(); }

 private:
  const std::string& s_;
  size_t pos_ = 0;
};

std::string tempName() {
  static std::atomic<uint64_t> counter{0};
  const uint64_t tid = std::hash<std::thread::id>{}(std::this_thread::get_id());
  return ".tmp." + std::to_string(::getpid()) + "." + std::to_string(tid % 100000) + "." +
         std::to_string(counter++);
}

}  // namespace

DiskCache::DiskCache(fs::path dir, WarnFn warn, PruneLimits limits)
    : dir_(std::move(dir)), warn_(std::move(warn)) {
  if (dir_.empty()) return;
  std::error_code ec;
  fs::create_directories(dir_, ec);
  if (ec || !fs::is_directory(dir_)) {
    const std::string kind = describeFileKind(dir_);
    disable("cannot create cache directory " + dir_.string() + ": " +
            (kind.rfind("a symbolic link", 0) == 0 || !ec ? "it is " + kind : ec.message()));
    return;
  }
  enabled_ = true;
  // Probe: can we create a file there? A read-only folder (a shared or packaged cache) still serves reads.
  const fs::path probe = dir_ / tempName();
  const int fd = ::open(probe.c_str(), O_WRONLY | O_CREAT | O_EXCL, 0644);
  if (fd < 0) {
    if (warn_) {
      warn_("shader cache: " + dir_.string() + " is not writable (" + std::strerror(errno) +
            "): reading its entries, writing none");
    }
    return;
  }
  ::close(fd);
  fs::remove(probe, ec);
  writable_ = true;
  prune(limits);
}

void DiskCache::disable(const std::string& why) {
  enabled_ = false;
  writable_ = false;
  if (warn_) warn_("shader cache: " + why + "; using a memory-only cache");
}

std::optional<std::string> DiskCache::readChecked(const fs::path& p, const char magic[4],
                                                  const Hash128& key) {
  std::error_code ec;
  if (!fs::exists(p, ec)) return std::nullopt;
  std::string unreadable;
  auto data = readRegularFile(p, &unreadable);  // non-blocking: a named pipe here is refused, not waited on
  auto reject = [&](const std::string& why) -> std::optional<std::string> {
    if (warn_) warn_("shader cache: discarding " + p.string() + ": " + why);
    std::error_code rec;
    if (writable_) fs::remove(p, rec);
    return std::nullopt;
  };
  if (!data) return reject("unreadable (" + unreadable + ")");
  if (data->empty()) return reject("empty file");
  if (data->size() < kHeaderSize)
    return reject("truncated header (" + std::to_string(data->size()) + " bytes)");
  if (std::memcmp(data->data(), magic, 4) != 0) return reject("bad magic (not a cache file)");
  Reader r(*data);
  char m[4];
  uint32_t version = 0;
  Hash128 k;
  uint64_t size = 0, checksum = 0;
  r.raw(m, 4);
  r.u32(version);
  r.u64(k.lo);
  r.u64(k.hi);
  r.u64(size);
  r.u64(checksum);
  if (version != kFormatVersion)
    return reject("format version " + std::to_string(version) + ", expected " +
                  std::to_string(kFormatVersion));
  if (!(k == key)) return reject("key mismatch");
  if (size != data->size() - kHeaderSize)
    return reject("payload size " + std::to_string(data->size() - kHeaderSize) + ", header says " +
                  std::to_string(size) + " (truncated?)");
  std::string payload = data->substr(kHeaderSize);
  if (hash64(payload) != checksum) return reject("checksum mismatch");
  return payload;
}

bool DiskCache::writeAtomic(const fs::path& p, const char magic[4], const Hash128& key,
                            const std::string& payload) {
  if (!writable_) return false;
  Writer w;
  w.raw(magic, 4);
  w.u32(kFormatVersion);
  w.u64(key.lo);
  w.u64(key.hi);
  w.u64(payload.size());
  w.u64(hash64(payload));
  w.raw(payload.data(), payload.size());
  try {
    writeFileAtomically(p, w.out, "shader cache", FileKind::Cache);
  } catch (const std::exception& e) {
    if (warn_) warn_(e.what());
    return false;
  }
  return true;
}

std::optional<std::vector<fs::path>> DiskCache::loadIndex(const Hash128& variant) {
  if (!enabled_) return std::nullopt;
  auto payload = readChecked(indexPath(variant), kIndexMagic, variant);
  if (!payload) return std::nullopt;
  Reader r(*payload);
  uint32_t n = 0;
  std::vector<fs::path> files;
  bool ok = r.u32(n) && n < 100000;
  for (uint32_t i = 0; ok && i < n; ++i) {
    std::string s;
    ok = r.str(s);
    files.emplace_back(s);
  }
  if (!ok || !r.done() || files.empty()) {
    if (warn_) warn_("shader cache: discarding malformed index " + indexPath(variant).string());
    std::error_code ec;
    if (writable_) fs::remove(indexPath(variant), ec);
    return std::nullopt;
  }
  std::error_code ec;
  if (writable_)
    fs::last_write_time(indexPath(variant), fs::file_time_type::clock::now(), ec);  // LRU, as load()
  return files;
}

void DiskCache::storeIndex(const Hash128& variant, const std::vector<fs::path>& files) {
  if (!enabled_) return;
  Writer w;
  w.u32(static_cast<uint32_t>(files.size()));
  for (const auto& f : files) w.str(f.string());
  writeAtomic(indexPath(variant), kIndexMagic, variant, w.out);
}

std::optional<CacheEntry> DiskCache::load(const Hash128& key) {
  if (!enabled_) return std::nullopt;
  const fs::path p = entryPath(key);
  auto payload = readChecked(p, kEntryMagic, key);
  if (!payload) return std::nullopt;
  Reader r(*payload);
  CacheEntry e;
  e.key = key;
  uint32_t words = 0, nfiles = 0, nwarn = 0;
  bool ok = r.u32(words) && words > 0 && uint64_t(words) * 4 <= payload->size();
  if (ok) {
    e.spirv.resize(words);
    ok = r.raw(e.spirv.data(), words * 4ull) && e.spirv[0] == 0x07230203u;
  }
  ok = ok && r.u32(nfiles) && nfiles < 100000;
  for (uint32_t i = 0; ok && i < nfiles; ++i) {
    std::string s;
    ok = r.str(s);
    e.files.emplace_back(s);
  }
  ok = ok && r.u32(nwarn) && nwarn < 100000;
  for (uint32_t i = 0; ok && i < nwarn; ++i) {
    Diagnostic d;
    std::string file;
    uint32_t line = 0;
    ok = r.str(file) && r.u32(line) && r.str(d.severity) && r.str(d.message);
    d.file = file;
    d.line = static_cast<int>(line);
    e.warnings.push_back(std::move(d));
  }
  if (!ok || !r.done()) {
    if (warn_) warn_("shader cache: discarding malformed entry " + p.string());
    std::error_code ec;
    if (writable_) fs::remove(p, ec);
    return std::nullopt;
  }
  std::error_code ec;
  if (writable_) fs::last_write_time(p, fs::file_time_type::clock::now(), ec);  // LRU for pruning
  return e;
}

void DiskCache::store(const CacheEntry& e) {
  if (!enabled_) return;
  Writer w;
  w.u32(static_cast<uint32_t>(e.spirv.size()));
  w.raw(e.spirv.data(), e.spirv.size() * 4);
  w.u32(static_cast<uint32_t>(e.files.size()));
  for (const auto& f : e.files) w.str(f.string());
  w.u32(static_cast<uint32_t>(e.warnings.size()));
  for (const auto& d : e.warnings) {
    w.str(d.file.string());
    w.u32(static_cast<uint32_t>(d.line));
    w.str(d.severity);
    w.str(d.message);
  }
  writeAtomic(entryPath(e.key), kEntryMagic, e.key, w.out);
}

void DiskCache::prune(const PruneLimits& limits) {
  if (!writable_) return;
  struct Item {
    fs::path path;
    fs::file_time_type time;
    uint64_t size;
  };
  std::vector<Item> items;
  const auto now = fs::file_time_type::clock::now();
  std::error_code ec;
  for (auto it = fs::directory_iterator(dir_, ec); !ec && it != fs::directory_iterator(); it.increment(ec)) {
    const fs::path p = it->path();
    const std::string name = p.filename().string();
    std::error_code e2;
    const auto t = fs::last_write_time(p, e2);
    if (e2) continue;
    if (name.rfind(".tmp.", 0) == 0) {
      if (now - t > std::chrono::hours(1)) fs::remove(p, e2);  // left by a crashed writer
      continue;
    }
    if (p.extension() != ".wbspv" && p.extension() != ".wbidx") continue;
    if (!it->is_regular_file(e2)) {  // a named pipe, a folder...: never a cache entry
      if (warn_) warn_("shader cache: discarding " + p.string() + ": is " + describeFileKind(p));
      fs::remove_all(p, e2);
      continue;
    }
    if (now - t > std::chrono::hours(24) * limits.maxAgeDays) {
      fs::remove(p, e2);
      continue;
    }
    items.push_back({p, t, static_cast<uint64_t>(fs::file_size(p, e2))});
  }
  uint64_t total = 0;
  for (const auto& i : items) total += i.size;
  if (total <= limits.maxBytes) return;
  std::sort(items.begin(), items.end(), [](const Item& a, const Item& b) { return a.time < b.time; });
  for (const auto& i : items) {
    if (total <= limits.maxBytes) break;
    std::error_code e2;
    fs::remove(i.path, e2);
    total -= i.size;
  }
}

}  // namespace wb::shader
