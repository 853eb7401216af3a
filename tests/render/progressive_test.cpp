// render::ProgressiveTracer's preview levels, on the path tracer of a headless session: a change is previewed at a
// quarter of the resolution, a new pipeline (a reset from outside) first at a coarser level chosen from the
// measured rate, then at a quarter, and both then go on at full resolution as one restart.
#include <gtest/gtest.h>

#include "render/progressive.h"
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
    progressive = std::make_unique<wb::render::ProgressiveTracer>(session->context(), session->pathTracer());
    progressive->options().budgetMs = 1e6;     // every level in one frame
    progressive->options().stopAtSamples = 1;  // and one sample at full resolution
  }
  // One frame: the boundary, then this frame's strips.
  void frame() {
    progressive->beginFrame();
    session->context().submitAndWait([&](VkCommandBuffer cmd) { progressive->record(cmd); });
  }
  uint32_t traceWidth() const { return session->pathTracer().settings().width; }
  // One frame, then whether it traced `width` wide, in the preview or at full resolution.
  ::testing::AssertionResult frameAt(bool preview, uint32_t width) {
    frame();
    if (progressive->inPreview() == preview && traceWidth() == width) return ::testing::AssertionSuccess();
    return ::testing::AssertionFailure()
           << "traced " << traceWidth() << " wide " << (progressive->inPreview() ? "in" : "after")
           << " the preview; expected " << width << (preview ? " in" : " after") << " it";
  }
  // A change traced to its first full-resolution sample (the preview, then the full image).
  void firstSample() {
    progressive->invalidate();
    frame();
    frame();
  }

  std::unique_ptr<wb::render::RenderSession> session;
  std::unique_ptr<wb::render::ProgressiveTracer> progressive;
};

TEST_F(ProgressiveFixture, AChangePreviewsAtAQuarterThenTracesTheFullImage) {
  progressive->invalidate();
  EXPECT_TRUE(frameAt(true, 80u));
  EXPECT_TRUE(frameAt(false, 320u));
  EXPECT_EQ(progressive->samples(), 1u);
  EXPECT_EQ(progressive->resets(), 1u);
}

TEST_F(ProgressiveFixture, ANewPipelineIsShownCoarserFirst) {
  firstSample();
  ASSERT_EQ(progressive->samples(), 1u);
  const auto resets = progressive->resets();
  // 250 pixels per ms (the estimate before any frame was timed): a few ms are 750 pixels, which 320x240 at a
  // sixteenth (20x15) fits and at an eighth (40x30) does not.
  ASSERT_EQ(progressive->pixelsPerMs(), 250.0);
  EXPECT_EQ(progressive->coarseDivisor(), 16u);
  session->pathTracer().resetAccumulation();  // what installing a hot-reloaded pipeline does
  EXPECT_TRUE(frameAt(true, 20u));
  EXPECT_TRUE(frameAt(true, 80u));
  EXPECT_TRUE(progressive->previewValid()) << "the coarse image is kept to show under the preview";
  EXPECT_EQ(progressive->previewImage().width(), 20u);
  EXPECT_TRUE(frameAt(false, 320u));
  EXPECT_EQ(progressive->samples(), 1u);
  EXPECT_EQ(progressive->resets(), resets + 1) << "the three levels are one restart";
}

TEST_F(ProgressiveFixture, TheCoarseLevelFollowsTheMeasuredRate) {
  // Slower: the coarse level stops at the smallest image worth showing (16x16 pixels or more).
  for (int i = 0; i < 40; ++i) progressive->reportTraceTime(10, 1.0);
  EXPECT_EQ(progressive->coarseDivisor(), 16u) << "320x240 / 32 is 10x7, under 256 pixels";
  // Faster: an eighth (40x30 = 1200 pixels) traces within the few ms at 500 pixels per ms.
  for (int i = 0; i < 40; ++i) progressive->reportTraceTime(500, 1.0);
  EXPECT_NEAR(progressive->pixelsPerMs(), 500.0, 1.0);
  EXPECT_EQ(progressive->coarseDivisor(), 8u);
  // A device on which the quarter preview itself is that fast (a GPU) has no coarse level: a new pipeline is
  // previewed at a quarter, like any change.
  for (int i = 0; i < 40; ++i) progressive->reportTraceTime(100000, 1.0);
  EXPECT_EQ(progressive->coarseDivisor(), 4u);
  firstSample();
  session->pathTracer().resetAccumulation();
  EXPECT_TRUE(frameAt(true, 80u));
  EXPECT_TRUE(frameAt(false, 320u));
}

}  // namespace
