// ProgressiveTracer's preview levels, on the path tracer of a headless session: a change is previewed at a
// quarter of the resolution, a new pipeline (a reset from outside) first at an eighth, then at a quarter,
// and both then go on at full resolution as one restart.
#include <gtest/gtest.h>

#include "app/window/progressive.h"
#include "common/paths.h"
#include "render/render_session.h"

namespace {

struct ProgressiveFixture : ::testing::Test {
  void SetUp() override {
    wb::render::SessionOptions o;
    o.scenePath = wb::defaultScenePath().string();
    o.settings.width = 320;
    o.settings.height = 240;
    o.quiet = true;
    session = std::make_unique<wb::render::RenderSession>(o);
    progressive = std::make_unique<wb::app::ProgressiveTracer>(session->context(), session->pathTracer());
    progressive->options().budgetMs = 1e6;     // every level in one frame
    progressive->options().stopAtSamples = 1;  // and one sample at full resolution
  }
  // One frame: the boundary, then this frame's strips.
  void frame() {
    progressive->beginFrame();
    session->context().submitAndWait([&](VkCommandBuffer cmd) { progressive->record(cmd); });
  }
  uint32_t traceWidth() const { return session->pathTracer().settings().width; }

  std::unique_ptr<wb::render::RenderSession> session;
  std::unique_ptr<wb::app::ProgressiveTracer> progressive;
};

TEST_F(ProgressiveFixture, AChangePreviewsAtAQuarterThenTracesTheFullImage) {
  progressive->invalidate();
  frame();
  EXPECT_TRUE(progressive->inPreview());
  EXPECT_EQ(traceWidth(), 80u);
  frame();
  EXPECT_FALSE(progressive->inPreview());
  EXPECT_EQ(traceWidth(), 320u);
  EXPECT_EQ(progressive->samples(), 1u);
  EXPECT_EQ(progressive->resets(), 1u);
}

TEST_F(ProgressiveFixture, ANewPipelineIsShownAtAnEighthFirst) {
  progressive->invalidate();
  frame();
  frame();
  ASSERT_EQ(progressive->samples(), 1u);
  const auto resets = progressive->resets();
  session->pathTracer().resetAccumulation();  // what installing a hot-reloaded pipeline does
  frame();
  EXPECT_TRUE(progressive->inPreview());
  EXPECT_EQ(traceWidth(), 40u);
  frame();
  EXPECT_TRUE(progressive->inPreview());
  EXPECT_EQ(traceWidth(), 80u);
  EXPECT_TRUE(progressive->previewValid()) << "the coarse preview is kept to show under the finer one";
  EXPECT_EQ(progressive->previewImage().width(), 40u);
  frame();
  EXPECT_FALSE(progressive->inPreview());
  EXPECT_EQ(traceWidth(), 320u);
  EXPECT_EQ(progressive->samples(), 1u);
  EXPECT_EQ(progressive->resets(), resets + 1) << "the three levels are one restart";
}

}  // namespace
