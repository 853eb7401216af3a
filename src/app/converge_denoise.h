// converge.md's section for configurations with --denoise: raw and denoised side by side at every checkpoint
// (relMSE, the bias^2 / variance split, the denoised mean against the raw one, the pixels significantly off
// the reference and off the raw image), time to relMSE 0.01 of each and the goals of the denoiser
// (docs/reports/denoiser.md).
#pragma once
#include <optional>
#include <ostream>
#include <vector>

#include "app/converge_report.h"

namespace wb::app {

// What the goals compare, for one configuration with denoised checkpoints.
struct DenoiseVerdict {
  std::optional<double> rawSeconds, denoisedSeconds;  // to relMSE 0.01 (empty: not reached)
  std::optional<double> timeRatio;                    // denoised / raw: denoised_vs_raw_time_to_relmse_0.01
  bool neverWorse = true;                             // denoised relMSE <= raw at every checkpoint
  double worstRatio = 0;                              // the largest denoised / raw relMSE
  uint32_t worstSpp = 0;
  double finalMeanDifference =
      0;  // the largest |denoised mean / raw mean - 1| over channels, last checkpoint
};
DenoiseVerdict denoiseVerdict(const ConfigResult& r, double target = 0.01);

// Writes the section for every configuration with denoised checkpoints (nothing when there is none).
void writeDenoiseComparison(std::ostream& md, const std::vector<ConfigResult>& results);

}  // namespace wb::app
