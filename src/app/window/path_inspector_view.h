// The path inspector in the window: the Inspect tab's section (the running estimate, the sample choice, one
// row per vertex of the pixel's records that the session reads, live/pixel_inspection.h) and the recorded
// paths drawn over the image (lines projected with the camera, coloured by throughput; shadow rays dashed,
// green where they reached the light, red where blocked).
#pragma once
#include <optional>
#include <vector>

#include <glm/glm.hpp>

#include "app/window/rect.h"
#include "live/pixel_inspection.h"
#include "live/session_state.h"
#include "render/renderer.h"

namespace wb::app {

// Where world point p lands in a width x height trace image seen by `camera` (pixels, y down; the inverse of
// cameraRay in pixel_picker.h), or nullopt when it is behind the camera.
std::optional<glm::vec2> projectToImage(const render::CameraState& camera, uint32_t width, uint32_t height,
                                        const glm::vec3& p);

// The Inspect tab's path inspector section (the hybrid modes: their shadow, AO and reflection rays).
void drawInspectorSection(live::SessionState& state, const live::PixelInspection& view, bool pathTracing);
// The shown sample's path (or every kept one; the hybrid modes: the pixel's rays) over the image rectangle
// `image` of the trace image.
void drawInspectorOverlay(const live::SessionState& state, const live::PixelInspection& view,
                          const render::CameraState& camera, uint32_t traceWidth, uint32_t traceHeight,
                          const Rect& image, float sceneRadius);

}  // namespace wb::app
