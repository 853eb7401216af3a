// The workbench window: its statistics and parameters as JSON (`stats`, `--stats`), saved renders (F12,
// `save`).
#include "app/window/workbench_window.h"

#include <cstdio>
#include <ctime>
#include <filesystem>

#include "app/hybrid_json.h"
#include "app/parameter_json.h"
#include "app/reload_log.h"
#include "common/json_text.h"
#include "common/paths.h"

namespace wb::app {

namespace {

std::string timestampName() {
  const std::time_t t = std::time(nullptr);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y%m%d_%H%M%S", std::localtime(&t));
  return buf;
}

}  // namespace

nlohmann::json WorkbenchWindow::parametersJson() {
  const auto& s = session_->pathTracer().settings();
  const auto cam = camera_.state();
  nlohmann::json j;
  j["scene"] = session_->scene().sourcePath.string();
  j["width"] = s.width;
  j["height"] = s.height;
  j["samples"] = currentSamples();
  j["preview"] = !activeHybrid() && progressive_->inPreview();
  j["mode"] = render::renderModeName(state_.params.mode);
  if (const auto* h = activeHybrid()) {
    j["width"] = h->settings().width;
    j["height"] = h->settings().height;
    j["hybrid"] = hybridSettingsJson(*h);
  }
  // Every parameter under its own name (the schema of every JSON writer), and the older grouped keys.
  j.update(app::parametersJson(state_.params));
  j["rr"] = {{"enabled", s.russianRoulette},
             {"start", s.rrStart},
             {"min", s.rrMin},
             {"max", s.rrMax},
             {"exponent", s.rrExponent}};
  j["generic_shaders"] = s.generic;
  j["environment"] = {{"path", s.envPath},
                      {"color", {s.envColor.x, s.envColor.y, s.envColor.z}},
                      {"rotation_deg", s.envRotationDeg},
                      {"intensity", s.envIntensity}};
  const glm::vec3 eye = camera_.eye(), fwd = camera_.forward();
  j["camera"] = {{"eye", {eye.x, eye.y, eye.z}}, {"forward", {fwd.x, fwd.y, fwd.z}}, {"yfov", cam.yfov}};
  return j;
}

nlohmann::json WorkbenchWindow::statsJson() {
  nlohmann::json j;
  j["frames"] = frameCount_;
  j["trace_only_submits"] = traceOnlySubmits_;  // trace submissions between presents while converging
  j["key_presses"] = keyPressesHandled_;        // the window's keys (F5, F12, Tab, Home) acted on
  j["panel_visible"] = state_.showPanel;
  j["samples"] = currentSamples();
  j["preview"] = !activeHybrid() && progressive_->inPreview();
  j["resets"] = progressive_->resets() + hybridResets_;
  j["mode"] = render::renderModeName(session_->mode());  // the mode shown (a switch may be in preparation)
  j["mode_switching_to"] = modeSwitch_;                  // empty: none
  nlohmann::json le;
  le["reference"] = liveError_.referenceName();
  le["error"] = liveError_.error();
  le["history"] = nlohmann::json::array();
  for (const auto& p : liveError_.history()) {
    le["history"].push_back({{"samples", p.samples},
                             {"seconds", p.seconds},
                             {"rmse", p.rmse},
                             {"rel_mse", p.relMse},
                             {"estimated", p.estimated}});
  }
  j["live_error"] = le;
  j["trace_width"] = session_->pathTracer().settings().width;
  j["trace_height"] = session_->pathTracer().settings().height;
  j["target_width"] = progressive_->targetWidth();
  j["target_height"] = progressive_->targetHeight();
  j["window_width"] = swapchain_->extent().width;
  j["window_height"] = swapchain_->extent().height;
  j["present_mode"] = vk::presentModeName(swapchain_->presentMode());
  j["frame_ms"] = {
      {"last", frames_.last()},           {"mean", frames_.mean()}, {"p50", frames_.percentile(0.5f)},
      {"p95", frames_.percentile(0.95f)}, {"max", frames_.max()},   {"count", frames_.count()}};
  j["trace_budget_ms"] = state_.budgetMs;
  j["trace_gpu_ms_last"] = traceMs_;
  j["display_gpu_ms_last"] = displayMs_;
  j["pixels_per_ms"] = progressive_->pixelsPerMs();
  const double secs = std::max(traceSeconds_, 1e-6);
  j["paths_per_second"] = counters_.pathCount / secs;  // per second of GPU trace time
  // What the window delivers: paths traced since the accumulation restarted, per second of wall time.
  j["paths_traced"] = counters_.pathCount;
  const double wall = activeHybrid() ? std::chrono::duration<double>(Clock::now() - hybridReset_).count()
                                     : progressive_->secondsSinceReset();
  j["seconds_since_reset"] = wall;
  j["delivered_paths_per_second"] = wall > 0 ? counters_.pathCount / wall : 0.0;
  j["rays_per_second"] = counters_.rayCount / secs;
  j["nan_inf_dropped"] = counters_.droppedSamples;
  const std::string err = loop_->hot().currentError();
  j["shader_error"] = err;
  j["banner"] = err.empty() ? "" : "shader error (still rendering with the last good pipeline):\n" + err;
  j["mode_switches"] = nlohmann::json::array();
  for (const auto& m : modeSwitchTimer_.records()) {
    j["mode_switches"].push_back({{"to", m.to},
                                  {"prepare_ms", m.prepareMs},
                                  {"longest_frame_ms", m.longestFrameMs},
                                  {"total_ms", m.totalMs},
                                  {"frames", m.frames},
                                  {"done", m.done}});
  }
  // The last A/B comparison shown in the panel (its "ab" as in the watch log), and whether edits are
  // compared.
  j["ab"] = ab_.results.empty() ? nlohmann::json(nullptr) : abJson(ab_.results.front());
  j["ab_enabled"] = ab_.enabled;
  j["ab_ms"] = ab_.abMs;
  j["ab_edit_ms"] = ab_.editMs;
  j["ab_note"] = ab_.note;
  j["reloads"] = nlohmann::json::array();
  for (const auto& e : loop_->hot().history()) j["reloads"].push_back(reloadEventJson(e));
  j["shader_files"] = nlohmann::json::array();
  for (const auto& [path, f] : session_->library().fileStatuses()) {
    j["shader_files"].push_back({{"path", path.string()}, {"ok", f.ok}, {"programs", f.programs}});
  }
  j["parameters"] = parametersJson();
  j["validation_errors"] = session_->context().validationErrors();
  return j;
}

void WorkbenchWindow::writeStats(const std::string& path) {
  writeJsonFile(path, statsJson(), "stats");
}

void WorkbenchWindow::saveRender(std::string base) {
  if (base.empty()) {
    std::filesystem::create_directories(projectRoot() / "out");
    base = (projectRoot() / "out" / ("workbench_" + timestampName())).string();
  }
  auto image = currentImage();
  eval::writePng(base + ".png", image, state_.params.display.exposure, state_.params.display.tonemap);
  eval::writeExr(base + ".exr", image);
  writeJsonFile(base + ".json", parametersJson(), "save");
  lastSaved_ = std::filesystem::path(base).filename().string() + ".png/.exr/.json";
  std::printf("workbench: saved %s.png (tonemapped), %s.exr (linear), %s.json\n", base.c_str(), base.c_str(),
              base.c_str());
  std::fflush(stdout);
}

}  // namespace wb::app
