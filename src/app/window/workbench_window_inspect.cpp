// The workbench window's path inspector: the Inspect tab's pixel to the path tracer (the hybrid modes: to the
// hybrid renderer, which records the pixel's shadow, AO and reflection rays), the records read after each
// frame, the pixel picked by a click, and the `inspect FILE.json` script command.
#include <stdexcept>

#include "app/inspect_json.h"
#include "app/window/workbench_window.h"
#include "common/json_text.h"

namespace wb::app {

bool WorkbenchWindow::applyInspection() {
  auto& tracer = session_->pathTracer();
  std::optional<render::InspectRequest> want;
  if (state_.inspectPixel && state_.params.mode == render::RenderMode::PathTrace &&
      state_.inspectPixel->x < progressive_->targetWidth() &&
      state_.inspectPixel->y < progressive_->targetHeight()) {
    render::InspectRequest r;
    r.x = state_.inspectPixel->x;
    r.y = state_.inspectPixel->y;
    r.samples = state_.inspectSamples;
    r.ring = true;  // the latest samples stay; the running estimate sees every one
    want = r;
  }
  // The hybrid renderer of the mode shown records its rays; setting the pixel restarts nothing.
  if (auto* hybrid = activeHybrid()) {
    std::optional<glm::uvec2> pixel;
    if (state_.inspectPixel && state_.inspectPixel->x < hybrid->settings().width &&
        state_.inspectPixel->y < hybrid->settings().height)
      pixel = state_.inspectPixel;
    if (pixel != hybrid->inspectPixel()) hybrid->setInspectPixel(pixel);
  }
  if (want == tracer.inspection()) return false;
  tracer.setInspection(want);
  state_.inspectShown = -1;
  return true;
}

void WorkbenchWindow::updateInspection() {
  // The frame's traces have finished: every sample below the count is complete. The preview's samples are of
  // another resolution: none count.
  const uint32_t finished = progressive_->inPreview() ? 0 : progressive_->samples();
  inspector_.update(session_->pathTracer(), finished, progressive_->generation());
  const auto* hybrid = activeHybrid();
  inspector_.updateHybrid(hybrid && hybrid->inspectPixel() ? std::optional(hybrid->readInspection())
                                                           : std::nullopt);
}

void WorkbenchWindow::inspectClick(const Rect& image, glm::vec2 at) {
  if (!state_.inspectOnClick) return;
  if (!image.contains(at.x, at.y)) return;
  const glm::vec2 rel = (at - glm::vec2(image.x, image.y)) / glm::vec2(image.w, image.h);
  const glm::uvec2 size(progressive_->targetWidth(), progressive_->targetHeight());
  state_.inspectPixel = glm::min(glm::uvec2(rel * glm::vec2(size)), size - 1u);
  state_.inspectOpenPanel = 2;
}

void WorkbenchWindow::scriptInspect(const std::string& path) {
  if (auto* hybrid = activeHybrid()) {
    if (!hybrid->inspectPixel())
      throw std::runtime_error("inspect: no pixel is inspected (set inspect_pixel X,Y)");
    InspectContext ctx;
    ctx.x = hybrid->inspectPixel()->x;
    ctx.y = hybrid->inspectPixel()->y;
    ctx.width = hybrid->settings().width;
    ctx.height = hybrid->settings().height;
    ctx.scene = session_->scene().sourcePath.string();
    ctx.spp = hybrid->samplesAccumulated();
    const auto out = hybrid->readOutput();  // the device is idle at a script step
    const size_t i = (size_t(ctx.y) * ctx.width + ctx.x) * 4;
    if (i + 3 < out.size()) ctx.pixelValue = glm::vec4(out[i], out[i + 1], out[i + 2], 1.0f);
    writeJsonFile(path,
                  hybridInspectJson(ctx, hybrid->readInspection(), render::renderModeName(hybrid->mode())),
                  "inspect");
    return;
  }
  const auto& tracer = session_->pathTracer();
  if (!tracer.inspection())
    throw std::runtime_error("inspect: no pixel is inspected (set inspect_pixel X,Y)");
  updateInspection();
  const auto& s = tracer.settings();
  InspectContext ctx;
  ctx.x = tracer.inspection()->x;
  ctx.y = tracer.inspection()->y;
  ctx.width = s.width;
  ctx.height = s.height;
  ctx.samplesRequested = tracer.inspection()->samples;
  ctx.scene = session_->scene().sourcePath.string();
  const auto accum = tracer.readAccumulation();  // the device is idle at a script step
  const size_t i = (size_t(ctx.y) * s.width + ctx.x) * 4;
  if (i + 3 < accum.size()) ctx.pixelValue = glm::vec4(accum[i], accum[i + 1], accum[i + 2], accum[i + 3]);
  ctx.spp = tracer.samplesAccumulated();
  auto j = inspectJson(ctx, inspector_.samples());
  const auto& e = inspector_.estimate();
  j["running_estimate"] = {{"samples", e.count()},
                           {"dropped", e.dropped()},
                           {"mean", {e.mean().x, e.mean().y, e.mean().z}},
                           {"variance", {e.variance().x, e.variance().y, e.variance().z}}};
  writeJsonFile(path, j, "inspect");
}

}  // namespace wb::app
