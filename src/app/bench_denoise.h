// `bench --only denoise`: what the denoiser (render/denoiser.h) costs against one sample of the path tracer,
// timed on the device (GPU timestamps) on the default scene at the bench size and at 1920x1080, and how much
// sooner the Cornell box reaches relMSE 0.01 against Cycles' reference denoised than raw, at 256x256 (the
// times the converge report measures: the traces, plus the denoiser's pass where it is denoised).
#pragma once
#include <cstdint>
#include <string>

#include <nlohmann/json.hpp>

namespace wb::app {

class StepProgress;

struct DenoiseBenchOptions {
  uint32_t width = 512, height = 512;  // the bench size (the cost is measured there and at 1920x1080)
  int repeats = 3;                     // samples timed per size; independent runs of the time to relMSE
  bool quick = false;                  // 128x128 and 64x64 instead of 1920x1080 and 256x256
  std::string device;
};

int denoiseBenchSteps(const DenoiseBenchOptions& o);
// Keys: denoise_ms, denoise_share_of_sample (the bench size), the same per size under "cost", and
// denoised_vs_raw_time_to_relmse_0.01 with its raw and denoised seconds under "cornell" (absent when
// ../shared/reference has no Cycles image: "cornell" then says why). Throws std::runtime_error on failure.
nlohmann::json benchDenoise(const DenoiseBenchOptions& o, StepProgress& progress);

}  // namespace wb::app
