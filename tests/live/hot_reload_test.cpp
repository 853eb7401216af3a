// HotReload without a GPU (pipelines are stand-ins): a program that compiles but whose pipeline cannot be
// built keeps the last good one and is the current error until a later build succeeds; saves that arrive
// while a build runs supersede it; a save that changes no SPIR-V rebuilds nothing.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <map>
#include <mutex>
#include <filesystem>
#include <functional>
#include <fstream>
#include <random>
#include <thread>

#include "live/hot_reload.h"

namespace fs = std::filesystem;
using namespace std::chrono_literals;

namespace {

void writeShader(const fs::path& p, int value) {
  std::ofstream(p, std::ios::trunc) << "#version 460\nlayout(local_size_x = 1) in;\n"
                                       "layout(set = 0, binding = 0, std430) buffer Out { uint v[]; } o;\n"
                                       "void main() { o.v[0] = "
                                    << value << "u; }\n";
}

std::optional<wb::live::ReloadEvent> waitForEvent(wb::live::HotReload& hot) {
  const auto deadline = std::chrono::steady_clock::now() + 300s;  // a cap for a busy machine, not a timing
  while (std::chrono::steady_clock::now() < deadline) {
    if (auto e = hot.poll()) return e;
    std::this_thread::sleep_for(10ms);
  }
  return std::nullopt;
}

// A pass without a device: `build` makes its pipelines (stand-ins), `onInstall` sees each install.
class FakePass : public wb::render::ReloadTarget {
 public:
  using Build = std::function<std::shared_ptr<wb::vk::BuiltPipeline>(const ProgramBuild&)>;
  FakePass(wb::shader::ShaderLibrary& lib, ProgramId program, Build build,
           std::function<void(const wb::vk::BuiltPipeline*)> onInstall = {})
      : program_(program), build_(std::move(build)), onInstall_(std::move(onInstall)) {
    installed_ = {program, lib.buildProgram(program), std::make_shared<wb::vk::BuiltPipeline>()};
  }
  const std::string& name() const override { return name_; }
  ProgramId program() const override { return program_; }
  wb::render::PassPipeline buildPipeline(ProgramId program, const ProgramBuild& build) const override {
    return {program, build, build_(build)};
  }
  wb::render::PassPipeline install(wb::render::PassPipeline p) override {
    if (p.program != program_) return {};
    if (onInstall_) onInstall_(p.pipeline.get());
    std::lock_guard lock(m_);
    std::swap(installed_, p);
    return p;
  }
  wb::render::PassPipeline installed() const override {
    std::lock_guard lock(m_);
    return installed_;
  }

 private:
  std::string name_ = "test pipeline";
  ProgramId program_;
  Build build_;
  std::function<void(const wb::vk::BuiltPipeline*)> onInstall_;
  mutable std::mutex m_;
  wb::render::PassPipeline installed_;
};

}  // namespace

TEST(HotReload, PipelineFailureIsTheCurrentErrorUntilABuildSucceeds) {
  std::random_device rd;
  const fs::path dir = fs::temp_directory_path() / ("wb_hot_reload_" + std::to_string(rd()));
  fs::create_directories(dir);
  const fs::path file = fs::canonical(dir) / "c.comp";
  writeShader(file, 1);
  wb::shader::ShaderLibrary lib({.includeRoots = {dir}, .cacheDir = {}, .printWarnings = false});
  const auto id = lib.registerProgram("test", {{file}});
  lib.buildProgram(id);

  std::atomic<bool> failing{true};
  std::atomic<int> commits{0};
  wb::live::HotReload hot(lib, {dir});
  FakePass pass(
      lib, id,
      [&](const wb::shader::ShaderLibrary::ProgramBuild&) {
        if (failing) throw std::runtime_error("the driver refused it");
        return std::make_shared<wb::vk::BuiltPipeline>();
      },
      [&](const wb::vk::BuiltPipeline*) { ++commits; });
  hot.addPass(pass);
  hot.start();  // the watches are in place when start() returns

  writeShader(file, 2);
  auto bad = waitForEvent(hot);
  ASSERT_TRUE(bad) << "no reload after an edit";
  EXPECT_FALSE(bad->ok);
  EXPECT_EQ(commits.load(), 0) << "a failed pipeline must not replace the last good one";
  EXPECT_NE(hot.currentError().find("pipeline creation failed"), std::string::npos) << hot.currentError();
  EXPECT_NE(hot.currentError().find("the driver refused it"), std::string::npos) << hot.currentError();

  failing = false;
  writeShader(file, 3);
  auto good = waitForEvent(hot);
  ASSERT_TRUE(good);
  EXPECT_TRUE(good->ok) << good->error;
  EXPECT_EQ(commits.load(), 1);
  EXPECT_EQ(hot.currentError(), "");
  hot.stop();
  fs::remove_all(dir);
}

