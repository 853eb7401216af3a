#include "render/progressive.h"

#include <algorithm>
#include <chrono>

namespace wb::render {
namespace {

double nowSeconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

vk::Image makePreviewImage(vk::Context& ctx, uint32_t w, uint32_t h) {
  vk::Image img(
      ctx, w, h, VK_FORMAT_R32G32B32A32_SFLOAT,
      VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT);
  ctx.submitAndWait([&](VkCommandBuffer cmd) {
    vk::transition(cmd, img.handle(), VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_GENERAL);
    VkClearColorValue zero{};
    VkImageSubresourceRange range{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
    vkCmdClearColorImage(cmd, img.handle(), VK_IMAGE_LAYOUT_GENERAL, &zero, 1, &range);
  });
  return img;
}

// A new pipeline's first image traces in about this long at the measured rate, and has at least this many
// pixels (16x16).
constexpr double kCoarseImageMs = 3.0;
constexpr double kMinCoarsePixels = 256.0;

}  // namespace

ProgressiveTracer::ProgressiveTracer(vk::Context& ctx, PathTracer& tracer) : ctx_(ctx), tracer_(tracer) {
  targetWidth_ = tracer.settings().width;
  targetHeight_ = tracer.settings().height;
  preview_ = makePreviewImage(ctx, 1, 1);
  resetTime_ = nowSeconds();
}

void ProgressiveTracer::setTargetSize(uint32_t width, uint32_t height) {
  width = std::max(width, 1u);
  height = std::max(height, 1u);
  if (width == targetWidth_ && height == targetHeight_) return;
  // The accumulation of the size left is set aside: going back to that size (Tab twice) resumes it.
  const Parked& sized = parked_[size_t(ParkSlot::Size)];
  const bool back = hasParked(ParkSlot::Size) && sized.width == width && sized.height == height;
  if (!back) parkAccumulation(ParkSlot::Size);
  targetWidth_ = width;
  targetHeight_ = height;
  previewValid_ = false;
  if (back && resumeParked(ParkSlot::Size)) return;
  if (!inPreview_) resize(width, height);
  pendingInvalidate_ = true;
}

void ProgressiveTracer::setSettings(RenderSettings settings) {
  settings.width = tracer_.settings().width;
  settings.height = tracer_.settings().height;
  tracer_.setSettings(settings);
  invalidate();
}

void ProgressiveTracer::invalidate() {
  pendingInvalidate_ = true;
  dropParked();
}

void ProgressiveTracer::dropParked() {
  dropParked(ParkSlot::Size);
  dropParked(ParkSlot::Review);
}

bool ProgressiveTracer::parkAccumulation(ParkSlot slot) {
  dropParked(slot);
  if (inPreview_ || pendingInvalidate_ || expectedSamples_ == 0 || tracer_.settings().width != targetWidth_ ||
      tracer_.settings().height != targetHeight_)
    return false;
  tracer_.parkAccumulation(slot, expectedSamples_);
  parked_[size_t(slot)] = {expectedSamples_, cursor_, targetWidth_, targetHeight_, resetTime_};
  return true;
}

bool ProgressiveTracer::parkedAtTargetSize(ParkSlot slot) const {
  const Parked& p = parked_[size_t(slot)];
  return hasParked(slot) && p.width == targetWidth_ && p.height == targetHeight_;
}

bool ProgressiveTracer::resumeParked(ParkSlot slot) {
  if (!parkedAtTargetSize(slot) || !tracer_.unparkAccumulation(slot)) return false;
  const Parked& p = parked_[size_t(slot)];
  inPreview_ = coarsePreview_ = pendingInvalidate_ = false;
  cursor_ = p.row;
  expectedSamples_ = tracer_.samplesAccumulated();
  resetTime_ = p.resetTime;
  ++generation_;
  return true;
}

void ProgressiveTracer::moveParked(ParkSlot from, ParkSlot to) {
  if (from == to) return;
  tracer_.moveParkedAccumulation(from, to);
  parked_[size_t(to)] = parked_[size_t(from)];
}

void ProgressiveTracer::resize(uint32_t width, uint32_t height) {
  if (tracer_.settings().width == width && tracer_.settings().height == height) return;
  RenderSettings s = tracer_.settings();
  s.width = width;
  s.height = height;
  tracer_.setSettings(s);
}

void ProgressiveTracer::restart() {
  tracer_.resetAccumulation();
  tracer_.resetCounters();
  cursor_ = 0;
  expectedSamples_ = 0;
  ++resets_;
  ++generation_;
  resetTime_ = nowSeconds();
}

double ProgressiveTracer::secondsSinceReset() const {
  return nowSeconds() - resetTime_;
}

void ProgressiveTracer::beginFrame() {
  // A reset from outside is a new pipeline (a hot reload, a revert): its first image comes at the coarse
  // preview resolution, the fastest frame that shows it.
  bool fromOutside = false;
  if (tracer_.samplesAccumulated() != expectedSamples_) pendingInvalidate_ = fromOutside = true;
  const uint32_t divisor = std::max(options_.previewDivisor, 1u);
  const uint32_t coarse = coarseDivisor();
  const uint32_t pw = std::max(1u, targetWidth_ / divisor), ph = std::max(1u, targetHeight_ / divisor);
  const bool previewWorthIt = options_.preview && divisor > 1 && targetWidth_ * targetHeight_ >= 4096;
  const bool coarseWorthIt = previewWorthIt && coarse > divisor;
  if (pendingInvalidate_) {
    pendingInvalidate_ = false;
    if (previewWorthIt) {
      inPreview_ = true;
      coarsePreview_ = fromOutside && coarseWorthIt;
      if (coarsePreview_) {
        resize(std::max(1u, targetWidth_ / coarse), std::max(1u, targetHeight_ / coarse));
      } else {
        resize(pw, ph);
      }
    } else {
      inPreview_ = false;
      resize(targetWidth_, targetHeight_);
    }
    restart();
    return;
  }
  if (inPreview_ && tracer_.samplesAccumulated() >= std::max(options_.previewSamples, 1u)) {
    // Keep the finished preview to show under the rows the full-resolution sample has not reached yet.
    const auto& accum = tracer_.accumulationImage();
    if (preview_.width() != accum.width() || preview_.height() != accum.height()) {
      preview_ = makePreviewImage(ctx_, accum.width(), accum.height());
    }
    ctx_.submitAndWait([&](VkCommandBuffer cmd) {
      VkImageCopy region{};
      region.srcSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
      region.dstSubresource = region.srcSubresource;
      region.extent = {accum.width(), accum.height(), 1};
      vkCmdCopyImage(cmd, accum.handle(), VK_IMAGE_LAYOUT_GENERAL, preview_.handle(), VK_IMAGE_LAYOUT_GENERAL,
                     1, &region);
    });
    previewValid_ = true;
    if (coarsePreview_) {
      coarsePreview_ = false;  // then the finer preview, shown over this one row by row
      resize(pw, ph);
    } else {
      inPreview_ = false;
      resize(targetWidth_, targetHeight_);
    }
    const double keep = resetTime_;
    restart();
    --resets_;  // the same restart, continued at the next resolution
    resetTime_ = keep;
  }
}

uint32_t ProgressiveTracer::coarseDivisor() const {
  // The preview level is fast enough already when it traces within the coarse image's time.
  const double budget = std::max(kMinCoarsePixels, pixelsPerMs_ * kCoarseImageMs);
  const uint32_t divisor = std::max(options_.previewDivisor, 1u);
  auto pixelsAt = [&](uint32_t d) { return double(targetWidth_ / d) * double(targetHeight_ / d); };
  if (pixelsAt(divisor) <= budget) return divisor;
  // Powers of two past the preview's divisor: the levels keep their sizes from one edit to the next (the
  // path tracer keeps the images of sizes used before), down to the smallest image still worth showing.
  uint32_t d = divisor * 2;
  while (pixelsAt(d) > budget && pixelsAt(d * 2) >= kMinCoarsePixels) d *= 2;
  return d;
}

bool ProgressiveTracer::done() const {
  return !inPreview_ && options_.targetSpp > 0 && tracer_.samplesAccumulated() >= options_.targetSpp;
}

uint64_t ProgressiveTracer::record(VkCommandBuffer cmd) {
  if (options_.paused || done()) return 0;
  const uint32_t w = tracer_.settings().width, h = tracer_.settings().height;
  uint64_t pixelBudget = uint64_t(std::max(options_.budgetMs, 1.0) * pixelsPerMs_);
  pixelBudget = std::max<uint64_t>(pixelBudget, w);  // at least one row
  uint64_t traced = 0;
  while (traced + w <= pixelBudget || traced == 0) {
    const uint32_t rows =
        std::min<uint32_t>(h - cursor_, std::max<uint32_t>(1u, uint32_t((pixelBudget - traced) / w)));
    tracer_.recordRegion(cmd, PixelRegion{0, cursor_, w, rows});
    traced += uint64_t(rows) * w;
    cursor_ += rows;
    if (cursor_ >= h) {
      cursor_ = 0;
      tracer_.advance();
      ++expectedSamples_;
      if (done() || (inPreview_ && tracer_.samplesAccumulated() >= options_.previewSamples)) break;
      if (options_.stopAtSamples && tracer_.samplesAccumulated() >= options_.stopAtSamples) break;
    }
  }
  return traced;
}

void ProgressiveTracer::reportTraceTime(uint64_t pixels, double ms) {
  if (pixels == 0 || ms <= 0.0) return;
  // Clamped so that one slow frame (the first trace compiles the pipeline) cannot stall the estimate.
  const double measured = std::clamp(double(pixels) / ms, pixelsPerMs_ * 0.25, pixelsPerMs_ * 4.0);
  pixelsPerMs_ = std::clamp(0.7 * pixelsPerMs_ + 0.3 * measured, 1.0, 1.0e9);
}

}  // namespace wb::render
