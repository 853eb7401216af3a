// `bench`'s roofline (pathtracer section): the bare ray rates of the path tracer's own scene and acceleration
// structure at its size (render/roofline.h), beside the path tracer's rate, in the same process, timed on the
// device with timestamps in alternating rounds. Keys: docs/bench/roofline.md.
#pragma once
#include <cstdint>

#include <nlohmann/json.hpp>

namespace wb::render {
class RenderSession;
}

namespace wb::app {

// The path tracer of `s` timed on the device: `samples` samples recorded into one submission (in launches of
// its samplesPerLaunch).
struct GpuSampleTiming {
  uint32_t samples = 0;
  double secondsPerSample = 0;  // GPU time
  double raysPerSecond = 0;     // path and shadow rays the shaders counted, over the GPU time
  double pathsPerSecond = 0;
};
GpuSampleTiming timePathTracerOnGpu(render::RenderSession& s, uint32_t samples);
// How many launches of one that takes `secondsEach` make about `targetSeconds` of device time (1 .. 256).
uint32_t launchesFor(double secondsEach, double targetSeconds);

// The roofline of the session's scene at its size: `rounds` rounds, each timing the path tracer and the three
// bare kinds one after another (launches per round chosen to take ~50 ms of device time each); medians.
nlohmann::json benchRoofline(render::RenderSession& s, int rounds);

}  // namespace wb::app