namespace {

struct Fixture {
  fs::path dir, file;
  std::unique_ptr<wb::shader::ShaderLibrary> lib;
  wb::shader::ShaderLibrary::ProgramId id{};

  Fixture(const std::string& name) {
    std::random_device rd;
    dir = fs::temp_directory_path() / ("wb_hot_reload_" + name + std::to_string(rd()));
    fs::create_directories(dir);
    file = fs::canonical(dir) / "c.comp";
    writeShader(file, 1001);
    lib = std::make_unique<wb::shader::ShaderLibrary>(
        wb::shader::ShaderLibrary::Options{.includeRoots = {dir}, .cacheDir = {}, .printWarnings = false});
    id = lib->registerProgram("test", {{file}});
    lib->buildProgram(id);
  }
  ~Fixture() { fs::remove_all(dir); }
};

// The constant a build of writeShader's program stores (its SPIR-V holds it as a literal word).
bool buildHolds(const wb::shader::ShaderLibrary::ProgramBuild& b, uint32_t value) {
  const auto& spirv = b.stages.at(0)->spirv;
  return std::find(spirv.begin(), spirv.end(), value) != spirv.end();
}

template <class Pred>
bool waitUntil(Pred pred) {
  const auto deadline = std::chrono::steady_clock::now() + 300s;  // a cap for a busy machine, not a timing
  while (!pred()) {
    if (std::chrono::steady_clock::now() > deadline) return false;
    std::this_thread::sleep_for(5ms);
  }
  return true;
}

}  // namespace

TEST(HotReload, SavesDuringABuildSupersedeItAndOnlyTheNewestIsInstalled) {
  Fixture f("supersede");
  std::mutex m;
  std::condition_variable cv;
  bool firstStarted = false, release = false;
  std::vector<uint32_t> built, installed;  // the constant of each build / install
  std::map<const wb::vk::BuiltPipeline*, uint32_t> tags;
  auto valueOf = [](const wb::shader::ShaderLibrary::ProgramBuild& b) -> uint32_t {
    for (uint32_t v : {1001u, 1002u, 1003u, 1004u})
      if (buildHolds(b, v)) return v;
    return 0;
  };
  wb::live::HotReload hot(*f.lib, {f.dir});
  FakePass pass(
      *f.lib, f.id,
      [&](const wb::shader::ShaderLibrary::ProgramBuild& b) {
        std::unique_lock lock(m);
        built.push_back(valueOf(b));
        if (!firstStarted) {  // the first build blocks until the test has saved twice more
          firstStarted = true;
          cv.notify_all();
          cv.wait(lock, [&] { return release; });
        }
        auto p = std::make_shared<wb::vk::BuiltPipeline>();
        tags[p.get()] = valueOf(b);
        return p;
      },
      [&](const wb::vk::BuiltPipeline* p) {
        std::lock_guard lock(m);
        installed.push_back(tags[p]);
      });
  hot.addPass(pass);
  hot.start();
  writeShader(f.file, 1002);
  {
    std::unique_lock lock(m);
    ASSERT_TRUE(cv.wait_for(lock, 300s, [&] { return firstStarted; })) << "no build after a save";
  }
  writeShader(f.file, 1003);
  writeShader(f.file, 1004);
  // The reloader has seen the newest save once the library holds its compile.
  ASSERT_TRUE(waitUntil([&] { return buildHolds(f.lib->buildProgram(f.id), 1004); }));
  {
    std::lock_guard lock(m);
    release = true;
  }
  cv.notify_all();
  auto e = waitForEvent(hot);
  ASSERT_TRUE(e) << "no reload";
  EXPECT_TRUE(e->ok) << e->error;
  {
    // Not held past these reads: a build still running (after a failure here) takes it before hot.stop().
    std::lock_guard lock(m);
    EXPECT_EQ(installed, std::vector<uint32_t>{1004}) << "only the newest save is installed";
    EXPECT_EQ(std::count(built.begin(), built.end(), 1004u), 1) << "the newest content is built once";
    EXPECT_EQ(std::count(built.begin(), built.end(), 1003u), 0) << "a save superseded before its build is "
                                                                   "not built";
  }
  EXPECT_GE(hot.status().superseded, 1u);
  EXPECT_EQ(hot.history().size(), 1u) << "one reload for the burst of saves";
  EXPECT_FALSE(hot.poll()) << "nothing else pending";
  hot.stop();
}

