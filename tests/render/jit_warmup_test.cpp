// The JIT warm-up of hot reloads on a lazily compiling driver (lavapipe): the new pipeline is compiled on a
// second device into Mesa's shader disk cache, so the render device's first trace with it loads the machine
// code instead of compiling it. Observed without timings: what that first trace adds to the disk cache. A
// compile stores the pipeline's machine code there (tens of KiB); a cache load adds nothing.
#include <gtest/gtest.h>

#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <thread>

#include "common/paths.h"
#include "gpu_fixture.h"
#include "render/hot_reload.h"
#include "render/jit_warmup.h"

namespace fs = std::filesystem;
using namespace std::chrono_literals;

namespace {

// The cache's size once Mesa's writer thread is done (no change for 300 ms).
uint64_t settledCacheBytes() {
  uint64_t last = wb::render::mesaShaderCacheBytes();
  auto stableSince = std::chrono::steady_clock::now();
  const auto deadline = stableSince + 10s;
  while (std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(20ms);
    const uint64_t now = wb::render::mesaShaderCacheBytes();
    if (now != last) {
      last = now;
      stableSince = std::chrono::steady_clock::now();
    } else if (std::chrono::steady_clock::now() - stableSince > 300ms) {
      break;
    }
  }
  return last;
}

void setMinCos(const fs::path& chit, const std::string& value) {
  std::ifstream in(chit);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::string needle = "const float minCos = ";
  const auto pos = text.find(needle);
  ASSERT_NE(pos, std::string::npos);
  text.replace(pos, text.find(';', pos) - pos, needle + value);
  std::ofstream(chit, std::ios::trunc) << text;
}

}  // namespace

TEST(JitWarmup, TheFirstTraceAfterAWarmedReloadCompilesNothing) {
  // A private project root (shaders to edit) and private caches, set before the first device of this process.
  const fs::path root = fs::temp_directory_path() / ("wb_jit_warmup_" + std::to_string(::getpid()));
  fs::remove_all(root);
  fs::create_directories(root);
  fs::copy(fs::path(WB_SOURCE_DIR) / "shaders", root / "shaders", fs::copy_options::recursive);
  fs::copy(fs::path(WB_SOURCE_DIR) / "assets", root / "assets", fs::copy_options::recursive);
  ::setenv("WB_ROOT", root.c_str(), 1);
  ::setenv("MESA_SHADER_CACHE_DIR", (root / "mesa").c_str(), 1);
  ASSERT_EQ(wb::shaderDir(), root / "shaders") << "run this test in a process of its own (as ctest does)";
  wb::app::SessionOptions o;
  o.settings.width = o.settings.height = 16;
  o.cacheDir = root / "shader_cache";
  o.quiet = true;
  auto session = wb::testing::makeSession(o);
  auto& tracer = session->pathTracer();
  if (!tracer.jitWarmupEnabled())
    GTEST_SKIP() << session->context().deviceName() << " compiles pipelines when they are created";
  session->render(1);  // the first pipeline, compiled at its first trace

  // A hot reload of the closest-hit shader through the production path: HotReload's worker prepares the
  // pipeline and warms it up; poll() commits it.
  const fs::path chit = fs::canonical(root / "shaders/pathtracer/closesthit.rchit");
  wb::render::HotReload hot(session->library(), {wb::shaderDir()});
  tracer.addHotReloadTarget(hot);
  hot.start();
  std::this_thread::sleep_for(200ms);
  setMinCos(chit, "1.5e-3");
  std::optional<wb::render::ReloadEvent> e;
  for (auto deadline = std::chrono::steady_clock::now() + 60s;
       !e && std::chrono::steady_clock::now() < deadline;)
    if (!(e = hot.poll())) std::this_thread::sleep_for(10ms);
  hot.stop();
  ASSERT_TRUE(e) << "no reload after the edit";
  ASSERT_TRUE(e->ok) << e->error;
  EXPECT_EQ(tracer.jitWarmups(), 1u);
  const uint64_t beforeWarmed = settledCacheBytes();
  session->render(1);
  const uint64_t warmedTrace = settledCacheBytes() - beforeWarmed;
  const auto warmedImage = wb::testing::imageStats(session->image());

  // The same kind of edit without the warm-up (as a pipeline swapped on the render thread).
  setMinCos(chit, "2.5e-3");
  session->library().invalidateFiles({chit});
  tracer.swapPipeline(session->library().buildProgram(tracer.program()));
  const uint64_t beforeCold = settledCacheBytes();
  session->render(1);
  const uint64_t coldTrace = settledCacheBytes() - beforeCold;

  EXPECT_GT(coldTrace, 8u * 1024u) << "without the warm-up the first trace compiles and stores the pipeline";
  EXPECT_LT(warmedTrace, coldTrace / 4)
      << "after the warm-up the first trace should load the compiled pipeline (" << warmedTrace
      << " bytes stored vs " << coldTrace << " cold)";
  EXPECT_EQ(warmedImage.nonFinite, 0u);
  EXPECT_GT(warmedImage.mean[0] + warmedImage.mean[1] + warmedImage.mean[2], 0.0)
      << "the warmed pipeline renders";
  wb::testing::expectNoValidationErrors(*session);
  EXPECT_EQ(wb::vk::Context::processValidationErrors(), 0u) << "the warm-up device too";
  session.reset();
  fs::remove_all(root);
}
