// Reloader: editor save patterns, broken edits, dependency-driven rebuilds. The tests of its timing logic
// (quiet period, write and recreate graces) see real inotify events and move a manual clock instead of
// sleeping.
#include "live/reloader.h"
#include "live/watcher.h"
#include "../shader/test_util.h"

#include <fcntl.h>
#include <poll.h>
#include <sys/eventfd.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <mutex>
#include <thread>
#include <vector>

using namespace wb::shader;
using namespace wb::live;
using namespace wb::shader::test;
using namespace std::chrono_literals;

namespace {

const char* kCommon = "#define TINT vec3(1.0, 0.5, 0.25)\n";
const char* kVert = R"(#version 460
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"
layout(location = 0) out vec3 color;
void main() {
  color = TINT;
  gl_Position = vec4(float(gl_VertexIndex), 0.0, 0.0, 1.0);
}
)";
const char* kFrag = R"(#version 460
layout(location = 0) in vec3 color;
layout(location = 0) out vec4 outColor;
void main() { outColor = vec4(color, 1.0); }
)";
const char* kRgen = R"(#version 460
#extension GL_EXT_ray_tracing : require
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"
layout(set = 0, binding = 0, rgba8) uniform image2D img;
void main() { imageStore(img, ivec2(gl_LaunchIDEXT.xy), vec4(TINT, 1.0)); }
)";
const char* kRmiss = R"(#version 460
#extension GL_EXT_ray_tracing : require
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"
layout(location = 0) rayPayloadInEXT vec3 p;
void main() { p = TINT; }
)";

// A clock for the reloader that moves only when the test advances it. The worker waits on it for events and
// for advance(), never for real time to pass. settle() waits until the worker is blocked with nothing unread:
// the events of every file operation that returned before it, and every advance, have been taken into
// account.
class ManualClock : public Reloader::Clock {
 public:
  ManualClock() : wakeFd_(::eventfd(0, EFD_NONBLOCK | EFD_CLOEXEC)) {}
  ~ManualClock() override { ::close(wakeFd_); }

  std::chrono::steady_clock::time_point now() const override {
    std::lock_guard lock(mutex_);
    return now_;
  }
  void wait(std::span<pollfd> fds, int /*timeoutMs: real time, not this clock's*/) override {
    std::vector<pollfd> all(fds.begin(), fds.end());
    all.push_back({wakeFd_, POLLIN, 0});
    {
      std::lock_guard lock(mutex_);
      watched_ = all;
      blocked_ = true;
    }
    ::poll(all.data(), all.size(), -1);
    {
      std::lock_guard lock(mutex_);
      blocked_ = false;
    }
    uint64_t v;
    [[maybe_unused]] auto n = ::read(wakeFd_, &v, sizeof v);
    for (size_t i = 0; i < fds.size(); ++i) fds[i].revents = all[i].revents;
  }
  void advance(std::chrono::milliseconds d) {
    {
      std::lock_guard lock(mutex_);
      now_ += d;
    }
    const uint64_t one = 1;
    [[maybe_unused]] auto n = ::write(wakeFd_, &one, sizeof one);
  }
  // False only when the worker stays busy past the (generous) limit.
  bool settle(std::chrono::milliseconds limit = 300000ms) {
    const auto end = std::chrono::steady_clock::now() + limit;
    while (std::chrono::steady_clock::now() < end) {
      {
        std::lock_guard lock(mutex_);
        if (blocked_ && !readable(watched_)) return true;
      }
      std::this_thread::sleep_for(1ms);
    }
    return false;
  }

 private:
  static bool readable(std::vector<pollfd> fds) { return ::poll(fds.data(), fds.size(), 0) > 0; }
  const int wakeFd_;
  mutable std::mutex mutex_;
  std::chrono::steady_clock::time_point now_{};
  std::vector<pollfd> watched_;
  bool blocked_ = false;
};

struct ReloaderFixture : ::testing::Test {
  TempDir t;
  fs::path dir;
  std::unique_ptr<ShaderLibrary> lib;
  std::unique_ptr<Reloader> reloader;
  ShaderLibrary::ProgramId graphics = 0, rt = 0;

