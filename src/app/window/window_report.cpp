#include "app/window/window_report.h"

#include <cstdio>
#include <ctime>
#include <filesystem>
#include <stdexcept>

#include "app/debug_json.h"
#include "app/hybrid_json.h"
#include "app/inspect_json.h"
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

nlohmann::json parametersJson(live::LiveSession& session, const CameraController& camera) {
  const auto& state = session.state();
  nlohmann::json j;
  j["scene"] = session.render().scene().sourcePath.string();
  j["width"] = session.imageWidth();
  j["height"] = session.imageHeight();
  j["samples"] = session.samples();
  j["preview"] = session.inPreview();
  j["mode"] = render::renderModeName(state.params.mode);
  if (const auto* h = session.hybrid()) j["hybrid"] = hybridSettingsJson(*h);
  // Every parameter under its own name (the schema of every JSON writer), and the older grouped keys.
  j.update(app::parametersJson(state.params));
  const auto& s = session.render().pathTracer().settings();
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
  const glm::vec3 eye = camera.eye(), fwd = camera.forward();
  j["camera"] = {{"eye", {eye.x, eye.y, eye.z}}, {"forward", {fwd.x, fwd.y, fwd.z}}, {"yfov", camera.yfov()}};
  return j;
}

nlohmann::json sessionStatsJson(live::LiveSession& session) {
  const auto& state = session.state();
  nlohmann::json j;
  j["samples"] = session.samples();
  j["preview"] = session.inPreview();
  j["resets"] = session.resets();
  j["mode"] = render::renderModeName(session.mode());  // the mode shown (a switch may be in preparation)
  j["mode_switching_to"] = session.modeSwitch();       // empty: none
  j["pathtrace_samples_kept"] = session.pathTracerSamplesKept();  // resumed on going back to pathtrace
  const auto& error = session.liveError();
  nlohmann::json le;
  le["reference"] = error.referenceName();
  le["error"] = error.error();
  le["history"] = nlohmann::json::array();
  for (const auto& p : error.history()) {
    le["history"].push_back({{"samples", p.samples},
                             {"seconds", p.seconds},
                             {"rmse", p.rmse},
                             {"rel_mse", p.relMse},
                             {"estimated", p.estimated}});
  }
  j["live_error"] = le;
  const auto& tracer = session.render().pathTracer();
  j["trace_width"] = tracer.settings().width;
  j["trace_height"] = tracer.settings().height;
  j["target_width"] = session.traceWidth();
  j["target_height"] = session.traceHeight();
  j["trace_budget_ms"] = state.budgetMs;
  j["pixels_per_ms"] = session.progressive().pixelsPerMs();
  const auto& counters = session.counters();
  const double secs = std::max(session.gpuTraceSeconds(), 1e-6);
  j["paths_per_second"] = counters.pathCount / secs;  // per second of GPU trace time
  // What the window delivers: paths traced since the accumulation restarted, per second of wall time.
  j["paths_traced"] = counters.pathCount;
  const double wall = session.secondsSinceReset();
  j["seconds_since_reset"] = wall;
  j["delivered_paths_per_second"] = wall > 0 ? counters.pathCount / wall : 0.0;
  j["rays_per_second"] = counters.rayCount / secs;
  j["nan_inf_dropped"] = counters.droppedSamples;
  // The instruments: the last timed submission's GPU ms per pass, the cost views' summary, the asserts.
  const auto& in = session.instruments();
  j["pass_ms"] = nlohmann::json::object();
  for (const auto& t : in.passTimes()) j["pass_ms"][t.pass] = t.ms;
  if (in.denoiseMs()) j["pass_ms"]["denoise"] = *in.denoiseMs();  // its last run
  j["cost"] = in.cost() ? costJson(*in.cost()) : nlohmann::json(nullptr);
  j["asserts"] = state.asserts ? assertsJson(in.asserts(), in.labels()) : nlohmann::json(nullptr);
  const auto& hot = session.loop().hot();
  const std::string err = hot.currentError();
  j["shader_error"] = err;
  j["banner"] = err.empty() ? "" : "shader error (still rendering with the last good pipeline):\n" + err;
  j["mode_switches"] = nlohmann::json::array();
  for (const auto& m : session.modeSwitches().records()) {
    j["mode_switches"].push_back({{"to", m.to},
                                  {"prepare_ms", m.prepareMs},
                                  {"longest_frame_ms", m.longestFrameMs},
                                  {"total_ms", m.totalMs},
                                  {"frames", m.frames},
                                  {"done", m.done}});
  }
  // The last A/B comparison shown in the panel (its "ab" as in the watch log), and whether edits are
  // compared.
  const auto& ab = session.ab();
  j["ab"] = ab.results.empty() ? nlohmann::json(nullptr) : abJson(ab.results.front());
  j["ab_enabled"] = ab.enabled;
  j["ab_ms"] = ab.abMs;
  j["ab_edit_ms"] = ab.editMs;
  j["ab_note"] = ab.note;
  j["ab_open"] = ab.open;
  j["ab_pinned"] = ab.pinned;
  j["ab_decided"] = ab.decided;
  j["ab_budget"] =
      ab.results.empty()
          ? nlohmann::json(nullptr)
          : nlohmann::json{{"width", ab.plan.budget.width},   {"height", ab.plan.budget.height},
                           {"spp", ab.plan.budget.spp},       {"rounds", ab.plan.budget.rounds},
                           {"reduced", ab.plan.reduced},      {"over_allowance", ab.plan.overAllowance},
                           {"allowed_ms", ab.plan.allowedMs}, {"estimated_ms", ab.plan.estimatedMs},
                           {"summary", ab.plan.summary()}};
  // The path inspector's held sample (-1: none yet) and whether it is still among the kept ones.
  j["inspect_pixel"] = state.inspectPixel
                           ? nlohmann::json::array({state.inspectPixel->x, state.inspectPixel->y})
                           : nlohmann::json(nullptr);
  j["inspect_shown"] = state.inspectShown;
  const auto* shown = session.inspection().shown(state.inspectShown);
  bool kept = false;
  for (const auto& s : session.inspection().samples()) kept = kept || &s == shown;
  j["inspect_shown_vertices"] = shown ? nlohmann::json(shown->vertices.size()) : nlohmann::json(nullptr);
  j["inspect_shown_kept"] = kept;
  j["reloads"] = nlohmann::json::array();
  for (const auto& e : hot.history()) j["reloads"].push_back(reloadEventJson(e));
  j["shader_files"] = nlohmann::json::array();
  for (const auto& [path, f] : session.render().library().fileStatuses()) {
    j["shader_files"].push_back({{"path", path.string()}, {"ok", f.ok}, {"programs", f.programs}});
  }
  j["validation_errors"] = session.render().context().validationErrors();
  return j;
}

