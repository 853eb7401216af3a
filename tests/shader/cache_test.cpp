// Disk cache: warm start, invalidation, corruption, unwritable directories, concurrent processes.
#include "shader/library.h"
#include "test_util.h"

#include <sched.h>
#include <signal.h>
#include <sys/mount.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <functional>

using namespace wb::shader;
using namespace wb::shader::test;

namespace {

std::vector<fs::path> entries(const fs::path& dir, const std::string& ext = ".wbspv") {
  std::vector<fs::path> out;
  for (const auto& e : fs::directory_iterator(dir))
    if (e.path().extension() == ext) out.push_back(e.path());
  return out;
}

struct CacheFixture : ::testing::Test {
  TempDir t;
  fs::path cache() const { return t / "cache"; }
  void SetUp() override {
    writeFile(t / "a.comp", kComputeMain);
    writeFile(t / "inc.glsl", "#define VALUE 1u\n");
    writeFile(t / "b.comp", "#version 460\nlayout(local_size_x = 1) in;\nvoid main() {}\n");
  }
  ShaderLibrary lib() { return ShaderLibrary({.cacheDir = cache(), .printWarnings = false}); }
};

}  // namespace

TEST_F(CacheFixture, WarmStartHasZeroCompiles) {
  std::vector<uint32_t> spirv;
  {
    auto l = lib();
    spirv = l.compile({t / "a.comp"})->spirv;
    l.compile({t / "b.comp"});
    EXPECT_EQ(l.stats().compiles, 2u);
    EXPECT_EQ(l.stats().misses, 2u);
  }
  auto l = lib();
  auto a = l.compile({t / "a.comp"});
  auto b = l.compile({t / "b.comp"});
  EXPECT_TRUE(a->cacheHit);
  EXPECT_TRUE(b->cacheHit);
  EXPECT_EQ(a->spirv, spirv);
  EXPECT_EQ(a->files, (std::vector<fs::path>{t / "a.comp", t / "inc.glsl"}));
  EXPECT_EQ(a->reflection.bindings.size(), 1u);
  EXPECT_EQ(l.stats().compiles, 0u);
  EXPECT_EQ(l.stats().hits, 2u);
  EXPECT_TRUE(l.cacheWarnings().empty());
  // Same library again: memory hit, same object.
  EXPECT_EQ(l.compile({t / "a.comp"}), a);
  EXPECT_EQ(l.stats().compiles, 0u);
}

TEST_F(CacheFixture, IncludeEditInvalidatesDependentsOnly) {
  {
    auto l = lib();
    l.compile({t / "a.comp"});
    l.compile({t / "b.comp"});
  }
  writeFile(t / "inc.glsl", "#define VALUE 2u\n");  // same size, same clock tick: must still be seen
  {
    auto l = lib();
    auto a = l.compile({t / "a.comp"});
    auto b = l.compile({t / "b.comp"});
    EXPECT_FALSE(a->cacheHit);
    EXPECT_TRUE(b->cacheHit);
    EXPECT_EQ(l.stats().compiles, 1u);
  }
  // In one library too.
  auto l = lib();
  auto a1 = l.compile({t / "a.comp"});
  writeFile(t / "inc.glsl", "#define VALUE 3u\n");
  auto a2 = l.compile({t / "a.comp"});
  EXPECT_NE(a1, a2);
  EXPECT_NE(a1->spirv, a2->spirv);
  EXPECT_EQ(l.stats().compiles, 1u);
  // Reverting the edit finds the old entry on disk.
  writeFile(t / "inc.glsl", "#define VALUE 2u\n");
  auto a3 = l.compile({t / "a.comp"});
  EXPECT_TRUE(a3->cacheHit);
  EXPECT_EQ(a3->spirv, a1->spirv);
  EXPECT_EQ(l.stats().compiles, 1u);
}

