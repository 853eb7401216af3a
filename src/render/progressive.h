// Progressive tracing that keeps the window responsive when one sample of the full image takes a second (as
// on lavapipe): each frame traces horizontal strips of the image within a time budget, and right after a
// change the image is first traced at a lower preview resolution, which is then shown under the rows the
// full-resolution sample has not reached yet. A new pipeline (hot reload) starts coarser still: at the power
// of two that traces in a few milliseconds at the measured rate (none on a device where the preview is that
// fast).
#pragma once
#include <array>
#include <cstdint>

#include "render/path_tracer.h"
#include "vk/resources.h"

namespace wb::render {

struct ProgressiveOptions {
  double budgetMs = 30.0;  // tracing time per frame
  bool preview = true;     // trace at 1/previewDivisor resolution right after a change
  uint32_t previewDivisor = 4;
  uint32_t previewSamples = 1;  // preview samples before switching to full resolution
  uint32_t targetSpp = 0;       // stop at this many samples (0 = never)
  bool paused = false;
  uint32_t stopAtSamples = 0;  // end the frame's strips when this many samples are done (to read them back)
};

class ProgressiveTracer {
 public:
  ProgressiveTracer(vk::Context& ctx, PathTracer& tracer);

  ProgressiveOptions& options() { return options_; }
  // The full trace resolution (view size x resolution scale, or --size). A change restarts accumulation; the
  // accumulation of the size left is parked (parkAccumulation), and going back to that size resumes it.
  void setTargetSize(uint32_t width, uint32_t height);
  uint32_t targetWidth() const { return targetWidth_; }
  uint32_t targetHeight() const { return targetHeight_; }
  // Settings that alter the image (the size in them is ignored: this class owns it). Restarts.
  void setSettings(RenderSettings settings);
  // Something that alters the image changed (camera, materials, lights): restart, with a preview first.
  void invalidate();

  // At a frame boundary (the previous frame finished): switches between preview and full resolution, notices
  // resets from outside (a hot-reloaded pipeline). May wait for the device.
  void beginFrame();
  // Records this frame's strips into cmd; returns the pixels it traced.
  uint64_t record(VkCommandBuffer cmd);
  // The measured GPU time of the last frame's strips (refines the pixels-per-ms estimate).
  void reportTraceTime(uint64_t pixels, double ms);

  bool inPreview() const { return inPreview_; }
  bool done() const;  // target spp reached
  // Finished samples of the current accumulation (0 while a restart is pending).
  uint32_t samples() const { return pendingInvalidate_ ? 0 : tracer_.samplesAccumulated(); }
  uint32_t cursorRow() const { return cursor_; }
  uint64_t resets() const { return resets_; }          // restarts caused by changes
  uint64_t generation() const { return generation_; }  // every restart, preview -> full resolution too
  double pixelsPerMs() const { return pixelsPerMs_; }
  // The divisor of a new pipeline's first image (previewDivisor when the preview level is fast enough).
  uint32_t coarseDivisor() const;
  const vk::Image& previewImage() const { return preview_; }
  bool previewValid() const { return previewValid_; }
  // Accumulations set aside, one per slot (PathTracer::ParkSlot): Size holds the size left (setTargetSize),
  // Review the old pipeline's while an edit's comparison is pending. parkAccumulation() moves the current
  // accumulation (images, samples, the row its next sample starts at) into a slot, dropping what the slot
  // held; false, keeping nothing, when there is nothing worth keeping (a preview, no finished sample). Any
  // restart (invalidate) forgets every slot.
  using ParkSlot = PathTracer::ParkSlot;
  bool parkAccumulation(ParkSlot slot);
  // Takes a slot's accumulation back (a revert, a new pipeline that renders the same image, a size come back
  // to): tracing goes on from its samples at full resolution. False when the slot holds none of the current
  // target size (one of another size stays parked).
  bool resumeParked(ParkSlot slot);
  void dropParked(ParkSlot slot) { tracer_.dropParkedAccumulation(slot); }
  void dropParked();
  bool hasParked(ParkSlot slot) const { return tracer_.hasParkedAccumulation(slot); }
  uint32_t parkedSamples(ParkSlot slot) const { return hasParked(slot) ? parked_[size_t(slot)].samples : 0; }
  bool parkedAtTargetSize(ParkSlot slot) const;
  // Hands a slot's accumulation to another (dropping what that one held).
  void moveParked(ParkSlot from, ParkSlot to);
  // Seconds of wall time since the last restart (for the Stats panel).
  double secondsSinceReset() const;

 private:
  void resize(uint32_t width, uint32_t height);
  void restart();

  vk::Context& ctx_;
  PathTracer& tracer_;
  ProgressiveOptions options_;
  uint32_t targetWidth_ = 0, targetHeight_ = 0;
  bool inPreview_ = false;
  bool coarsePreview_ = false;  // the coarse level (coarseDivisor()), before the preview
  bool pendingInvalidate_ = false;
  bool previewValid_ = false;
  uint32_t cursor_ = 0;
  uint32_t expectedSamples_ = 0;
  uint64_t resets_ = 0;
  uint64_t generation_ = 0;
  double pixelsPerMs_ = 250.0;  // lavapipe: a 512x512 sample in about a second
  vk::Image preview_;
  double resetTime_ = 0;
  // What each slot's parked accumulation was (see parkAccumulation), by ParkSlot.
  struct Parked {
    uint32_t samples = 0, row = 0, width = 0, height = 0;
    double resetTime = 0;
  };
  std::array<Parked, 2> parked_{};
};

}  // namespace wb::render
