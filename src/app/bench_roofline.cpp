#include "app/bench_roofline.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <vector>

#include "common/statistics.h"
#include "render/render_session.h"
#include "render/roofline.h"
#include "vk/gpu_timer.h"

namespace wb::app {
namespace {

constexpr double kRoundSeconds = 0.05;  // device time of one kind's launches in a round

const render::BareRays kKinds[] = {render::BareRays::Primary, render::BareRays::Diffuse,
                                   render::BareRays::Shadow, render::BareRays::Path};

}  // namespace

uint32_t launchesFor(double secondsEach, double targetSeconds) {
  if (!(secondsEach > 0)) return 1;
  return uint32_t(std::clamp(std::round(targetSeconds / secondsEach), 1.0, 256.0));
}

GpuSampleTiming timePathTracerOnGpu(render::RenderSession& s, uint32_t samples) {
  render::Renderer& r = s.renderer();
  r.resetCounters();
  const double seconds = vk::gpuSeconds(s.context(), [&](VkCommandBuffer cmd) {
    for (uint32_t i = 0; i < samples;) i += r.recordBatch(cmd, samples - i);
  });
  const auto c = r.readCounters();
  GpuSampleTiming t;
  t.samples = samples;
  t.secondsPerSample = seconds / samples;
  t.raysPerSecond = seconds > 0 ? double(c.rayCount) / seconds : 0;
  t.pathsPerSecond = seconds > 0 ? double(c.pathCount) / seconds : 0;
  return t;
}

nlohmann::json benchRoofline(render::RenderSession& s, int rounds) {
  const auto& settings = s.renderer().settings();
  render::Roofline roofline({s.context(), s.library(), s.scene(), s.gpuScene(), s.environment()},
                            settings.width, settings.height, s.camera(), settings.maxBounces);
  vk::Context& ctx = s.context();
  const auto timeBare = [&](render::BareRays kind, uint32_t launches) {
    return vk::gpuSeconds(ctx, [&](VkCommandBuffer cmd) { roofline.record(cmd, kind, launches); }) / launches;
  };
  // Warm-up (a CPU device compiles at the first launch) and the launches per round.
  std::map<render::BareRays, uint32_t> launches;
  for (auto kind : kKinds) {
    timeBare(kind, 1);
    launches[kind] = launchesFor(timeBare(kind, 1), kRoundSeconds);
  }
  timePathTracerOnGpu(s, 1);
  const uint32_t ptSamples = launchesFor(timePathTracerOnGpu(s, 1).secondsPerSample, kRoundSeconds);
  std::map<render::BareRays, std::vector<double>> bareSeconds;
  std::vector<double> ptSeconds, ptRays, ptPaths;
  for (int round = 0; round < rounds; ++round) {
    const GpuSampleTiming pt = timePathTracerOnGpu(s, ptSamples);
    ptSeconds.push_back(pt.secondsPerSample);
    ptRays.push_back(pt.raysPerSecond);
    ptPaths.push_back(pt.pathsPerSecond);
    for (auto kind : kKinds) bareSeconds[kind].push_back(timeBare(kind, launches[kind]));
  }
  nlohmann::json j;
  std::map<render::BareRays, double> rate;
  for (auto kind : kKinds) {
    const double t = median(bareSeconds[kind]);
    rate[kind] = t > 0 ? double(roofline.raysPerLaunch(kind)) / t : 0;
    const std::string name = render::bareRaysName(kind);
    j["bare_" + name + "_rays_per_second"] = rate[kind];
    j["bare_" + name + "_seconds_per_launch"] = t;
    j["bare_" + name + "_rays_per_launch"] = roofline.raysPerLaunch(kind);
    j["bare_" + name + "_launches_per_round"] = launches[kind];
  }
  const double ptRate = median(ptRays);
  j["pathtracer_gpu_seconds_per_sample"] = median(ptSeconds);
  j["pathtracer_gpu_rays_per_second"] = ptRate;
  j["pathtracer_gpu_paths_per_second"] = median(ptPaths);
  j["pathtracer_samples_per_round"] = ptSamples;
  j["pathtracer_vs_bare_diffuse_ratio"] =
      rate[render::BareRays::Diffuse] > 0 ? ptRate / rate[render::BareRays::Diffuse] : 0.0;
  // Against bare paths of the same bounces: the share of the path tracer's time per ray that traversal of
  // its own mix of rays (incoherent after the first bounce) would take with trivial shading.
  j["pathtracer_vs_bare_path_ratio"] =
      rate[render::BareRays::Path] > 0 ? ptRate / rate[render::BareRays::Path] : 0.0;
  j["bare_path_bounces"] = settings.maxBounces;
  j["roofline_rounds"] = rounds;
  return j;
}

}  // namespace wb::app
