// What `converge` and `sweep` share to make convergence runs: a configuration's flags, the session of a
// configuration, the reference render, the seed of each independent run and the measurement at a checkpoint.
// Both commands make a run the same way, so a sweep task repeats the run a converge configuration makes with
// the same seed and samples.
#pragma once
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "app/converge_report.h"
#include "app/progress.h"
#include "app/render_options.h"
#include "eval/image.h"
#include "render/render_session.h"

namespace wb::app {

// The seed the reference renders with: never one of the runs' seeds.
inline constexpr uint32_t kReferenceSeed = 0x5eed0000u;

// Splits a configuration's flag text at blanks; quotes group ("--env 'a b.hdr'"). Throws
// std::invalid_argument naming `what` on an unbalanced quote.
std::vector<std::string> splitFlags(const std::string& text, const std::string& what = "--config");

// Parses render flags (later ones win) into finished render options. `ignored` adds a command's own flags,
// parsed and dropped. Throws CLI::ParseError on an unknown flag, std::invalid_argument on a bad value.
RenderOptions parseRenderFlags(const std::vector<std::string>& args,
                               const std::function<void(CLI::App&)>& ignored = {});

// The session of one configuration: its scene, settings, device and mode, quiet.
render::SessionOptions sessionOptions(const RenderOptions& ro);

// The seed of independent run `run` (0, 1, ...) of a configuration whose --seed is `base`.
uint32_t runSeed(uint32_t base, uint32_t run);

// Adds `samples` samples (hybrid modes: frames) to the current image; returns the seconds it took.
double timedRender(render::RenderSession& session, uint32_t samples);

// The parameters a reference of `base` renders with: the path tracer, kReferenceSeed, not denoised.
render::Parameters referenceParameters(const render::Parameters& base);

struct ReferenceRender {
  eval::ImageRGBA image;
  double seconds = 0;       // rendering
  double setupSeconds = 0;  // the session's set-up (scene, device, shaders)
  std::string device;
  bool interrupted = false;  // `stop` ended it before `spp` samples (no image)
};
// Renders the reference of `base` (referenceParameters) at `spp`, showing progress. `stop` (optional) is
// asked between batches of samples: true ends it, interrupted.
ReferenceRender renderReference(const RenderOptions& base, uint32_t spp, ProgressLine& progress,
                                const std::function<bool()>& stop = {});

// A reference image file for a render of width x height: an OpenEXR file of that size or of the same integer
// multiple on both axes. Throws std::invalid_argument starting "--reference" with a plain reason (no such
// file, not an OpenEXR image, the sizes).
eval::ImageRGBA readReferenceFile(const std::string& path, uint32_t width, uint32_t height);
// A reference read by readReferenceFile, box-downsampled to width x height when it is larger; `description`
// says which.
eval::ImageRGBA downsampleReference(eval::ImageRGBA ref, const std::string& path, uint32_t width,
                                    uint32_t height, std::string& description);
// Both.
eval::ImageRGBA loadReferenceFile(const std::string& path, uint32_t width, uint32_t height,
                                  std::string& description);

// Adds one run's measurement at a checkpoint to cp: its time, errors against the reference, mean and image.
void addMeasurement(Checkpoint& cp, eval::ImageRGBA image, const eval::ImageRGBA& reference, double seconds);

}  // namespace wb::app