  void SetUp() override {
    dir = t / "shaders";
    writeFile(dir / "common.glsl", kCommon);
    writeFile(dir / "g.vert", kVert);
    writeFile(dir / "g.frag", kFrag);
    writeFile(dir / "rt/rt.rgen", kRgen);
    writeFile(dir / "rt/rt.rmiss", kRmiss);
    lib = std::make_unique<ShaderLibrary>(ShaderLibrary::Options{.includeRoots = {dir}});
    graphics = lib->registerProgram("graphics", {{dir / "g.vert"}, {dir / "g.frag"}});
    rt = lib->registerProgram("rt", {{dir / "rt/rt.rgen"}, {dir / "rt/rt.rmiss"}});
    lib->buildProgram(graphics);
    lib->buildProgram(rt);
    reloader = std::make_unique<Reloader>(*lib, std::vector<fs::path>{dir});
    reloader->start();
  }
  void TearDown() override { reloader->stop(); }

  // For the tests of the timing logic: the reloader restarted on a clock that moves only through pass().
  std::shared_ptr<ManualClock> clock;
  const Reloader::Timing timing;  // the production defaults the tests' steps are measured against
  void useManualClock() {
    reloader->stop();
    clock = std::make_shared<ManualClock>();
    Reloader::Timing t = timing;
    t.clock = clock;
    reloader = std::make_unique<Reloader>(*lib, std::vector<fs::path>{dir}, t);
    reloader->start();
    EXPECT_TRUE(clock->settle()) << "the worker never went idle";
  }
  // Manual clock: the worker takes in what happened so far, then `d` passes and it takes that in.
  void pass(std::chrono::milliseconds d) {
    EXPECT_TRUE(clock->settle()) << "the worker stayed busy";
    clock->advance(d);
    EXPECT_TRUE(clock->settle()) << "the worker stayed busy";
  }
  // Manual clock: the burst's quiet period passes and gives one reload; then time runs on past every grace
  // and no second one comes.
  ReloadResult expectOneReload() {
    pass(timing.quiet);
    auto r = reloader->poll();
    EXPECT_TRUE(r.has_value()) << "no reload once the burst was quiet";
    if (!r) return {};
    pass(timing.writeGrace + timing.recreateGrace);
    auto extra = reloader->poll();
    EXPECT_FALSE(extra.has_value()) << "a second reload for one save: "
                                    << (extra ? describeResult(*extra) + " after " + describeResult(*r) : "");
    return *r;
  }

  // Results are waited for with a generous cap: a busy machine makes a reload slow, never absent.
  std::optional<ReloadResult> waitResult(std::chrono::milliseconds timeout = 300000ms) {
    const auto end = std::chrono::steady_clock::now() + timeout;
    while (std::chrono::steady_clock::now() < end) {
      if (auto r = reloader->poll()) return r;
      std::this_thread::sleep_for(5ms);
    }
    return std::nullopt;
  }
  // Exactly one reload: one result, then nothing more for a while.
  ReloadResult expectOne() {
    auto r = waitResult();
    EXPECT_TRUE(r.has_value()) << "no reload";
    if (!r) return {};
    std::this_thread::sleep_for(600ms);
    auto extra = reloader->poll();
    EXPECT_FALSE(extra.has_value()) << "a second reload for one save: "
                                    << (extra ? describeResult(*extra) + " after " + describeResult(*r) : "");
    return *r;
  }
  static std::string describeResult(const ReloadResult& r) {
    std::string files;
    for (const auto& f : r.filesChanged) files += (files.empty() ? "" : ", ") + f.filename().string();
    return std::string(r.ok ? "ok" : "failed") + " reload of [" + files + "]" +
           (r.ok ? "" : ": " + r.error());
  }
  static bool has(const std::vector<std::string>& v, const fs::path& p) {
    return std::any_of(v.begin(), v.end(), [&](const std::string& s) { return s.rfind(p.string(), 0) == 0; });
  }
  static bool has(const std::vector<ShaderLibrary::ProgramId>& v, ShaderLibrary::ProgramId id) {
    return std::find(v.begin(), v.end(), id) != v.end();
  }
};

// A real edit: an unused global still changes the SPIR-V (a comment alone does not, and rebuilds nothing).
std::string edited(const char* text) {
  return std::string(text) + "float wbEdited = 1.0;\n";
}

}  // namespace

