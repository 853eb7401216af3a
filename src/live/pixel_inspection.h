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
  // A new `generation` (an accumulation restart) or pixel starts the running estimate over. `chosen`: the
  // sample the user holds (-1: none yet); its record is kept after it leaves the kept samples, until another
  // is chosen or the pixel changes.
  void update(const render::PathTracer& tracer, uint32_t finished, uint64_t generation, int chosen = -1);
  // Holds sample `chosen` of the kept ones (-1: none).
  void hold(int chosen);
  // The hybrid modes: the record of the last finished frame (nullopt: no pixel inspected there).
  void updateHybrid(std::optional<gpu::HybridInspectRecord> record) { hybrid_ = record; }
  void clear();
  const std::optional<gpu::HybridInspectRecord>& hybrid() const { return hybrid_; }

  std::optional<glm::uvec2> pixel() const { return pixel_; }
  const std::vector<render::InspectedSample>& samples() const { return samples_; }  // the kept ones, by index
  // Over every finished sample read since the restart (more than the kept ones).
  const render::RunningEstimate& estimate() const { return estimate_; }
  // The sample `shown` picks (-1: the latest; a sample no longer kept: its held copy), or nullptr when there
  // is none.
  const render::InspectedSample* shown(int shown) const;
  // Whether the held sample is from an earlier accumulation than the kept ones (the image restarted since).
  bool heldFromEarlier() const { return held_ && heldGeneration_ != generation_; }

 private:
  std::optional<glm::uvec2> pixel_;
  uint64_t generation_ = ~0ull;
  uint32_t nextSample_ = 0;  // samples below it are in estimate_
  std::vector<render::InspectedSample> samples_;
  std::optional<render::InspectedSample> held_;  // the chosen sample's record as last seen
  uint64_t heldGeneration_ = 0;
  render::RunningEstimate estimate_;
  std::optional<gpu::HybridInspectRecord> hybrid_;
};

}  // namespace wb::live