std::string saveRender(live::LiveSession& session, const CameraController& camera, std::string base) {
  if (base.empty()) {
    std::filesystem::create_directories(projectRoot() / "out");
    base = (projectRoot() / "out" / ("workbench_" + timestampName())).string();
  }
  const auto& display = session.state().params.display;
  auto image = session.image();
  eval::writePng(base + ".png", image, display.exposure, display.tonemap);
  eval::writeExr(base + ".exr", image);
  writeJsonFile(base + ".json", parametersJson(session, camera), "save");
  std::printf("workbench: saved %s.png (tonemapped), %s.exr (linear), %s.json\n", base.c_str(), base.c_str(),
              base.c_str());
  std::fflush(stdout);
  return std::filesystem::path(base).filename().string() + ".png/.exr/.json";
}

void writeInspection(live::LiveSession& session, const std::string& path) {
  nlohmann::json j;
  InspectContext ctx;
  ctx.scene = session.render().scene().sourcePath.string();
  if (const auto* hybrid = session.hybrid()) {
    if (!hybrid->inspectPixel())
      throw std::runtime_error("inspect: no pixel is inspected (set inspect_pixel X,Y)");
    ctx.x = hybrid->inspectPixel()->x;
    ctx.y = hybrid->inspectPixel()->y;
    ctx.width = hybrid->settings().width;
    ctx.height = hybrid->settings().height;
    ctx.spp = hybrid->samplesAccumulated();
    const auto out = hybrid->readOutput();
    const size_t i = (size_t(ctx.y) * ctx.width + ctx.x) * 4;
    if (i + 3 < out.size()) ctx.pixelValue = glm::vec4(out[i], out[i + 1], out[i + 2], 1.0f);
    j = hybridInspectJson(ctx, hybrid->readInspection(), render::renderModeName(hybrid->mode()));
  } else {
    const auto& tracer = session.render().pathTracer();
    if (!tracer.inspection())
      throw std::runtime_error("inspect: no pixel is inspected (set inspect_pixel X,Y)");
    const auto& inspection = session.inspectionNow();
    const auto& s = tracer.settings();
    ctx.x = tracer.inspection()->x;
    ctx.y = tracer.inspection()->y;
    ctx.width = s.width;
    ctx.height = s.height;
    ctx.samplesRequested = tracer.inspection()->samples;
    const auto accum = tracer.readAccumulation();
    const size_t i = (size_t(ctx.y) * s.width + ctx.x) * 4;
    if (i + 3 < accum.size()) ctx.pixelValue = glm::vec4(accum[i], accum[i + 1], accum[i + 2], accum[i + 3]);
    ctx.spp = tracer.samplesAccumulated();
    ctx.clock = tracer.clock();
    ctx.labels = tracer.debugLabels();
    j = inspectJson(ctx, inspection.samples());
    const auto& e = inspection.estimate();
    j["running_estimate"] = {{"samples", e.count()},
                             {"dropped", e.dropped()},
                             {"mean", {e.mean().x, e.mean().y, e.mean().z}},
                             {"variance", {e.variance().x, e.variance().y, e.variance().z}}};
  }
  writeJsonFile(path, j, "inspect");
}

}  // namespace wb::app
