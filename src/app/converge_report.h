// `workbench converge`'s results and how they are written: per configuration and checkpoint the errors of its
// independent runs, then converge.csv, the gnuplot plot, converge.md (with time to error) and the error
// images, each file written whole or not at all (common/atomic_file.h; failures throw naming the file).
#pragma once
#include <cstdint>
#include <filesystem>
#include <functional>
#include <ostream>
#include <optional>
#include <string>
#include <vector>

#include "app/render_options.h"
#include "eval/image.h"
#include "eval/metrics.h"
#include "eval/pixel_test.h"

namespace wb::app {

struct ConvergeOptions {
  std::string reference;
  uint32_t referenceSpp = 0;
  double seconds = 10.0;
  uint32_t runs = 3;
  uint32_t maxSpp = 1u << 16;
  double targetRelMse = 0;
  std::vector<std::string> configs;
  std::string out;
  bool hardCases = false;
};

// One checkpoint of one configuration, over its independent runs.
struct Checkpoint {
  uint32_t spp = 0;
  std::vector<double> seconds;  // per run
  std::vector<double> mse, relMse;
  std::vector<eval::Rgb> mean;
  std::vector<eval::ImageRGBA> images;  // per run (kept for the run-to-run variance)
  double variance = 0;                  // mean per-pixel variance of one run, from the runs
  // With 2 runs or more: pixels whose mean over the runs is significantly off the reference, and (a denoised
  // checkpoint) off the raw image of the same samples (the filter's own bias). runs == 0: not tested.
  eval::PixelTestResult offReference, offRaw;
};

struct ConfigResult {
  std::string name;
  std::string flags;
  std::vector<Checkpoint> checkpoints;
  // A configuration with --denoise (path tracer): the denoised image of the same samples at each checkpoint
  // (its seconds include the denoiser's); `checkpoints` are then the raw images. Empty otherwise.
  std::vector<Checkpoint> denoised;
  uint64_t dropped = 0;
  eval::FireflyStats fireflies;
  double setupSeconds = 0;
};

double mean(const std::vector<double>& v);  // 0 for none
// The seconds a checkpoint took to render: with several runs, the mean of those after the first. The first
// run renders one sample per submission and waits for it (it finds the checkpoints by time), so its time also
// holds a round trip to the device per sample; the others render each checkpoint's samples in one submission,
// as `render` does. With one run, its time.
double renderSeconds(const Checkpoint& cp);
// Seconds for the report's tables: 3 significant digits below 100 s ("0.0143", "2.43"), whole seconds above
// (a GPU's milliseconds and a CPU's minutes alike).
std::string secondsText(double s);
// A file-name-safe version of a configuration name (letters, digits, - and _; others become _).
std::string safeName(const std::string& name);
// The image mean of a checkpoint, averaged over its runs.
eval::Rgb meanOfRuns(const Checkpoint& cp);
// printf-style formatting of one number.
std::string fmt(const char* format, double v);

// Seconds to reach `target` relMSE, interpolated in log-log between checkpoints; empty if never reached.
std::optional<double> timeToReach(const std::vector<Checkpoint>& checkpoints, double target);
inline std::optional<double> timeToReach(const ConfigResult& r, double target) {
  return timeToReach(r.checkpoints, target);
}
// The pixel tests of every checkpoint with 2 runs or more (before the images are dropped): off the reference
// (whose own variance is the raw runs' times spp / referenceSpp when it is a render of referenceSpp samples;
// referenceSpp 0: exact), and the denoised images off the raw ones.
void testPixels(ConfigResult& r, const eval::ImageRGBA& reference, uint32_t referenceSpp);
void writeCsv(const std::filesystem::path& path, const std::vector<ConfigResult>& results,
              const eval::Rgb& refMean);
// Writes the gnuplot script and runs gnuplot; returns an empty string or the reason the plot is missing.
std::string writePlot(const std::filesystem::path& dir, const std::vector<ConfigResult>& results,
                      const std::string& title);
// What converge.md says about how its results were made.
struct ReportSetup {
  std::string scene;  // as the user named it
  uint32_t width = 0, height = 0;
  std::string budget;  // what one run renders: "10 s per run", "checkpoints at 1, 2, 4 spp"
  uint32_t runs = 0;   // independent runs (seeds) per configuration
  std::string device;
  std::string reference;  // where the reference comes from
  eval::Rgb referenceMean{0, 0, 0};
  double targetRelMse = 0;         // the time-to-error target; 0: the median of the final relMSEs
  std::string plotNote;            // why the plot is missing; empty when it is there
  std::vector<std::string> notes;  // further lines of the set-up list
  std::string partialNote;  // non-empty: heads the report ("**Partial:** ..."): the run was interrupted
  // Sections written after the table of final errors, before the error images (converge_denoise.h's).
  std::function<void(std::ostream&)> moreSections;
};
// converge.md: the set-up, the table of final errors and time to error, and the error images.
void writeSummary(const std::filesystem::path& dir, const std::vector<ConfigResult>& results,
                  const ReportSetup& setup, const eval::ImageRGBA& reference);

}  // namespace wb::app
