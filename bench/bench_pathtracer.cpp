// Path tracer throughput on the default scene: paths/s and rays/s (primary + bounce + shadow rays, from the
// shader's own counters) at 512x512 with the default settings. Prints one JSON object.
// Usage: bench_pathtracer [--frames N] [--warmup N] [--width W] [--height H] [--scene PATH]
// (validation is off unless WB_VALIDATION=1; the first traced frame, which compiles the pipeline, is
// warm-up.)
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <thread>
#include <vector>

#include <nlohmann/json.hpp>

#include "app/render_session.h"
#include "common/json_text.h"
#include "common/paths.h"

namespace {

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n == 0 ? 0.0 : (n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]));
}

}  // namespace

int main(int argc, char** argv) {
  uint32_t frames = 5, warmup = 1;
  wb::app::SessionOptions options;  // default scene, default settings (512x512, 8 bounces, NEE + MIS, RR)
  options.quiet = true;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string a = argv[i];
    const unsigned long v = std::strtoul(argv[i + 1], nullptr, 10);
    if (a == "--frames")
      frames = uint32_t(v);
    else if (a == "--warmup")
      warmup = uint32_t(v);
    else if (a == "--width")
      options.settings.width = uint32_t(v);
    else if (a == "--height")
      options.settings.height = uint32_t(v);
    else if (a == "--scene")
      options.scenePath = argv[i + 1];
    else {
      std::fprintf(stderr, "unknown option %s\n", a.c_str());
      return 2;
    }
  }
  using clock = std::chrono::steady_clock;
  wb::app::RenderSession session(options);
  auto& tracer = session.pathTracer();

  tracer.resetAccumulation();
  const auto w0 = clock::now();
  tracer.render(warmup);  // the first trace compiles the pipeline (or loads it from Mesa's cache)
  const double warmupSeconds = std::chrono::duration<double>(clock::now() - w0).count();

  tracer.resetAccumulation();
  tracer.resetCounters();
  std::vector<double> frameSeconds;
  for (uint32_t f = 0; f < frames; ++f) {
    const auto t0 = clock::now();
    tracer.render(1);
    frameSeconds.push_back(std::chrono::duration<double>(clock::now() - t0).count());
  }
  const wb::gpu::Counters c = tracer.readCounters();
  double total = 0;
  for (double s : frameSeconds) total += s;

  const auto& st = tracer.settings();
  nlohmann::json j;
  j["device"] = session.context().deviceName();
  j["hardware_threads"] = std::thread::hardware_concurrency();
  j["scene"] = options.scenePath.empty() ? wb::defaultScenePath().string() : options.scenePath;
  j["triangles"] = session.scene().triangleCount();
  j["width"] = st.width;
  j["height"] = st.height;
  j["max_bounces"] = st.maxBounces;
  j["setup_s"] = session.setupSeconds();
  j["warmup_frames"] = warmup;
  j["warmup_s"] = warmupSeconds;
  j["frames"] = frames;
  j["frame_s_median"] = median(frameSeconds);
  j["frame_s_min"] = frames ? *std::min_element(frameSeconds.begin(), frameSeconds.end()) : 0.0;
  j["frame_s_max"] = frames ? *std::max_element(frameSeconds.begin(), frameSeconds.end()) : 0.0;
  j["paths"] = c.pathCount;
  j["rays"] = c.rayCount;
  j["shadow_rays"] = c.shadowRayCount;
  j["rays_per_path"] = c.pathCount ? double(c.rayCount) / c.pathCount : 0.0;
  j["paths_per_s"] = total > 0 ? c.pathCount / total : 0.0;
  j["rays_per_s"] = total > 0 ? c.rayCount / total : 0.0;
  j["mrays_per_s"] = total > 0 ? c.rayCount / total / 1e6 : 0.0;
  std::printf("%s\n", wb::jsonText(j, 2).c_str());
  return 0;
}
