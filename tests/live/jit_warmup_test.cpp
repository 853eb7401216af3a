// The JIT warm-up of hot reloads on a lazily compiling driver (lavapipe): the new pipeline is compiled on a
// second device into Mesa's shader disk cache, so the render device's first frame with it loads the machine
// code instead of compiling it. Observed without timings: what that first frame adds to the disk cache. A
// compile stores the pipeline's machine code there (tens of KiB); a cache load adds nothing. The render
// device makes extra ray tracing pipelines first, so the warm-up must bring its group numbering in step
// (alignGroupCounter).
#include <gtest/gtest.h>

#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <thread>

#include "common/paths.h"
#include "../render/gpu_fixture.h"
#include "live/hot_reload.h"
#include "live/jit_warmup.h"

namespace fs = std::filesystem;
using namespace std::chrono_literals;

namespace {

// The cache's size once Mesa's writer thread is done (no change for 1 s; at most 120 s on a busy machine).
uint64_t settledCacheBytes() {
  uint64_t last = wb::live::mesaShaderCacheBytes();
  auto stableSince = std::chrono::steady_clock::now();
  const auto deadline = stableSince + 120s;
  while (std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(20ms);
    const uint64_t now = wb::live::mesaShaderCacheBytes();
    if (now != last) {
      last = now;
      stableSince = std::chrono::steady_clock::now();
    } else if (std::chrono::steady_clock::now() - stableSince > 1s) {
      break;
    }
  }
  return last;
}

// Replaces the first `from` in the file by `to` (a real code change: the driver has to compile anew).
void edit(const fs::path& file, const std::string& from, const std::string& to) {
  std::ifstream in(file);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const auto pos = text.find(from);
  ASSERT_NE(pos, std::string::npos) << file << " has no '" << from << "'";
  text.replace(pos, from.size(), to);
  std::ofstream(file, std::ios::trunc) << text;
}

// A private project root (shaders to edit) and private caches, set before the first device of this process.
class JitWarmup : public ::testing::Test {
 protected:
  void SetUp() override {
    root_ = fs::temp_directory_path() / ("wb_jit_warmup_" + std::to_string(::getpid()));
    fs::remove_all(root_);
    fs::create_directories(root_);
    fs::copy(fs::path(WB_SOURCE_DIR) / "shaders", root_ / "shaders", fs::copy_options::recursive);
    fs::copy(fs::path(WB_SOURCE_DIR) / "assets", root_ / "assets", fs::copy_options::recursive);
    ::setenv("WB_ROOT", root_.c_str(), 1);
    // Mesa's cache and llvmpipe's width as the workbench sets them (vk/driver_policy.h): under the private
    // shader cache of the first session.
    ::unsetenv("MESA_SHADER_CACHE_DIR");
    ASSERT_EQ(wb::shaderDir(), root_ / "shaders") << "run this test in a process of its own (as ctest does)";
  }
  void TearDown() override { fs::remove_all(root_); }

  std::unique_ptr<wb::render::RenderSession> session(wb::render::RenderMode mode) {
    wb::render::SessionOptions o;
    o.settings.width = o.settings.height = 16;
    o.cacheDir = root_ / "shader_cache";
    o.quiet = true;
    o.mode = mode;
    return wb::testing::makeSession(o);
  }

  // Waits for the hot reload of one edit and commits it (poll() at a frame boundary, as the render loops do).
  static void reload(wb::live::HotReload& hot) {
    std::optional<wb::live::ReloadEvent> e;
    for (auto deadline = std::chrono::steady_clock::now() + 300s;  // a cap for a busy machine, not a timing
         !e && std::chrono::steady_clock::now() < deadline;)
      if (!(e = hot.poll())) std::this_thread::sleep_for(10ms);
    ASSERT_TRUE(e) << "no reload after the edit";
    ASSERT_TRUE(e->ok) << e->error;
  }

  fs::path root_;
};

}  // namespace

