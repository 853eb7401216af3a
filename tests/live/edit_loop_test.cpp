// live::EditLoop as `watch` and the window drive it, on the device: a broken save is over at once (nothing
// installed, the old pipeline draws on); a working one is over after the new image's first frame and its A/B
// comparison, which says the image changed; Revert puts the old pipeline back into the pass.
#include <gtest/gtest.h>

#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <thread>

#include "../render/gpu_fixture.h"
#include "common/paths.h"
#include "live/edit_loop.h"

namespace fs = std::filesystem;
using namespace std::chrono_literals;
using namespace wb;

namespace {

void replaceIn(const fs::path& file, const std::string& from, const std::string& to) {
  std::ifstream in(file);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const auto pos = text.find(from);
  ASSERT_NE(pos, std::string::npos) << file << " has no '" << from << "'";
  text.replace(pos, from.size(), to);
  std::ofstream(file, std::ios::trunc) << text;
}

class EditLoopTest : public ::testing::Test {
 protected:
  void SetUp() override {
    root_ = fs::temp_directory_path() / ("wb_edit_loop_" + std::to_string(::getpid()));
    fs::remove_all(root_);
    fs::create_directories(root_);
    fs::copy(fs::path(WB_SOURCE_DIR) / "shaders", root_ / "shaders", fs::copy_options::recursive);
    fs::copy(fs::path(WB_SOURCE_DIR) / "assets", root_ / "assets", fs::copy_options::recursive);
    ::setenv("WB_ROOT", root_.c_str(), 1);
    ASSERT_EQ(shaderDir(), root_ / "shaders") << "run this test in a process of its own (as ctest does)";
    render::SessionOptions o;
    o.settings.width = o.settings.height = 24;
    o.cacheDir = root_ / "shader_cache";
    o.quiet = true;
    session_ = wb::testing::makeSession(o);
  }
  void TearDown() override {
    if (session_) wb::testing::expectNoValidationErrors(*session_);
    session_.reset();
    fs::remove_all(root_);
  }

  // Frames as a render loop draws them until a reload is over (a cap for a busy machine, not a timing).
  std::vector<live::CompletedReload> framesUntilCompleted(live::EditLoop& loop) {
    for (auto deadline = std::chrono::steady_clock::now() + 300s;
         std::chrono::steady_clock::now() < deadline;) {
      loop.beginFrame();
      const auto begin = std::chrono::steady_clock::now();
      auto& r = session_->renderer();
      session_->context().submitAndWait([&](VkCommandBuffer cmd) { r.record(cmd); });
      r.advance();
      loop.frameFinished(begin);
      auto done = loop.takeCompleted();
      if (!done.empty()) return done;
      std::this_thread::sleep_for(5ms);
    }
    return {};
  }

  fs::path root_;
  std::unique_ptr<render::RenderSession> session_;
};

}  // namespace