TEST_F(CacheFixture, DefineChangeGivesSeparateEntry) {
  writeFile(t / "inc.glsl", "#define VALUE BASE\n");
  {
    auto l = lib();
    auto x = l.compile({t / "a.comp", std::nullopt, {{"BASE", "1u"}}});
    auto y = l.compile({t / "a.comp", std::nullopt, {{"BASE", "2u"}}});
    EXPECT_NE(x->spirv, y->spirv);
    EXPECT_EQ(l.stats().compiles, 2u);
  }
  EXPECT_EQ(entries(cache()).size(), 2u);
  EXPECT_EQ(entries(cache(), ".wbidx").size(), 2u);
  auto l = lib();
  EXPECT_TRUE(l.compile({t / "a.comp", std::nullopt, {{"BASE", "2u"}}})->cacheHit);
  EXPECT_TRUE(l.compile({t / "a.comp", std::nullopt, {{"BASE", "1u"}}})->cacheHit);
  EXPECT_EQ(l.stats().compiles, 0u);
  // An option change misses too.
  ShaderLibrary opt({.cacheDir = cache(), .optimize = true, .printWarnings = false});
  EXPECT_FALSE(opt.compile({t / "a.comp", std::nullopt, {{"BASE", "1u"}}})->cacheHit);
}

namespace {
enum class Corruption { Truncated, Empty, Garbage, WrongVersion, BadChecksum };
}

class CorruptEntry : public CacheFixture, public ::testing::WithParamInterface<Corruption> {};

TEST_P(CorruptEntry, IsRebuiltWithWarning) {
  std::vector<uint32_t> good;
  {
    auto l = lib();
    good = l.compile({t / "a.comp"})->spirv;
  }
  auto files = entries(cache());
  ASSERT_EQ(files.size(), 1u);
  std::string data = readAll(files[0]);
  std::string expectWord;
  switch (GetParam()) {
    case Corruption::Truncated:
      data.resize(data.size() / 2);
      expectWord = "truncated";
      break;
    case Corruption::Empty:
      data.clear();
      expectWord = "empty";
      break;
    case Corruption::Garbage:
      for (size_t i = 0; i < data.size(); ++i) data[i] = static_cast<char>((i * 7919 + 13) & 0xff);
      expectWord = "magic";
      break;
    case Corruption::WrongVersion:
      data[4] = 99;
      expectWord = "version";
      break;
    case Corruption::BadChecksum:
      data[data.size() - 5] ^= 0x5a;
      expectWord = "checksum";
      break;
  }
  writeFile(files[0], data);
  {
    auto l = lib();
    auto s = l.compile({t / "a.comp"});
    EXPECT_FALSE(s->cacheHit);
    EXPECT_EQ(s->spirv, good);
    EXPECT_EQ(l.stats().compiles, 1u);
    auto w = l.cacheWarnings();
    ASSERT_EQ(w.size(), 1u);
    EXPECT_NE(w[0].find(expectWord), std::string::npos) << w[0];
  }
  auto l = lib();  // rebuilt entry is valid
  EXPECT_TRUE(l.compile({t / "a.comp"})->cacheHit);
  EXPECT_TRUE(l.cacheWarnings().empty());
}

INSTANTIATE_TEST_SUITE_P(All, CorruptEntry,
                         ::testing::Values(Corruption::Truncated, Corruption::Empty, Corruption::Garbage,
                                           Corruption::WrongVersion, Corruption::BadChecksum));

TEST_F(CacheFixture, CorruptIndexIsRebuiltWithWarning) {
  { lib().compile({t / "a.comp"}); }
  auto idx = entries(cache(), ".wbidx");
  ASSERT_EQ(idx.size(), 1u);
  writeFile(idx[0], "garbage");
  auto l = lib();
  EXPECT_FALSE(l.compile({t / "a.comp"})->cacheHit);
  EXPECT_EQ(l.cacheWarnings().size(), 1u);
}

TEST_F(CacheFixture, UnwritableCacheDirDegradesToMemoryOnly) {
  // Tests run as root, where chmod does not stop writes: put the cache dir under a regular file.
  writeFile(t / "blocker", "not a directory");
  ShaderLibrary l({.cacheDir = t / "blocker/cache", .printWarnings = false});
  EXPECT_FALSE(l.diskCacheEnabled());
  ASSERT_EQ(l.cacheWarnings().size(), 1u);
  EXPECT_NE(l.cacheWarnings()[0].find("memory-only"), std::string::npos);
  auto s = l.compile({t / "a.comp"});
  EXPECT_FALSE(s->spirv.empty());
  EXPECT_EQ(l.compile({t / "a.comp"}), s);  // memory cache still works
  EXPECT_EQ(l.stats().compiles, 1u);
  // A directory in /proc cannot take files either.
  ShaderLibrary p({.cacheDir = "/proc/self/wb_cache", .printWarnings = false});
  EXPECT_FALSE(p.diskCacheEnabled());
}