TEST_F(JitWarmup, TheFirstTraceAfterAWarmedReloadCompilesNothing) {
  auto s = session(wb::render::RenderMode::PathTrace);
  auto& tracer = s->pathTracer();
  if (!s->context().policy().jitWarmup)
    GTEST_SKIP() << s->context().deviceName() << " compiles at pipeline creation";
  s->render(1);  // the first pipeline, compiled at its first trace
  // Two more ray tracing pipelines on the render device: its group numbers run ahead of a new device's.
  for (int i = 0; i < 2; ++i) tracer.passes()[0]->rebuild();

  // A hot reload of the closest-hit shader through the production path: HotReload's worker builds the
  // pipeline and warms it up; poll() installs it.
  const fs::path chit = fs::canonical(root_ / "shaders/pathtracer/closesthit.rchit");
  wb::live::HotReload::WarmupStats warmup;
  {
    wb::live::HotReload hot(s->library(), {wb::shaderDir()});
    EXPECT_FALSE(hot.jitWarmup(tracer).present);
    hot.addRenderer(tracer);
    EXPECT_TRUE(hot.jitWarmup(tracer).present) << "made ahead of the first edit, not by it";
    hot.start();  // the watches are in place when start() returns
    edit(chit, "const float minCos = 1e-3;", "const float minCos = 1.5e-3;");
    reload(hot);
    hot.stop();
    warmup = hot.jitWarmup(tracer);
  }
  EXPECT_EQ(warmup.warmups, 1u);
  EXPECT_EQ(warmup.mismatches, 0u) << "the warm-up's pipeline has other group handles";
  const uint64_t beforeWarmed = settledCacheBytes();
  s->render(1);
  const uint64_t warmedTrace = settledCacheBytes() - beforeWarmed;
  const auto warmedImage = wb::testing::imageStats(s->image());

  // The same kind of edit without the warm-up (as a pipeline swapped on the render thread).
  edit(chit, "const float minCos = 1.5e-3;", "const float minCos = 2.5e-3;");
  s->library().invalidateFiles({chit});
  tracer.passes()[0]->rebuild();
  const uint64_t beforeCold = settledCacheBytes();
  s->render(1);
  const uint64_t coldTrace = settledCacheBytes() - beforeCold;

  EXPECT_GT(coldTrace, 8u * 1024u) << "without the warm-up the first trace compiles and stores the pipeline";
  EXPECT_LT(warmedTrace, coldTrace / 4)
      << "after the warm-up the first trace should load the compiled pipeline (" << warmedTrace
      << " bytes stored vs " << coldTrace << " cold)";
  EXPECT_EQ(warmedImage.nonFinite, 0u);
  EXPECT_GT(warmedImage.mean[0] + warmedImage.mean[1] + warmedImage.mean[2], 0.0)
      << "the warmed pipeline renders";
  wb::testing::expectNoValidationErrors(*s);
  EXPECT_EQ(wb::vk::Context::processValidationErrors(), 0u) << "the warm-up device too";
}

