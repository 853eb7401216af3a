// HotReload without a GPU: a program that compiles but whose pipeline cannot be built keeps the last good one
// (nothing is committed) and is the current error until a later build succeeds.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
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
                     [&](const wb::shader::ShaderLibrary::ProgramBuild&) {
                       if (failing) throw std::runtime_error("the driver refused it");
                       return std::make_unique<wb::vk::BuiltPipeline>();
                     },
                     [&](std::unique_ptr<wb::vk::BuiltPipeline>) { ++commits; }});
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