TEST_F(EditLoopTest, ABrokenSaveIsOverAtOnceAndAWorkingOneAfterItsFirstFrameAndComparison) {
  live::EditLoopOptions o;
  o.ab = true;
  o.budget = {16, 16, 2, 2};
  live::EditLoop loop(*session_, o);
  loop.start();
  render::Pass& pass = *session_->pathTracer().passes().at(0);
  const auto original = pass.installed().pipeline;
  const fs::path miss = root_ / "shaders/pathtracer/miss.rmiss";
  // The miss stage of a variant the session has not built (as the inspector's or the cost view's would be).
  auto& library = session_->library();
  shader::ShaderKey variantMiss;
  for (const auto& k : library.programStages(pass.program()))
    if (k.path.filename() == "miss.rmiss") variantMiss = k;
  ASSERT_FALSE(variantMiss.path.empty());
  variantMiss.defines.push_back({"WB_TEST_VARIANT", "1"});
  const auto variantBefore = library.compile(variantMiss)->spirv;

  replaceIn(miss, "payload.radiance = envRadiance(dir) * misWeight;", "payload.radiance = broken;");
  auto broken = framesUntilCompleted(loop);
  ASSERT_EQ(broken.size(), 1u) << "no reload after a broken save";
  EXPECT_FALSE(broken[0].event.ok);
  EXPECT_NE(broken[0].event.error.find("miss.rmiss:"), std::string::npos) << broken[0].event.error;
  EXPECT_TRUE(broken[0].event.pipelinesRebuilt.empty());
  EXPECT_TRUE(broken[0].ab.empty());
  EXPECT_EQ(pass.installed().pipeline, original) << "a broken save replaced the pipeline";

  replaceIn(miss, "payload.radiance = broken;", "payload.radiance = envRadiance(dir) * misWeight * 0.5;");
  auto fixed = framesUntilCompleted(loop);
  ASSERT_EQ(fixed.size(), 1u);
  const auto& c = fixed[0];
  EXPECT_TRUE(c.event.ok) << c.event.error;
  EXPECT_EQ(c.event.pipelinesRebuilt, std::vector<std::string>{"pathtracer"});
  EXPECT_GE(c.event.editToFirstFrameMs, 0.0) << "over before its first frame";
  ASSERT_EQ(c.ab.size(), 1u) << c.abError;
  EXPECT_EQ(c.ab[0].result.image.verdict, eval::ImageVerdict::Changed);
  EXPECT_TRUE(c.ab[0].result.active);
  EXPECT_GE(c.event.abMs, 0.0) << "the comparison's cost is in the event";
  ASSERT_EQ(c.installed.size(), 1u);
  EXPECT_EQ(c.installed[0].before.pipeline, original);
  EXPECT_NE(pass.installed().pipeline, original);

  EXPECT_NE(library.compile(variantMiss)->spirv, variantBefore) << "the edit is in the variant";

  EXPECT_TRUE(loop.revert(c.installed).empty()) << "the old text is known";
  EXPECT_EQ(pass.installed().pipeline, original) << "Revert did not reinstall the old pipeline";
  EXPECT_TRUE(loop.hot().history().back().reverted);
  // What is built after the revert is the reverted code, until the file is saved again.
  EXPECT_EQ(library.compile(variantMiss)->spirv, variantBefore) << "a variant built later compiled the edit";
  replaceIn(miss, "* misWeight * 0.5;", "* misWeight * 0.25;");
  auto saved = framesUntilCompleted(loop);
  ASSERT_EQ(saved.size(), 1u);
  EXPECT_TRUE(saved[0].event.ok) << saved[0].event.error;
  EXPECT_NE(pass.installed().pipeline, original) << "the next save is built from the file";
  EXPECT_NE(library.compile(variantMiss)->spirv, variantBefore);
  EXPECT_TRUE(library.keptSources().empty());
}

// The hang limit follows the frames the loop draws, not one that compiled a pipeline: the loop's first frame
// (here a long one, as a driver's JIT at the first dispatch makes it) leaves the limit at its first-frame
// allowance (ten floors) instead of fifty times that frame; steady frames then set it. A frame that may compile
// anywhere in it (the window's, compilingFrameLimit) keeps the allowance.
TEST_F(EditLoopTest, AFrameThatCompiledDoesNotSetTheHangLimit) {
  live::EditLoop loop(*session_, {});
  const double floor = session_->context().policy().hangSeconds;
  auto seconds = [](std::chrono::nanoseconds d) { return std::chrono::duration<double>(d).count(); };
  auto finishedFrameOf = [&](double s) {
    loop.frameFinished(
        std::chrono::steady_clock::now() -
        std::chrono::duration_cast<std::chrono::steady_clock::duration>(std::chrono::duration<double>(s)));
  };
  EXPECT_NEAR(seconds(loop.frameLimit()), 10.0 * floor, 1e-6) << "before any frame";
  finishedFrameOf(40.0 * floor);
  EXPECT_NEAR(seconds(loop.frameLimit()), 10.0 * floor, 1e-6) << "after the first frame, which compiled";
  for (int i = 0; i < 3; ++i) finishedFrameOf(0.5 * floor);
  EXPECT_NEAR(seconds(loop.frameLimit()), 25.0 * floor, 1e-3 * floor) << "fifty times the steady frames";
  EXPECT_NEAR(seconds(loop.compilingFrameLimit()), 25.0 * floor, 1e-3 * floor);
  for (int i = 0; i < 9; ++i) finishedFrameOf(0.01 * floor);
  EXPECT_NEAR(seconds(loop.frameLimit()), floor, 1e-3 * floor) << "fast frames: the floor";
  // A window frame may compile the display's or the denoiser's pipelines: the first-frame allowance stays.
  EXPECT_NEAR(seconds(loop.compilingFrameLimit()), 10.0 * floor, 1e-6);
}