TEST_F(ReloaderFixture, WriteInPlace) {
  // Same length, no truncation: overwrite bytes of the existing file.
  std::string text = kVert;
  text.replace(text.find("0.0, 0.0, 1.0"), 13, "0.0, 0.5, 1.0");
  FILE* f = std::fopen((dir / "g.vert").c_str(), "r+");
  ASSERT_TRUE(f);
  std::fwrite(text.data(), 1, text.size(), f);
  std::fclose(f);
  auto r = expectOne();
  EXPECT_TRUE(r.ok) << r.error();
  EXPECT_EQ(r.programs, std::vector<ShaderLibrary::ProgramId>{graphics});
  EXPECT_EQ(r.stagesRecompiled, std::vector<std::string>{(dir / "g.vert").string()});
}

// An edit made as soon as start() returns is a reload of that stage however late the worker thread first runs
// (it is niced: a busy machine delays it). The worker once took its snapshot of the programs itself: an edit
// before that went into the snapshot, and its reload reported no stage recompiled (seen in `watch`, whose
// first frame keeps both cores busy on lavapipe).
TEST_F(ReloaderFixture, EditRightAfterStartIsRecompiledHoweverLateTheWorkerRuns) {
  reloader->stop();
  std::atomic<bool> busy{true};
  std::vector<std::thread> hogs;
  for (unsigned i = 0; i < 2 * std::max(1u, std::thread::hardware_concurrency()); ++i)
    hogs.emplace_back([&] {
      while (busy.load(std::memory_order_relaxed)) {
      }
    });
  reloader = std::make_unique<Reloader>(*lib, std::vector<fs::path>{dir});
  reloader->start();
  writeFile(dir / "g.vert", edited(kVert));
  busy = false;
  for (auto& h : hogs) h.join();
  auto r = expectOne();
  EXPECT_TRUE(r.ok) << r.error();
  EXPECT_EQ(r.stagesRecompiled, std::vector<std::string>{(dir / "g.vert").string()});
}

TEST_F(ReloaderFixture, TruncateThenSlowWriteIsNotCompiledHalfWay) {
  useManualClock();
  const std::string text = edited(kVert);
  const int fd = ::open((dir / "g.vert").c_str(), O_WRONLY | O_TRUNC);
  ASSERT_GE(fd, 0);
  const size_t half = text.size() / 2;
  ASSERT_EQ(::write(fd, text.data(), half), ssize_t(half));
  ASSERT_LT(timing.quiet, timing.writeGrace / 2);
  pass(timing.writeGrace / 2);  // the quiet period is over; the file is still open for writing
  EXPECT_FALSE(reloader->poll().has_value()) << "the half-written file was compiled";
  ASSERT_EQ(::write(fd, text.data() + half, text.size() - half), ssize_t(text.size() - half));
  ::close(fd);
  auto r = expectOneReload();
  EXPECT_TRUE(r.ok) << r.error();
  EXPECT_EQ(r.programs, std::vector<ShaderLibrary::ProgramId>{graphics});
}

// A writer that never closes its file (a crashed editor) holds the reload back only for the write grace.
TEST_F(ReloaderFixture, AFileLeftOpenIsCompiledOnceTheWriteGraceIsOver) {
  useManualClock();
  const std::string text = edited(kVert);
  const int fd = ::open((dir / "g.vert").c_str(), O_WRONLY | O_TRUNC);
  ASSERT_GE(fd, 0);
  ASSERT_EQ(::write(fd, text.data(), text.size()), ssize_t(text.size()));
  pass(timing.writeGrace / 2);
  EXPECT_FALSE(reloader->poll().has_value()) << "compiled within the write grace";
  pass(timing.writeGrace / 2 + timing.quiet);
  auto r = reloader->poll();
  ASSERT_TRUE(r.has_value()) << "no reload after the write grace";
  EXPECT_TRUE(r->ok) << r->error();
  EXPECT_EQ(r->programs, std::vector<ShaderLibrary::ProgramId>{graphics});
  // The close comes later: a reload of the same contents, with nothing to rebuild.
  ::close(fd);
  auto again = expectOneReload();
  EXPECT_TRUE(again.programs.empty());
  EXPECT_EQ(again.unchangedPrograms, std::vector<ShaderLibrary::ProgramId>{graphics});
}

