#include "live/pixel_inspection.h"

#include <algorithm>

namespace wb::live {

void PixelInspection::clear() {
  pixel_.reset();
  samples_.clear();
  estimate_ = {};
  nextSample_ = 0;
  generation_ = ~0ull;
}

void PixelInspection::update(const render::PathTracer& tracer, uint32_t finished, uint64_t generation) {
  const auto& request = tracer.inspection();
  if (!request) {
    clear();
    return;
  }
  const glm::uvec2 pixel(request->x, request->y);
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
}

const render::InspectedSample* PixelInspection::shown(int shown) const {
  if (samples_.empty()) return nullptr;
  if (shown < 0) return &samples_.back();
  for (const auto& s : samples_)
    if (s.record.sampleIndex == uint32_t(shown)) return &s;
  return nullptr;
}

}  // namespace wb::live