namespace {

// Runs `body` in a child process and waits for it at most `seconds`: a hang is a failed test (the child is
// killed) instead of a test that never ends. Returns the child's exit status, or -1 when it was killed.
int inChild(const std::function<int()>& body, int seconds = 120) {
  const pid_t pid = fork();
  if (pid == 0) {
    int rc = 1;
    try {
      rc = body();
    } catch (...) {
      rc = 100;
    }
    _exit(rc);
  }
  for (int i = 0; i < seconds * 20; ++i) {
    int status = 0;
    if (waitpid(pid, &status, WNOHANG) == pid) return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    usleep(50000);
  }
  kill(pid, SIGKILL);
  waitpid(pid, nullptr, 0);
  return -1;
}

}  // namespace

// A cache entry or index replaced by a named pipe: a miss with a warning, never a blocking read.
TEST_F(CacheFixture, NamedPipeInsteadOfAnEntryIsAMissNotAHang) {
  std::vector<uint32_t> good;
  {
    auto l = lib();
    good = l.compile({t / "a.comp"})->spirv;
  }
  for (const char* ext : {".wbspv", ".wbidx"}) {
    { lib().compile({t / "a.comp"}); }  // both files exist again
    const auto files = entries(cache(), ext);
    ASSERT_EQ(files.size(), 1u);
    fs::remove(files[0]);
    ASSERT_EQ(mkfifo(files[0].c_str(), 0644), 0);
    const int rc = inChild([&] {
      auto l = lib();
      auto s = l.compile({t / "a.comp"});
      if (s->cacheHit || s->spirv != good) return 2;
      const auto w = l.cacheWarnings();
      return w.size() == 1 && w[0].find("named pipe") != std::string::npos ? 0 : 3;
    });
    EXPECT_EQ(rc, 0) << ext << (rc == -1 ? ": hung on the named pipe" : "");
    fs::remove(files[0]);  // if the child hung, the pipe is still there
  }
}

// A read-only cache folder still serves its entries (one warning, nothing written).
TEST_F(CacheFixture, ReadOnlyCacheDirIsReadNotWritten) {
  { lib().compile({t / "a.comp"}); }
  const size_t before = entries(cache()).size() + entries(cache(), ".wbidx").size();
  const int rc = inChild([&] {
    // root ignores permission bits: make the folder read-only with a read-only bind mount in a mount
    // namespace of this child's own; others drop the write bits.
    if (geteuid() == 0) {
      if (unshare(CLONE_NEWNS) != 0 || mount(nullptr, "/", nullptr, MS_REC | MS_PRIVATE, nullptr) != 0 ||
          mount(cache().c_str(), cache().c_str(), nullptr, MS_BIND, nullptr) != 0 ||
          mount(nullptr, cache().c_str(), nullptr, MS_BIND | MS_REMOUNT | MS_RDONLY, nullptr) != 0)
        return 50;  // no mount namespace here: skipped below
    } else {
      fs::permissions(cache(), fs::perms::owner_write | fs::perms::group_write | fs::perms::others_write,
                      fs::perm_options::remove);
    }
    auto l = lib();
    auto a = l.compile({t / "a.comp"});
    l.compile({t / "b.comp"});  // a miss: compiled, not stored
    const auto w = l.cacheWarnings();
    if (!a->cacheHit) return 2;
    if (l.stats().hits != 1 || l.stats().compiles != 1) return 3;
    if (w.size() != 1 || w[0].find("not writable") == std::string::npos) return 4;
    return 0;
  });
  if (rc == 50) GTEST_SKIP() << "cannot make a read-only folder here (no mount namespace for root)";
  EXPECT_EQ(rc, 0);
  fs::permissions(cache(), fs::perms::owner_all, fs::perm_options::add);
  EXPECT_EQ(entries(cache()).size() + entries(cache(), ".wbidx").size(), before)
      << "wrote to a read-only cache";
}

