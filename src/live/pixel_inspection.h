// The path inspector's records of the inspected pixel as a live session keeps them: read after each frame
// from the path tracer (the samples kept, and the running mean and variance over every finished sample since
// the accumulation restarted), or the hybrid renderer's record of the pixel's shadow, AO and reflection rays.
#pragma once
#include <cstdint>
#include <optional>
#include <vector>

#include <glm/glm.hpp>

#include "render/path_inspector.h"
#include "render/path_tracer.h"

namespace wb::live {

class PixelInspection {
 public:
  // Reads the records of the samples below `finished` (call when the frame that traced them has finished).
  // A new `generation` (an accumulation restart) or pixel starts the running estimate over.
  void update(const render::PathTracer& tracer, uint32_t finished, uint64_t generation);
  // The hybrid modes: the record of the last finished frame (nullopt: no pixel inspected there).
  void updateHybrid(std::optional<gpu::HybridInspectRecord> record) { hybrid_ = record; }
  void clear();
  const std::optional<gpu::HybridInspectRecord>& hybrid() const { return hybrid_; }

  std::optional<glm::uvec2> pixel() const { return pixel_; }
  const std::vector<render::InspectedSample>& samples() const { return samples_; }  // the kept ones, by index
  // Over every finished sample read since the restart (more than the kept ones).
  const render::RunningEstimate& estimate() const { return estimate_; }
  // The sample `shown` picks (-1: the latest), or nullptr when there is none.
  const render::InspectedSample* shown(int shown) const;

 private:
  std::optional<glm::uvec2> pixel_;
  uint64_t generation_ = ~0ull;
  uint32_t nextSample_ = 0;  // samples below it are in estimate_
  std::vector<render::InspectedSample> samples_;
  render::RunningEstimate estimate_;
  std::optional<gpu::HybridInspectRecord> hybrid_;
};

}  // namespace wb::live