// A program that uses a resource its pass does not bind fails to build on both devices; the warm-up stays on
// and compiles the next good edit ahead.
TEST_F(JitWarmup, ABindingErrorLeavesTheWarmupOn) {
  auto s = session(wb::render::RenderMode::PathTrace);
  auto& tracer = s->pathTracer();
  if (!s->context().policy().jitWarmup)
    GTEST_SKIP() << s->context().deviceName() << " compiles at pipeline creation";
  s->render(1);
  const fs::path chit = fs::canonical(root_ / "shaders/pathtracer/closesthit.rchit");
  std::ifstream in(chit);
  const std::string good((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::string bad = good;
  bad.insert(bad.find('\n', bad.rfind("#include")) + 1,
             "layout(set = 0, binding = 30, std430) buffer WbExtra { vec4 v[]; } wbExtra;\n");
  bad.insert(bad.find('\n', bad.find("void main()")) + 1, "  if (wbExtra.v[0].x > 1e30) return;\n");
  wb::live::HotReload hot(s->library(), {wb::shaderDir()});
  hot.addRenderer(tracer);
  hot.start();
  std::ofstream(chit, std::ios::trunc) << bad;
  std::optional<wb::live::ReloadEvent> e;
  for (auto deadline = std::chrono::steady_clock::now() + 300s;  // a cap for a busy machine, not a timing
       !e && std::chrono::steady_clock::now() < deadline;)
    if (!(e = hot.poll())) std::this_thread::sleep_for(10ms);
  ASSERT_TRUE(e) << "no reload after the edit";
  EXPECT_FALSE(e->ok) << "a binding the pass does not fill was accepted";
  EXPECT_NE(e->error.find("WbExtra"), std::string::npos) << e->error;
  std::string fixed = good;  // and edited: one save, one reload
  const std::string from = "const float minCos = 1e-3;";
  ASSERT_NE(fixed.find(from), std::string::npos);
  fixed.replace(fixed.find(from), from.size(), "const float minCos = 1.5e-3;");
  std::ofstream(chit, std::ios::trunc) << fixed;
  reload(hot);
  hot.stop();
  const auto warmup = hot.jitWarmup(tracer);
  EXPECT_TRUE(warmup.enabled) << "a binding error turned the warm-up off";
  EXPECT_GE(warmup.warmups, 1u) << "the good edit after the failure was not compiled ahead";
  EXPECT_EQ(warmup.mismatches, 0u);
}

TEST_F(JitWarmup, AHybridShadowShaderEditIsCompiledAhead) {
  auto s = session(wb::render::RenderMode::Reflections);
  auto* hybrid = s->hybrid();
  ASSERT_NE(hybrid, nullptr);
  if (!s->context().policy().jitWarmup)
    GTEST_SKIP() << s->context().deviceName() << " compiles at pipeline creation";
  s->render(1);  // every pass compiled at its first use (the path tracer's pipeline exists too: more groups)

  const fs::path rgen = fs::canonical(root_ / "shaders/hybrid/shadow_ao.rgen");
  const std::string original = "const float phi = 2.0 * kPi * u.y;";
  wb::live::HotReload::WarmupStats warmup;
  {
    wb::live::HotReload hot(s->library(), {wb::shaderDir()});
    EXPECT_FALSE(hot.jitWarmup(*hybrid).present);
    hot.addRenderer(*hybrid);
    EXPECT_TRUE(hot.jitWarmup(*hybrid).present) << "made ahead of the first edit, not by it";
    hot.start();  // the watches are in place when start() returns
    edit(rgen, original, "const float phi = 2.0 * kPi * u.y * 0.9999;");
    reload(hot);
    hot.stop();
    warmup = hot.jitWarmup(*hybrid);
  }
  EXPECT_EQ(warmup.warmups, 1u);
  EXPECT_EQ(warmup.mismatches, 0u);
  const uint64_t beforeWarmed = settledCacheBytes();
  s->render(1);
  const uint64_t warmedFrame = settledCacheBytes() - beforeWarmed;

  edit(rgen, "u.y * 0.9999;", "u.y * 0.9998;");
  s->library().invalidateFiles({rgen});
  hybrid->pass(wb::render::HybridPass::ShadowAo).rebuild();
  const uint64_t beforeCold = settledCacheBytes();
  s->render(1);
  const uint64_t coldFrame = settledCacheBytes() - beforeCold;

  EXPECT_GT(coldFrame, 4u * 1024u) << "without the warm-up the first frame compiles and stores the pipeline";
  EXPECT_LT(warmedFrame, coldFrame / 4) << warmedFrame << " bytes stored after the warm-up vs " << coldFrame;
  wb::testing::expectNoValidationErrors(*s);
  EXPECT_EQ(wb::vk::Context::processValidationErrors(), 0u) << "the warm-up device too";
}

// A mode made off the render loop (RenderSession::prepareMode, the window's mode switch) with a hot reload
// attached has its pipelines compiled ahead on the warm-up device: its first frame loads them. Without, the
// first frame of a mode whose code is new compiles on the render device.
TEST_F(JitWarmup, AModePreparedOffTheLoopIsCompiledAhead) {
  using wb::render::RenderMode;
  auto prepareHybrid = [](wb::render::RenderSession& s) {
    const wb::render::RenderSettings settings = s.renderer().settings();
    s.prepareMode(RenderMode::Hybrid, settings);
    for (auto deadline = std::chrono::steady_clock::now() + 600s;  // a cap for a busy machine, not a timing
         !s.modeReady(RenderMode::Hybrid) && std::chrono::steady_clock::now() < deadline;)
      std::this_thread::sleep_for(10ms);
    ASSERT_TRUE(s.modeReady(RenderMode::Hybrid));
    s.setMode(RenderMode::Hybrid, settings);
  };
  uint64_t warmedFrame = 0;
  {
    auto s = session(RenderMode::PathTrace);
    if (!s->context().policy().jitWarmup)
      GTEST_SKIP() << s->context().deviceName() << " compiles at pipeline creation";
    s->render(1);
    wb::live::HotReload hot(s->library(), {wb::shaderDir()});
    s->setRendererHooks(hot.sessionHooks());
    prepareHybrid(*s);
    auto* hybrid = s->hybrid();
    ASSERT_NE(hybrid, nullptr);
    const auto warmup = hot.jitWarmup(*hybrid);
    EXPECT_EQ(warmup.warmups, hybrid->passes().size()) << "every pipeline of the mode compiled ahead";
    EXPECT_EQ(warmup.mismatches, 0u);
    const uint64_t before = settledCacheBytes();
    s->render(1);
    warmedFrame = settledCacheBytes() - before;
    wb::testing::expectNoValidationErrors(*s);
    s->setRendererHooks({});
  }
  // New shadow/AO code, and a mode made without a hot reload attached.
  edit(root_ / "shaders/hybrid/shadow_ao.rgen", "const float phi = 2.0 * kPi * u.y;",
       "const float phi = 2.0 * kPi * u.y * 0.9999;");
  auto s = session(RenderMode::PathTrace);
  s->render(1);
  prepareHybrid(*s);
  const uint64_t before = settledCacheBytes();
  s->render(1);
  const uint64_t coldFrame = settledCacheBytes() - before;
  EXPECT_GT(coldFrame, 4u * 1024u) << "without compiling ahead the first frame compiles the new code";
  EXPECT_LT(warmedFrame, coldFrame / 4)
      << warmedFrame << " bytes stored after compiling ahead vs " << coldFrame;
  EXPECT_EQ(wb::vk::Context::processValidationErrors(), 0u) << "the warm-up device too";
}
