#include "app/bench_denoise.h"

#include <algorithm>
#include <filesystem>
#include <map>
#include <string>
#include <stdexcept>
#include <vector>

#include "app/converge_run.h"
#include "app/progress.h"
#include "common/paths.h"
#include "common/statistics.h"
#include "render/path_tracer.h"
#include "render/render_session.h"
#include "vk/context.h"
#include "vk/gpu_timer.h"

namespace wb::app {
namespace {

using nlohmann::json;
namespace fs = std::filesystem;

// One sample traced then denoised in one submission; the GPU milliseconds of each (vk::GpuTimer scopes).
std::pair<double, double> timeSampleAndDenoise(vk::Context& ctx, vk::GpuTimer& timer,
                                               render::PathTracer& tracer) {
  ctx.submitAndWait([&](VkCommandBuffer cmd) {
    {
      vk::GpuTimer::Scope scope(&timer, cmd, "sample");
      tracer.record(cmd);
    }
    vk::GpuTimer::Scope scope(&timer, cmd, "denoise");
    tracer.recordDenoise(cmd);
  });
  tracer.advance();
  double sample = 0, denoise = 0;
  for (const auto& t : timer.collect()) (t.pass == "sample" ? sample : denoise) = t.ms;
  return {sample, denoise};
}

json denoiseCost(uint32_t w, uint32_t h, int repeats, const std::string& device) {
  render::SessionOptions o;
  o.settings.width = w;
  o.settings.height = h;
  o.settings.denoise = true;
  o.context.deviceName = device;
  o.quiet = true;
  render::RenderSession s(o);
  render::PathTracer& tracer = s.pathTracer();
  vk::GpuTimer timer(s.context(), 2);
  // Warm-up: the driver compiles the pipelines at their first dispatch.
  timeSampleAndDenoise(s.context(), timer, tracer);
  // The share is the median of each submission's own denoise / sample: the two run back to back in one
  // submission, so a change of the machine's speed between submissions (a CPU device's VM drifts by up to
  // 1.5x within a minute) moves both and not their ratio.
  std::vector<double> sampleMs, denoiseMs, shares;
  for (int r = 0; r < std::max(repeats, 1); ++r) {
    const auto [sample, denoise] = timeSampleAndDenoise(s.context(), timer, tracer);
    sampleMs.push_back(sample);
    denoiseMs.push_back(denoise);
    if (sample > 0) shares.push_back(denoise / sample);
  }
  // Each pass's part: the same accumulation denoised again with a scope per pass (their sum is a little
  // above the whole's: each scope adds its timestamps). Keys: prepare, variance, atrous (its iterations
  // summed), final, gain, scale.
  vk::GpuTimer perPass(s.context(), 16);
  std::map<std::string, std::vector<double>> passMs;
  for (int r = 0; r < std::max(repeats, 1); ++r) {
    s.context().submitAndWait([&](VkCommandBuffer cmd) { tracer.recordDenoise(cmd, ~0u, &perPass); });
    for (const auto& t : perPass.collect()) passMs[t.pass].push_back(t.ms);
  }
  json passes = json::object();
  for (const auto& [pass, ms] : passMs) passes[pass.substr(pass.find('_') + 1)] = median(ms);
  const double d = median(denoiseMs), t = median(sampleMs);
  const auto [lowest, highest] = shares.empty() ? std::pair(0.0, 0.0)
                                                : std::pair(*std::min_element(shares.begin(), shares.end()),
                                                            *std::max_element(shares.begin(), shares.end()));
  return {{"size", std::to_string(w) + "x" + std::to_string(h)},
          {"denoise_ms", d},
          {"sample_ms", t},
          {"denoise_share_of_sample", shares.empty() ? 0.0 : median(shares)},
          {"denoise_share_of_sample_range", {lowest, highest}},
          {"denoise_pass_ms", passes},
          {"iterations", tracer.denoiser()->options().iterations},
          {"device", s.context().deviceName()},
          {"driver", s.context().driverInfo()}};
}

// The Cornell box against Cycles, raw and denoised from the same samples, `runs` seeds, until both reach
// relMSE 0.01 (or 4096 spp).
json cornellTimeToRelMse(uint32_t size, int runs, const std::string& device, StepProgress& progress) {
  const fs::path dir = sharedDir() / "reference";
  const fs::path scene = dir / "cornell.gltf", exr = dir / "cornell_cycles.exr";
  if (!fs::exists(scene) || !fs::exists(exr))
    return {{"skipped", "no " + exr.string() + " (set WB_SHARED_DIR)"}};
  std::string description;
  const eval::ImageRGBA reference = loadReferenceFile(exr.string(), size, size, description);
  const double target = 0.01;
  std::vector<Checkpoint> raw, denoised;
  for (int run = 0; run < std::max(runs, 1); ++run) {
    progress.step("denoise: Cornell box to relMSE 0.01, run " + std::to_string(run + 1));
    render::SessionOptions o;
    o.scenePath = scene.string();
    o.settings.width = o.settings.height = size;
    o.settings.envColor = {0.0f, 0.0f, 0.0f};
    o.settings.maxBounces = 64;
    o.settings.denoise = true;
    o.settings.seed = runSeed(0, uint32_t(run));
    o.context.deviceName = device;
    o.quiet = true;
    render::RenderSession s(o);
    render::PathTracer& tracer = s.pathTracer();
    double traced = 0;
    uint32_t spp = 0;
    // The first run goes until both images reach the target (or 4096 spp), one checkpoint more for the
    // interpolation; the others make the same checkpoints.
    for (size_t i = 0; run == 0 ? spp < 4096 : i < raw.size(); ++i) {
      const uint32_t next = std::max(spp + 1, spp * 2);
      traced += timedRender(s, next - spp);
      spp = next;
      if (raw.size() <= i) {
        raw.emplace_back();
        denoised.emplace_back();
      }
      raw[i].spp = denoised[i].spp = spp;
      addMeasurement(raw[i], tracer.readEstimate(), reference, traced);
      const double denoiseSeconds = tracer.denoise();
      addMeasurement(denoised[i], tracer.readDenoised(), reference, traced + denoiseSeconds);
      raw[i].images.clear();
      denoised[i].images.clear();
      if (run == 0 && i > 0 && raw[i - 1].relMse.back() <= target && denoised[i - 1].relMse.back() <= target)
        break;
    }
  }
  const auto rawSeconds = timeToReach(raw, target), denoisedSeconds = timeToReach(denoised, target);
  json j = {{"scene", "cornell (../shared/reference), Cycles reference " + description},
            {"size", std::to_string(size) + "x" + std::to_string(size)},
            {"runs", runs}};
  j["raw_seconds"] = rawSeconds ? json(*rawSeconds) : json(nullptr);
  j["denoised_seconds"] = denoisedSeconds ? json(*denoisedSeconds) : json(nullptr);
  j["denoised_vs_raw_time_to_relmse_0.01"] =
      rawSeconds && denoisedSeconds && *rawSeconds > 0 ? json(*denoisedSeconds / *rawSeconds) : json(nullptr);
  return j;
}

}  // namespace

int denoiseBenchSteps(const DenoiseBenchOptions& o) {
  return 2 + std::max(o.repeats, 1);
}

json benchDenoise(const DenoiseBenchOptions& o, StepProgress& progress) {
  json j;
  json cost = json::array();
  const uint32_t bigW = o.quick ? 128 : 1920, bigH = o.quick ? 128 : 1080;
  progress.step("denoise: cost at " + std::to_string(o.width) + "x" + std::to_string(o.height));
  cost.push_back(denoiseCost(o.width, o.height, o.repeats, o.device));
  progress.step("denoise: cost at " + std::to_string(bigW) + "x" + std::to_string(bigH));
  cost.push_back(denoiseCost(bigW, bigH, o.repeats, o.device));
  j["cost"] = cost;
  j["denoise_ms"] = cost[0]["denoise_ms"];
  j["denoise_share_of_sample"] = cost[0]["denoise_share_of_sample"];
  j["cornell"] = cornellTimeToRelMse(o.quick ? 64 : 256, o.repeats, o.device, progress);
  if (j["cornell"].contains("denoised_vs_raw_time_to_relmse_0.01"))
    j["denoised_vs_raw_time_to_relmse_0.01"] = j["cornell"]["denoised_vs_raw_time_to_relmse_0.01"];
  return j;
}

}  // namespace wb::app
