#include "live/pixel_inspection.h"

#include <algorithm>

namespace wb::live {

void PixelInspection::clear() {
  pixel_.reset();
  samples_.clear();
  held_.reset();
  estimate_ = {};
  nextSample_ = 0;
  generation_ = ~0ull;
}

void PixelInspection::update(const render::PathTracer& tracer, uint32_t finished, uint64_t generation,
                             int chosen) {
  const auto& request = tracer.inspection();
  if (!request) {
    clear();
    return;
  }
  const glm::uvec2 pixel(request->x, request->y);
  if (pixel_ != pixel) held_.reset();
  if (generation != generation_ || pixel_ != pixel) {
    estimate_ = {};
    nextSample_ = 0;
    generation_ = generation;
    pixel_ = pixel;
  }
  samples_ = render::inspectedSamples(tracer.readInspection(), finished);
  for (const auto& s : samples_) {
    if (s.record.sampleIndex < nextSample_) continue;
    if (s.record.accumulated) {
      estimate_.add(glm::dvec3(s.record.radiance));
    } else {
      estimate_.addDropped();
    }
  }
  nextSample_ = std::max(nextSample_, finished);
  hold(chosen);
}

void PixelInspection::hold(int chosen) {
  if (chosen < 0) {
    held_.reset();
  } else if (held_ && held_->record.sampleIndex != uint32_t(chosen)) {
    held_.reset();
  }
  for (const auto& s : samples_) {
    if (chosen >= 0 && s.record.sampleIndex == uint32_t(chosen)) {
      held_ = s;
      heldGeneration_ = generation_;
    }
  }
}

const render::InspectedSample* PixelInspection::shown(int shown) const {
  if (shown < 0) return samples_.empty() ? nullptr : &samples_.back();
  // The held copy first: a restarted accumulation numbers its samples from 0 again.
  if (held_ && held_->record.sampleIndex == uint32_t(shown)) return &*held_;
  for (const auto& s : samples_)
    if (s.record.sampleIndex == uint32_t(shown)) return &s;
  return nullptr;
}

}  // namespace wb::live