TEST_F(CacheFixture, TwoProcessesWritingAtOnce) {
  std::vector<ShaderKey> keys;
  writeFile(t / "inc.glsl", "#define VALUE BASE\n");
  for (int i = 0; i < 12; ++i)
    keys.push_back({t / "a.comp", std::nullopt, {{"BASE", std::to_string(i) + "u"}}});
  keys.push_back({t / "b.comp"});
  std::vector<pid_t> pids;
  for (int p = 0; p < 2; ++p) {
    pid_t pid = fork();
    ASSERT_GE(pid, 0);
    if (pid == 0) {
      int rc = 0;
      try {
        ShaderLibrary l({.cacheDir = cache(), .printWarnings = false});
        for (int round = 0; round < 2; ++round)
          for (const auto& k : keys) l.compile(k);
        rc = l.cacheWarnings().empty() ? 0 : 2;
      } catch (...) {
        rc = 1;
      }
      _exit(rc);
    }
    pids.push_back(pid);
  }
  for (pid_t pid : pids) {
    int status = 0;
    waitpid(pid, &status, 0);
    EXPECT_TRUE(WIFEXITED(status));
    EXPECT_EQ(WEXITSTATUS(status), 0);
  }
  auto l = lib();
  for (const auto& k : keys) EXPECT_TRUE(l.compile(k)->cacheHit);
  EXPECT_EQ(l.stats().compiles, 0u);
  EXPECT_TRUE(l.cacheWarnings().empty());
  for (const auto& e : fs::directory_iterator(cache()))
    EXPECT_EQ(e.path().filename().string().rfind(".tmp.", 0), std::string::npos) << e.path();
}

TEST_F(CacheFixture, PruneBySize) {
  { lib().compile({t / "a.comp"}); }
  EXPECT_EQ(entries(cache()).size(), 1u);
  DiskCache d(cache(), nullptr, CachePruneLimits{30, 0});
  EXPECT_TRUE(entries(cache()).empty());
}

namespace {

bool holdsWord(const std::vector<uint32_t>& spirv, uint32_t word) {
  return std::find(spirv.begin(), spirv.end(), word) != spirv.end();
}

}  // namespace

// A revert keeps the text its stages were compiled from: until a file's next save every compile reads it (a
// variant never built before too), from memory, the disk cache or glslang; a save of the file ends it.
TEST_F(CacheFixture, KeptSourcesStandForTheirFilesUntilTheNextSave) {
  for (const fs::path& dir : {cache(), fs::path()}) {
    SCOPED_TRACE(dir.empty() ? "memory only" : "disk cache");
    const fs::path inc = t / "inc.glsl", main = t / "a.comp";
    writeFile(inc, "#define VALUE 12345u\n");
    writeFile(main, kComputeMain);
    ShaderLibrary l({.cacheDir = dir, .printWarnings = false});
    const auto v1 = l.compile({main});
    ASSERT_TRUE(holdsWord(v1->spirv, 12345u));
    ASSERT_EQ(v1->fileHashes.size(), v1->files.size());

    writeFile(inc, "#define VALUE 67890u\n");  // the edit, in the include and the main file
    writeFile(main, std::string(kComputeMain) + "// edited\n");
    l.invalidateFiles({inc, main});
    ASSERT_TRUE(holdsWord(l.compile({main})->spirv, 67890u));

    EXPECT_TRUE(l.keepSourcesOf({v1}).empty()) << "both texts are known";
    EXPECT_EQ(l.keptSources(), (std::vector<fs::path>{main, inc}));
    EXPECT_EQ(l.compile({main})->spirv, v1->spirv);
    const auto variant = l.compile({main, std::nullopt, {{"EXTRA", "1"}}});
    EXPECT_TRUE(holdsWord(variant->spirv, 12345u)) << "a variant built after the revert is the reverted code";
    EXPECT_FALSE(holdsWord(variant->spirv, 67890u));

    writeFile(inc, "#define VALUE 55555u\n");  // the next save of the include
    l.invalidateFiles({inc});
    EXPECT_EQ(l.keptSources(), std::vector<fs::path>{main}) << "the main file was not saved again";
    EXPECT_TRUE(holdsWord(l.compile({main, std::nullopt, {{"EXTRA", "1"}}})->spirv, 55555u));
    l.invalidateFiles({main});
    EXPECT_TRUE(l.keptSources().empty());

    // A text never read (not in the last FileHashCache::kKeptTexts versions): named, not kept.
    auto unknown = std::make_shared<CompiledShader>();
    unknown->files = {inc};
    unknown->fileHashes = {42u};
    EXPECT_EQ(l.keepSourcesOf({unknown}), std::vector<fs::path>{inc});
    EXPECT_TRUE(l.keptSources().empty());
    fs::remove_all(cache());
  }
}
