#include "shader/hash.h"

#include "common/file_io.h"

#include <sys/stat.h>
#include <xxhash.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <sstream>

namespace wb::shader {

std::string Hash128::hex() const {
  char buf[33];
  std::snprintf(buf, sizeof buf, "%016llx%016llx", static_cast<unsigned long long>(hi),
                static_cast<unsigned long long>(lo));
  return buf;
}

uint64_t hash64(const void* data, size_t size) {
  return XXH3_64bits(data, size);
}

Hasher::Hasher() : state_(XXH3_createState()) {
  XXH3_128bits_reset(static_cast<XXH3_state_t*>(state_));
}
Hasher::~Hasher() {
  XXH3_freeState(static_cast<XXH3_state_t*>(state_));
}
Hasher& Hasher::add(const void* data, size_t size) {
  XXH3_128bits_update(static_cast<XXH3_state_t*>(state_), data, size);
  return *this;
}
Hasher& Hasher::add(std::string_view s) {
  add(static_cast<uint64_t>(s.size()));
  return add(s.data(), s.size());
}
Hash128 Hasher::finish() const {
  XXH128_hash_t h = XXH3_128bits_digest(static_cast<XXH3_state_t*>(state_));
  return {h.low64, h.high64};
}

std::optional<std::string> readFile(const fs::path& p) {
  return readRegularFile(p);  // a named pipe or device is unreadable here, never a wait
}

namespace {
int64_t toNs(const timespec& t) {
  return int64_t(t.tv_sec) * 1000000000LL + t.tv_nsec;
}
int64_t nowNs() {
  timespec t{};
  clock_gettime(CLOCK_REALTIME, &t);
  return toNs(t);
}
// File timestamps come from a coarse kernel clock; anything modified this recently may change again
// without its timestamp moving.
constexpr int64_t kRacyNs = 50'000'000;
}  // namespace

std::optional<uint64_t> FileHashCache::hash(const fs::path& p) {
  struct stat st {};
  const std::string key = p.string();
  if (::stat(key.c_str(), &st) != 0) {
    invalidate(p);
    return std::nullopt;
  }
  {
    std::lock_guard lock(mutex_);
    auto it = entries_.find(key);
    if (it != entries_.end() && it->second.trusted && it->second.mtimeNs == toNs(st.st_mtim) &&
        it->second.ctimeNs == toNs(st.st_ctim) && it->second.size == st.st_size &&
        it->second.ino == st.st_ino)
      return it->second.hash;
  }
  auto data = readFile(p);
  if (!data) return std::nullopt;
  uint64_t h = hash64(*data);
  const int64_t now = nowNs();
  std::lock_guard lock(mutex_);
  auto& kept = texts_[key];
  if (std::none_of(kept.begin(), kept.end(), [&](const auto& t) { return t.first == h; })) {
    kept.emplace_back(h, std::move(*data));
    if (kept.size() > kKeptTexts) kept.pop_front();
  }
  entries_[key] = Entry{toNs(st.st_mtim),
                        toNs(st.st_ctim),
                        st.st_size,
                        st.st_ino,
                        h,
                        now - toNs(st.st_mtim) > kRacyNs && now - toNs(st.st_ctim) > kRacyNs};
  return h;
}

std::optional<std::string> FileHashCache::text(const fs::path& p, uint64_t hash) const {
  std::lock_guard lock(mutex_);
  const auto it = texts_.find(p.string());
  if (it == texts_.end()) return std::nullopt;
  for (const auto& [h, t] : it->second)
    if (h == hash) return t;
  return std::nullopt;
}

void FileHashCache::invalidate(const fs::path& p) {
  std::lock_guard lock(mutex_);
  entries_.erase(p.string());
}

void FileHashCache::clear() {
  std::lock_guard lock(mutex_);
  entries_.clear();
}

}  // namespace wb::shader