TEST_F(ReloaderFixture, WriteTempThenRenameOver) {
  writeFile(dir / ".g.vert.swp~", edited(kVert));
  fs::rename(dir / ".g.vert.swp~", dir / "g.vert");
  auto r = expectOne();
  EXPECT_TRUE(r.ok) << r.error();
  EXPECT_EQ(r.programs, std::vector<ShaderLibrary::ProgramId>{graphics});
  EXPECT_TRUE(has(r.stagesRecompiled, dir / "g.vert"));
}

TEST_F(ReloaderFixture, DeleteThenRecreate) {
  useManualClock();
  fs::remove(dir / "common.glsl");
  ASSERT_LT(timing.quiet, timing.recreateGrace / 2);
  pass(timing.recreateGrace / 2);  // the quiet period is over; the deleted include may still come back
  EXPECT_FALSE(reloader->poll().has_value()) << "compiled without the deleted include";
  writeFile(dir / "common.glsl", "#define TINT vec3(0.0, 1.0, 0.0)\n");
  auto r = expectOneReload();
  EXPECT_TRUE(r.ok) << r.error();
  EXPECT_TRUE(has(r.programs, graphics));
  EXPECT_TRUE(has(r.programs, rt));
}

// An include deleted for longer than the recreate grace: the programs that use it fail, and recover when it
// comes back.
TEST_F(ReloaderFixture, DeleteWithoutRecreateFailsAfterTheGraceAndRecovers) {
  useManualClock();
  fs::remove(dir / "common.glsl");
  pass(timing.recreateGrace);
  auto r = reloader->poll();
  ASSERT_TRUE(r.has_value()) << "no reload after the recreate grace";
  EXPECT_FALSE(r->ok);
  EXPECT_TRUE(has(r->failedPrograms, graphics));
  EXPECT_TRUE(has(r->failedPrograms, rt));
  writeFile(dir / "common.glsl", "#define TINT vec3(0.0, 1.0, 0.0)\n");
  auto back = expectOneReload();
  EXPECT_TRUE(back.ok) << back.error();
  EXPECT_TRUE(has(back.programs, graphics));
  EXPECT_TRUE(has(back.programs, rt));
}

