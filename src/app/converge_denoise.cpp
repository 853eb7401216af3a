#include "app/converge_denoise.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace wb::app {
namespace {

std::string percent(const eval::PixelTestResult& t) {
  return t.runs ? fmt("%.2f%%", 100.0 * t.fraction()) : std::string("-");
}

double bias2(const Checkpoint& cp) {
  return std::max(0.0, mean(cp.mse) - cp.variance);
}

}  // namespace

DenoiseVerdict denoiseVerdict(const ConfigResult& r, double target) {
  DenoiseVerdict v;
  v.rawSeconds = timeToReach(r.checkpoints, target);
  v.denoisedSeconds = timeToReach(r.denoised, target);
  if (v.rawSeconds && v.denoisedSeconds && *v.rawSeconds > 0)
    v.timeRatio = *v.denoisedSeconds / *v.rawSeconds;
  const size_t n = std::min(r.checkpoints.size(), r.denoised.size());
  for (size_t i = 0; i < n; ++i) {
    const double raw = mean(r.checkpoints[i].relMse), den = mean(r.denoised[i].relMse);
    const double ratio = raw > 0 ? den / raw : (den > 0 ? INFINITY : 1.0);
    if (den > raw) v.neverWorse = false;
    if (i == 0 || ratio > v.worstRatio) {
      v.worstRatio = ratio;
      v.worstSpp = r.checkpoints[i].spp;
    }
  }
  if (n > 0) {
    const eval::Rgb raw = meanOfRuns(r.checkpoints[n - 1]), den = meanOfRuns(r.denoised[n - 1]);
    for (int c = 0; c < 3; ++c)
      if (raw[c] != 0)
        v.finalMeanDifference = std::max(v.finalMeanDifference, std::abs(den[c] / raw[c] - 1.0));
  }
  return v;
}

void writeDenoiseComparison(std::ostream& md, const std::vector<ConfigResult>& results) {
  for (const auto& r : results) {
    if (r.denoised.empty()) continue;
    const size_t n = std::min(r.checkpoints.size(), r.denoised.size());
    const size_t runs = r.checkpoints.back().seconds.size();
    md << "\n## Raw and denoised: " << r.name << "\n\n";
    md << "Both images are made from the same samples at every checkpoint; the denoised time adds the "
          "denoiser's (measured there, submitted and waited for). Pixel tests (with 2 runs or more): per "
          "pixel "
          "and channel a two-sided t test of the mean over the "
       << runs
       << " run(s), each pixel at level 1% (a pixel counts when a channel fails at 1%/3): *off ref* against "
          "the reference (see its noise above), *off raw* the denoised mean against the raw mean of the same "
          "samples (paired: the filter's own bias, free of the reference's noise). An unbiased image has "
          "about 1% of its pixels off; the raw image's *off ref* is that rate as this test measures it.\n\n";
    md << "| spp | raw relMSE | denoised relMSE | denoised / raw | raw bias^2 | raw variance | denoised "
          "bias^2 | "
          "denoised variance | denoised mean vs raw (%) | raw off ref | denoised off ref | denoised off raw "
          "|\n";
    md << "|---|---|---|---|---|---|---|---|---|---|---|---|\n";
    for (size_t i = 0; i < n; ++i) {
      const Checkpoint &raw = r.checkpoints[i], &den = r.denoised[i];
      const double a = mean(raw.relMse), b = mean(den.relMse);
      const eval::Rgb ma = meanOfRuns(raw), mb = meanOfRuns(den);
      std::string meanDiff;
      for (int c = 0; c < 3; ++c)
        meanDiff += (c ? " " : "") + fmt("%+.3f", ma[c] != 0 ? 100.0 * (mb[c] / ma[c] - 1.0) : 0.0);
      md << "| " << raw.spp << " | " << fmt("%.4g", a) << " | " << fmt("%.4g", b) << " | "
         << fmt("%.3f", a > 0 ? b / a : 0.0) << " | " << fmt("%.3g", bias2(raw)) << " | "
         << fmt("%.3g", raw.variance) << " | " << fmt("%.3g", bias2(den)) << " | "
         << fmt("%.3g", den.variance) << " | " << meanDiff << " | " << percent(raw.offReference) << " | "
         << percent(den.offReference) << " | " << percent(den.offRaw) << " |\n";
    }
    const DenoiseVerdict v = denoiseVerdict(r);
    auto seconds = [](const std::optional<double>& s) {
      return s ? fmt("%.3g s", *s) : std::string("not reached");
    };
    md << "\n- Time to relMSE 0.01: raw " << seconds(v.rawSeconds) << ", denoised "
       << seconds(v.denoisedSeconds) << ": `denoised_vs_raw_time_to_relmse_0.01` = "
       << (v.timeRatio ? fmt("%.3f", *v.timeRatio) : std::string("n/a")) << " (goal: at most 0.25).\n";
    md << "- Denoised relMSE at or below raw at every checkpoint: " << (v.neverWorse ? "yes" : "**no**")
       << " (the largest denoised / raw: " << fmt("%.3f", v.worstRatio) << " at " << v.worstSpp << " spp).\n";
    const Checkpoint &lastRaw = r.checkpoints[n - 1], &lastDen = r.denoised[n - 1];
    md << "- At " << lastRaw.spp << " spp: the denoised mean is within "
       << fmt("%.4f%%", 100.0 * v.finalMeanDifference)
       << " of the raw mean (goal at 4096 spp: 0.1%); pixels off the reference: raw "
       << percent(lastRaw.offReference) << ", denoised " << percent(lastDen.offReference)
       << "; denoised off raw: " << percent(lastDen.offRaw) << ".\n";
  }
}

}  // namespace wb::app