// A file no program uses, written while a build runs (an editor's swap or backup file beside the shader):
// the build is not dropped for it, since no newer result comes of it.
TEST(HotReload, AnUnrelatedFileDuringABuildDoesNotDropIt) {
  Fixture f("unrelated");
  std::mutex m;
  std::condition_variable cv;
  bool started = false, release = false;
  std::atomic<int> installs{0};
  wb::live::HotReload hot(*f.lib, {f.dir});
  FakePass pass(
      *f.lib, f.id,
      [&](const wb::shader::ShaderLibrary::ProgramBuild&) {
        std::unique_lock lock(m);
        started = true;
        cv.notify_all();
        cv.wait(lock, [&] { return release; });
        return std::make_shared<wb::vk::BuiltPipeline>();
      },
      [&](const wb::vk::BuiltPipeline*) { ++installs; });
  hot.addPass(pass);
  hot.start();
  writeShader(f.file, 1002);
  {
    std::unique_lock lock(m);
    ASSERT_TRUE(cv.wait_for(lock, 300s, [&] { return started; })) << "no build after a save";
  }
  std::ofstream(f.dir / ".c.comp.swp") << "not a shader";
  {
    std::lock_guard lock(m);
    release = true;
  }
  cv.notify_all();
  auto e = waitForEvent(hot);
  ASSERT_TRUE(e) << "the build was dropped for the unrelated file and never installed";
  EXPECT_TRUE(e->ok) << e->error;
  EXPECT_EQ(installs.load(), 1);
  EXPECT_EQ(hot.status().superseded, 0u);
  hot.stop();
}

TEST(HotReload, ASaveThatChangesNoSpirvRebuildsNothing) {
  Fixture f("unchanged");
  std::atomic<int> builds{0};
  wb::live::HotReload hot(*f.lib, {f.dir});
  FakePass pass(*f.lib, f.id, [&](const wb::shader::ShaderLibrary::ProgramBuild&) {
    ++builds;
    return std::make_shared<wb::vk::BuiltPipeline>();
  });
  hot.addPass(pass);
  hot.start();
  // The same bytes again (an editor's save without changes).
  writeShader(f.file, 1001);
  auto same = waitForEvent(hot);
  ASSERT_TRUE(same) << "no reload event for a save";
  EXPECT_TRUE(same->ok) << same->error;
  EXPECT_TRUE(same->pipelinesRebuilt.empty());
  EXPECT_EQ(builds.load(), 0);
  // A comment only.
  { std::ofstream(f.file, std::ios::app) << "// a comment changes no SPIR-V\n"; }
  auto comment = waitForEvent(hot);
  ASSERT_TRUE(comment);
  EXPECT_TRUE(comment->pipelinesRebuilt.empty());
  EXPECT_EQ(builds.load(), 0);
  // A real change is built.
  writeShader(f.file, 1002);
  auto real = waitForEvent(hot);
  ASSERT_TRUE(real);
  EXPECT_EQ(real->pipelinesRebuilt, std::vector<std::string>{"test pipeline"});
  EXPECT_EQ(builds.load(), 1);
  hot.stop();
}

// Two programs of the same file, one of them without a pipeline (a variant no renderer uses now): a broken
// save is one error in the banner, and fixing it clears the error of both.
TEST(HotReload, AFixClearsTheErrorOfEveryProgramOfTheFileOnce) {
  Fixture f("variants");
  const auto unused = f.lib->registerProgram("test", {{f.file, std::nullopt, {{"VARIANT", "1"}}}});
  f.lib->buildProgram(unused);
  wb::live::HotReload hot(*f.lib, {f.dir});
  FakePass pass(*f.lib, f.id, [&](const wb::shader::ShaderLibrary::ProgramBuild&) {
    return std::make_shared<wb::vk::BuiltPipeline>();
  });
  hot.addPass(pass);
  hot.start();
  { std::ofstream(f.file, std::ios::trunc) << "#version 460\nvoid main() { broken }\n"; }
  auto bad = waitForEvent(hot);
  ASSERT_TRUE(bad);
  EXPECT_FALSE(bad->ok);
  const std::string error = hot.currentError();
  const auto first = error.find("c.comp:2");
  ASSERT_NE(first, std::string::npos) << error;
  EXPECT_EQ(error.find("c.comp:2", first + 1), std::string::npos) << "the same message twice:\n" << error;
  writeShader(f.file, 1003);
  auto fixed = waitForEvent(hot);
  ASSERT_TRUE(fixed);
  EXPECT_TRUE(fixed->ok) << fixed->error;
  EXPECT_EQ(hot.currentError(), "") << "an error of the program without a pipeline stayed";
  hot.stop();
}