// A writer descheduled between creating the file and writing it (seen under load in CI): the empty new file
// is not compiled; the reload comes once, with the written contents.
TEST_F(ReloaderFixture, DeleteThenSlowRecreate) {
  useManualClock();
  fs::remove(dir / "common.glsl");
  pass(timing.recreateGrace / 5);
  const int fd = ::open((dir / "common.glsl").c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  ASSERT_GE(fd, 0);
  ASSERT_LT(timing.recreateGrace, timing.writeGrace / 2);
  pass(timing.writeGrace / 2);  // past the quiet period and the recreate grace, within the write grace
  EXPECT_FALSE(reloader->poll().has_value()) << "the empty new file was compiled";
  const std::string text = "#define TINT vec3(0.0, 0.0, 1.0)\n";
  ASSERT_EQ(::write(fd, text.data(), text.size()), ssize_t(text.size()));
  ::close(fd);
  auto r = expectOneReload();
  EXPECT_TRUE(r.ok) << r.error();
  EXPECT_TRUE(has(r.programs, graphics));
}

TEST_F(ReloaderFixture, Touch) {
  fs::last_write_time(dir / "g.frag", fs::file_time_type::clock::now());
  auto r = expectOne();
  EXPECT_TRUE(r.ok) << r.error();
  // Contents unchanged: the program is reported unchanged, with nothing to rebuild.
  EXPECT_TRUE(r.programs.empty());
  EXPECT_EQ(r.unchangedPrograms, std::vector<ShaderLibrary::ProgramId>{graphics});
  EXPECT_TRUE(r.stagesRecompiled.empty());
}

TEST_F(ReloaderFixture, UnrelatedFileDoesNothing) {
  useManualClock();
  writeFile(dir / "notes.txt", "hello");
  pass(timing.writeGrace + timing.recreateGrace);
  EXPECT_FALSE(reloader->poll().has_value());
}

TEST_F(ReloaderFixture, SharedIncludeRebuildsBothVertOnlyEditRebuildsGraphics) {
  writeFile(dir / "common.glsl", "#define TINT vec3(0.25, 0.5, 1.0)\n");
  auto r = expectOne();
  EXPECT_TRUE(r.ok) << r.error();
  EXPECT_TRUE(has(r.programs, graphics));
  EXPECT_TRUE(has(r.programs, rt));
  EXPECT_TRUE(has(r.stagesRecompiled, dir / "g.vert"));
  EXPECT_TRUE(has(r.stagesRecompiled, dir / "rt/rt.rgen"));
  EXPECT_TRUE(has(r.stagesRecompiled, dir / "rt/rt.rmiss"));
  EXPECT_FALSE(has(r.stagesRecompiled, dir / "g.frag"));
  EXPECT_EQ(r.builds.size(), 2u);

  writeFile(dir / "g.vert", edited(kVert));
  r = expectOne();
  EXPECT_EQ(r.programs, std::vector<ShaderLibrary::ProgramId>{graphics});
  EXPECT_EQ(r.stagesRecompiled, std::vector<std::string>{(dir / "g.vert").string()});
}

TEST_F(ReloaderFixture, BrokenEditReportsErrorThenFixRecovers) {
  writeFile(dir / "common.glsl", std::string(kCommon) + "const float broken = ;\n");
  auto r = expectOne();
  EXPECT_FALSE(r.ok);
  EXPECT_NE(r.error().find((dir / "common.glsl").string() + ":2: error"), std::string::npos) << r.error();
  EXPECT_TRUE(has(r.failedPrograms, graphics));
  EXPECT_TRUE(has(r.failedPrograms, rt));
  auto st = lib->fileStatuses();
  EXPECT_FALSE(st[dir / "common.glsl"].ok);

  // Fixed back to the content before the break: the same SPIR-V as the programs' pipelines in use, so both
  // are reported unchanged (nothing to rebuild).
  writeFile(dir / "common.glsl", kCommon);
  r = expectOne();
  EXPECT_TRUE(r.ok) << r.error();
  EXPECT_TRUE(has(r.unchangedPrograms, graphics));
  EXPECT_TRUE(has(r.unchangedPrograms, rt));
  EXPECT_TRUE(r.programs.empty());
  EXPECT_TRUE(lib->fileStatuses()[dir / "common.glsl"].ok);
}

TEST_F(ReloaderFixture, MissingIncludeAppearsLater) {
  writeFile(dir / "g.vert",
            std::string(kVert).replace(std::string(kVert).find("common.glsl"), 11, "later.glsl"));
  auto r = expectOne();
  EXPECT_FALSE(r.ok);
  EXPECT_NE(r.error().find("include file not found"), std::string::npos) << r.error();
  // The include that appears holds what common.glsl holds: the program compiles again, to the SPIR-V of the
  // pipeline in use (unchanged, nothing to rebuild).
  writeFile(dir / "later.glsl", kCommon);
  r = expectOne();
  EXPECT_TRUE(r.ok) << r.error();
  EXPECT_TRUE(has(r.unchangedPrograms, graphics));
}

TEST_F(ReloaderFixture, RequestReloadAll) {
  reloader->requestReloadAll();
  auto r = waitResult();
  ASSERT_TRUE(r);
  EXPECT_TRUE(r->ok);
  EXPECT_EQ(r->programs.size(), 2u);
}

TEST_F(ReloaderFixture, NewSubdirectoryIsWatched) {
  useManualClock();
  writeFile(dir / "newdir/x.glsl", kCommon);
  pass(timing.writeGrace + timing.recreateGrace);
  while (reloader->poll()) {
  }
  writeFile(dir / "g.vert",
            std::string(kVert).replace(std::string(kVert).find("common.glsl"), 11, "newdir/x.glsl"));
  auto r = expectOneReload();
  EXPECT_TRUE(r.ok) << r.error();
  writeFile(dir / "newdir/x.glsl", "#define TINT vec3(0.0)\n");
  r = expectOneReload();
  EXPECT_TRUE(r.ok) << r.error();
  EXPECT_EQ(r.programs, std::vector<ShaderLibrary::ProgramId>{graphics});
}
