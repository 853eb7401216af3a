// HotReload without a GPU: a program that compiles but whose pipeline cannot be built keeps the last good one
// (nothing is committed) and is the current error until a later build succeeds.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <random>
#include <thread>

#include "render/hot_reload.h"

namespace fs = std::filesystem;
using namespace std::chrono_literals;

namespace {

void writeShader(const fs::path& p, int value) {
  std::ofstream(p, std::ios::trunc) << "#version 460\nlayout(local_size_x = 1) in;\n"
                                       "layout(set = 0, binding = 0, std430) buffer Out { uint v[]; } o;\n"
                                       "void main() { o.v[0] = "
                                    << value << "u; }\n";
}

std::optional<wb::render::ReloadEvent> waitForEvent(wb::render::HotReload& hot) {
  const auto deadline = std::chrono::steady_clock::now() + 300s;  // a cap for a busy machine, not a timing
  while (std::chrono::steady_clock::now() < deadline) {
    if (auto e = hot.poll()) return e;
    std::this_thread::sleep_for(10ms);
  }
  return std::nullopt;
}

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
  wb::render::HotReload hot(lib, {dir});
  hot.addTarget(id, {"test pipeline",
                     [&](const wb::shader::ShaderLibrary::ProgramBuild&) -> std::shared_ptr<void> {
                       if (failing) throw std::runtime_error("the driver refused it");
                       return std::make_shared<int>(1);
                     },
                     [&](std::shared_ptr<void>) { ++commits; }});
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

// How long render loops rest after a frame while a rebuild compiles: most of the CPU goes to the compile on a
// CPU device (the frames keep kCpuRenderShareWhileCompiling), nothing changes on a GPU; WB_REBUILD_YIELD
// rules.
TEST(HotReloadRest, CpuDevicesRestGpusDoNotAndTheEnvironmentOverrides) {
  const char* saved = std::getenv("WB_REBUILD_YIELD");
  const std::string keep = saved ? saved : "";
  ::unsetenv("WB_REBUILD_YIELD");
  const double share = wb::render::kCpuRenderShareWhileCompiling;
  EXPECT_NEAR(1.0 / (1.0 + wb::render::rebuildRestRatio(true)), share, 1e-12);
  EXPECT_EQ(wb::render::rebuildRestRatio(false), 0.0);
  EXPECT_NEAR(wb::render::rebuildRestRatio(true, 0.25), 3.0, 1e-12);
  ::setenv("WB_REBUILD_YIELD", "3", 1);
  EXPECT_EQ(wb::render::rebuildRestRatio(false), 3.0);
  ::setenv("WB_REBUILD_YIELD", "-2", 1);
  EXPECT_EQ(wb::render::rebuildRestRatio(true), 0.0);
  ::setenv("WB_REBUILD_YIELD", "", 1);  // empty: the default
  EXPECT_NEAR(1.0 / (1.0 + wb::render::rebuildRestRatio(true)), share, 1e-12);
  if (saved) {
    ::setenv("WB_REBUILD_YIELD", keep.c_str(), 1);
  } else {
    ::unsetenv("WB_REBUILD_YIELD");
  }
}
