// The path inspector in the window: the records of the inspected pixel read after each frame, the running
// mean and variance of its samples, the Inspect tab's section (estimate, sample choice, one row per vertex)
// and the recorded paths drawn over the image (lines projected with the camera, coloured by throughput;
// shadow rays dashed, green where they reached the light, red where blocked).
#pragma once
#include <optional>
#include <vector>

#include <glm/glm.hpp>

#include "app/window/workbench_state.h"
#include "render/path_inspector.h"
#include "render/renderer.h"

namespace wb::app {

struct Rect;

class InspectorView {
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

// Where world point p lands in a width x height trace image seen by `camera` (pixels, y down; the inverse of
// cameraRay in pixel_picker.h), or nullopt when it is behind the camera.
std::optional<glm::vec2> projectToImage(const render::CameraState& camera, uint32_t width, uint32_t height,
                                        const glm::vec3& p);

// The Inspect tab's path inspector section (the hybrid modes: their shadow, AO and reflection rays).
void drawInspectorSection(WorkbenchState& state, const InspectorView& view, bool pathTracing);
// The shown sample's path (or every kept one; the hybrid modes: the pixel's rays) over the image rectangle
// `image` of the trace image.
void drawInspectorOverlay(const WorkbenchState& state, const InspectorView& view,
                          const render::CameraState& camera, uint32_t traceWidth, uint32_t traceHeight,
                          const Rect& image, float sceneRadius);

}  // namespace wb::app
