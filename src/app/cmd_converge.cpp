#include "app/cmd_converge.h"
#include "app/progress.h"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <map>
#include <optional>
#include <sstream>

#include "app/converge_denoise.h"
#include "app/converge_report.h"
#include "app/converge_run.h"
#include "app/render_options.h"
#include "render/render_session.h"
#include "shader/hash.h"
#include "common/atomic_file.h"
#include "common/file_io.h"
#include "common/paths.h"
#include "eval/metrics.h"

namespace fs = std::filesystem;

namespace wb::app {
namespace {

void addConvergeOptions(CLI::App& cli, ConvergeOptions& c) {
  cli.add_option("--reference", c.reference,
                 "reference image (.exr, linear; box-downsampled when an integer multiple of --size)");
  cli.add_option("--reference-spp", c.referenceSpp,
                 "without --reference: spp of the cached reference render (default 1024)");
  cli.add_option("--seconds", c.seconds, "render time per configuration and run")->capture_default_str();
  cli.add_option("--runs", c.runs, "independent runs (seeds) per configuration, for the variance")
      ->capture_default_str()
      ->check(CLI::Range(1u, 64u));
  cli.add_option("--max-spp", c.maxSpp, "stop a run at this many samples per pixel")->capture_default_str();
  cli.add_option("--target-relmse", c.targetRelMse,
                 "relMSE for the time-to-error column (default: median of the final relMSEs)");
  cli.add_option("--config", c.configs, "NAME:FLAGS, render flags of one configuration (repeatable)");
  cli.add_option("--out", c.out, "output folder")->required();
  cli.add_flag("--hard-cases", c.hardCases, "render the built-in numerical hard cases instead of SCENE");
}

// The command's own flags: a configuration (render flags only) cannot hold them.
const char* const kConvergeFlags[] = {"--reference", "--reference-spp", "--seconds",
                                      "--runs",      "--max-spp",       "--target-relmse",
                                      "--config",    "--out",           "--hard-cases"};

// The first of the command's own flags among a configuration's words, or nullptr.
const char* commandFlagIn(const std::vector<std::string>& words) {
  for (const auto& w : words)
    for (const char* flag : kConvergeFlags)
      if (w == flag || w.rfind(std::string(flag) + "=", 0) == 0) return flag;
  return nullptr;
}

// Parses the command's arguments (plus a configuration's flags, which win) into render options.
RenderOptions parseConvergeRenderFlags(const std::vector<std::string>& args,
                                       const std::vector<std::string>& extra) {
  std::vector<std::string> all = args;
  all.insert(all.end(), extra.begin(), extra.end());
  ConvergeOptions ignored;
  return parseRenderFlags(all, [&](CLI::App& cli) { addConvergeOptions(cli, ignored); });
}

std::string mtimeOf(const fs::path& p) {
  std::error_code ec;
  auto t = fs::last_write_time(p, ec);
  if (ec) return "?";
  return std::to_string(t.time_since_epoch().count());
}

// The reference: a file (read by finish(), downsampled to the render size when needed), or a cached long
// render (interrupted: nullopt).
std::optional<eval::ImageRGBA> loadOrRenderReference(const ConvergeOptions& c, const RenderOptions& base,
                                                     ProgressLine& progress, std::string& description,
                                                     const InterruptRequest& interrupt,
                                                     std::optional<eval::ImageRGBA> fromFile) {
  const auto& s = base.params.render;
  if (!c.reference.empty()) {
    eval::ImageRGBA ref = fromFile ? std::move(*fromFile) : readReferenceFile(c.reference, s.width, s.height);
    return downsampleReference(std::move(ref), c.reference, s.width, s.height, description);
  }
  const uint32_t spp = c.referenceSpp ? c.referenceSpp : 1024;
  const fs::path scene = base.scene.empty() ? defaultScenePath() : fs::path(base.scene);
  std::error_code ec;
  const fs::path canonical = fs::weakly_canonical(scene, ec);
  // The reference renders the path tracer with its own seed: the key holds what it renders with.
  const render::Parameters refParams = referenceParameters(base.params);
  std::string key = "scene " + canonical.string() + " mtime " + mtimeOf(scene) + " " +
                    std::to_string(s.width) + "x" + std::to_string(s.height) + " " +
                    render::imageKey(refParams) + " spp " + std::to_string(spp) + " shaders " +
                    render::shaderSourceFingerprint() + " v3";
  if (!s.envPath.empty()) key += " envmtime " + mtimeOf(s.envPath);
  const std::string hex = shader::Hasher().add(key).finish().hex();
  const fs::path dir = shaderCacheDir() / "references";
  const fs::path file = dir / (hex + ".exr");
  if (fs::exists(file)) {
    description = "cached render of the same scene and base flags, " + std::to_string(spp) + " spp (`" +
                  file.string() + "`)";
    return eval::readExr(file);
  }
  const ReferenceRender rendered =
      renderReference(base, spp, progress, [&] { return interrupt.requested(); });
  if (rendered.interrupted) return std::nullopt;
  const double t = rendered.seconds;
  const eval::ImageRGBA& ref = rendered.image;
  fs::create_directories(dir);
  eval::writeExr(file, ref);
  writeFileAtomically(dir / (hex + ".txt"), key + "\n", "reference cache");
  description = "rendered now by this command and cached: " + std::to_string(spp) +
                " spp of the same scene " + "with the base flags (`" + file.string() + "`, " +
                std::to_string(t) + " s)";
  return ref;
}

// Ctrl-C stops it after the sample in progress: the result holds the checkpoints reached.
// With --denoise (path tracer) each checkpoint measures the raw image and the denoised one of the same
// samples.
ConfigResult runConfig(const ConvergeConfig& cfg, const ConvergeOptions& c, const eval::ImageRGBA& reference,
                       uint32_t referenceSpp, ProgressLine& progress, size_t index, size_t count,
                       const InterruptRequest& interrupt) {
  ConfigResult result;
  const bool denoise =
      cfg.options.params.render.denoise && cfg.options.params.mode == render::RenderMode::PathTrace;
  result.name = cfg.name;
  for (const auto& f : cfg.flags) result.flags += (result.flags.empty() ? "" : " ") + f;
  render::RenderSession session(sessionOptions(cfg.options));
  result.setupSeconds = session.setupSeconds();
  std::vector<uint32_t> schedule;  // spp of the checkpoints, set by run 0
  for (uint32_t run = 0; run < c.runs && !interrupt.requested(); ++run) {
    render::RenderSettings s = cfg.options.params.render;
    s.seed = runSeed(cfg.options.params.render.seed, run);
    session.forEachRenderer([&](render::Renderer& r) {
      r.setSettings(s);
      r.resetAccumulation();
      r.resetCounters();
    });
    const std::string label = "[" + std::to_string(index + 1) + "/" + std::to_string(count) + "] " +
                              cfg.name + " run " + std::to_string(run + 1);
    double t = 0;
    uint32_t spp = 0;
    size_t next = 0;  // checkpoint index
    // Wall-time checkpoints: seconds / 64, / 32, ..., seconds.
    double nextTick = c.seconds / 64.0;
    auto checkpoint = [&]() {
      if (result.checkpoints.size() <= next) result.checkpoints.emplace_back();
      Checkpoint& cp = result.checkpoints[next];
      cp.spp = spp;
      if (denoise) {
        render::PathTracer& tracer = session.pathTracer();
        addMeasurement(cp, tracer.readEstimate(), reference, t);
        if (result.denoised.size() <= next) result.denoised.emplace_back();
        Checkpoint& d = result.denoised[next];
        d.spp = spp;
        const double denoiseSeconds = tracer.denoise();
        addMeasurement(d, tracer.readDenoised(), reference, t + denoiseSeconds);
      } else {
        addMeasurement(cp, session.image(), reference, t);
      }
      ++next;
    };
    while (!interrupt.requested()) {
      if (run == 0) {
        if (t >= c.seconds || spp >= c.maxSpp) break;
        const double dt = timedRender(session, 1);
        interrupt.noteWorkSeconds(dt);  // a signal's grace covers a sample in progress
        t += dt;
        ++spp;
        const bool pow2 = (spp & (spp - 1)) == 0;
        bool tick = false;
        while (t >= nextTick) {
          tick = true;
          nextTick *= 2;
        }
        if (pow2 || tick || t >= c.seconds || spp >= c.maxSpp) {
          schedule.push_back(spp);
          checkpoint();
        }
      } else {
        if (next >= schedule.size()) break;
        t += timedRender(session, schedule[next] - spp);
        spp = schedule[next];
        checkpoint();
      }
      char detail[96];
      std::snprintf(detail, sizeof detail, "%.1f/%.1f s %u spp", t, c.seconds, spp);
      const double fraction =
          run == 0 ? t / c.seconds : double(next) / double(std::max<size_t>(1, schedule.size()));
      progress.update(label, fraction, detail);
    }
    char detail[96];
    std::snprintf(detail, sizeof detail, "%.1f/%.1f s %u spp", t, c.seconds, spp);
    progress.update(label, 1.0, detail, true);
    progress.finish();
    result.dropped += session.renderer().readCounters().droppedSamples;
    if (run == 0 && !result.checkpoints.empty()) {
      result.fireflies = eval::fireflyStats(result.checkpoints.back().images.back());
    }
  }
  // Run-to-run variance and the pixel tests at each checkpoint; keep only run 0's final image.
  testPixels(result, reference, referenceSpp);
  for (auto* rows : {&result.checkpoints, &result.denoised}) {
    for (size_t i = 0; i < rows->size(); ++i) {
      Checkpoint& cp = (*rows)[i];
      if (cp.images.size() >= 2) cp.variance = eval::runStats(cp.images).meanVariance();
      if (i + 1 < rows->size()) {
        cp.images.clear();
      } else {
        cp.images.resize(1);
      }
    }
  }
  return result;
}

}  // namespace

void ConvergeCommand::addFlags(CLI::App& cli) {
  addRenderOptions(cli, base);
  addConvergeOptions(cli, converge);
  referenceSppOption_ = cli.get_option("--reference-spp");
}

int runConvergeCommand(const std::vector<std::string>& args) {
  ConvergeCommand c;
  return runCommand(c, args);
}

void ConvergeCommand::finish() {
  auto& c = converge;
  base = parseConvergeRenderFlags(args, {});
  if (!c.reference.empty() && c.referenceSpp) {
    throw std::invalid_argument("give --reference or --reference-spp, not both");
  }
  if (!(c.seconds > 0) || !std::isfinite(c.seconds))
    throw std::invalid_argument("--seconds: a finite number of seconds above 0");
  if (c.maxSpp == 0) throw std::invalid_argument("--max-spp: at least 1");
  if (!(c.targetRelMse >= 0) || !std::isfinite(c.targetRelMse))
    throw std::invalid_argument("--target-relmse: a finite relMSE of 0 or more (0: the median)");
  if (referenceSppOption_ && referenceSppOption_->count() && c.referenceSpp == 0)
    throw std::invalid_argument("--reference-spp: at least 1 (without it: 1024)");
  if (c.configs.empty()) c.configs.push_back("base:");
  std::map<std::string, std::string> files;  // error image -> the configuration that writes it
  for (const auto& text : c.configs) {
    const auto colon = text.find(':');
    if (colon == std::string::npos || colon == 0) {
      throw std::invalid_argument("--config: expected NAME:FLAGS, got '" + text + "'");
    }
    ConvergeConfig cfg;
    cfg.name = text.substr(0, colon);
    cfg.flags = splitFlags(text.substr(colon + 1));
    // Two configurations of one name would share a CSV name and an error image (one overwriting the other).
    const std::string image = "error_" + safeName(cfg.name) + ".png";
    if (const auto other = files.find(image); other != files.end()) {
      throw std::invalid_argument("--config '" + cfg.name + "': " +
                                  (other->second == cfg.name
                                       ? "a second configuration of this name"
                                       : "the same file name as '" + other->second + "'") +
                                  " (" + image + "): give each its own name");
    }
    files[image] = cfg.name;
    if (const char* flag = commandFlagIn(cfg.flags)) {
      throw std::invalid_argument("--config '" + cfg.name + "': " + flag +
                                  " belongs to the command, not to a configuration (give it once, outside "
                                  "--config)");
    }
    try {
      cfg.options = parseConvergeRenderFlags(args, cfg.flags);
    } catch (const CLI::ParseError& e) {
      throw std::invalid_argument("--config '" + cfg.name + "': " + e.what());
    }
    if (cfg.options.params.render.width != base.params.render.width ||
        cfg.options.params.render.height != base.params.render.height || cfg.options.scene != base.scene) {
      throw std::invalid_argument("--config '" + cfg.name +
                                  "': a configuration cannot change SCENE or --size");
    }
    configs.push_back(std::move(cfg));
  }
  // A reference file is read now: a missing file, another format or another size is refused before any
  // folder is made or anything rendered.
  if (!c.reference.empty() && !c.hardCases)
    referenceImage_ = readReferenceFile(c.reference, base.params.render.width, base.params.render.height);
}

int ConvergeCommand::run() {
  const auto& c = converge;
  const fs::path dir(c.out);
  std::error_code ec;
  const bool dirExisted = fs::exists(dir, ec);
  // A command that fails leaves no empty folder it made behind.
  auto removeIfEmptyAndNew = [&] {
    std::error_code rec;
    if (!dirExisted && fs::is_directory(dir, rec) && fs::is_empty(dir, rec)) fs::remove(dir, rec);
  };
  try {
    requireWritableDirectory(dir, "--out");  // before any render: never fail at the end for want of a folder
    if (c.hardCases) return runHardCases();
    // Ctrl-C stops the render in progress: the report then covers the checkpoints done, marked partial.
    InterruptRequest interrupt;
    ProgressLine progress("converge");
    std::string refDescription;
    std::optional<eval::ImageRGBA> loaded =
        loadOrRenderReference(c, base, progress, refDescription, interrupt, std::move(referenceImage_));
    if (!loaded) {
      std::fprintf(stderr,
                   "workbench converge: interrupted while rendering the reference: nothing written\n");
      removeIfEmptyAndNew();
      return 128 + interrupt.signal();
    }
    const eval::ImageRGBA reference = std::move(*loaded);
    const eval::Rgb refMean = eval::meanRgb(reference);
    // A render of the path tracer: its own noise is modelled in the pixel tests (a file is taken as exact).
    const uint32_t referenceSpp = c.reference.empty() ? (c.referenceSpp ? c.referenceSpp : 1024) : 0;
    std::vector<ConfigResult> results;
    std::string device;
    for (size_t i = 0; i < configs.size() && !interrupt.requested(); ++i) {
      results.push_back(
          runConfig(configs[i], c, reference, referenceSpp, progress, i, configs.size(), interrupt));
    }
    std::string partialNote;
    if (interrupt.requested()) {
      const ConfigResult& last = results.back();
      size_t runs = 0;
      for (const auto& cp : last.checkpoints) runs = std::max(runs, cp.seconds.size());
      partialNote = "interrupted (signal " + std::to_string(interrupt.signal()) + ") in configuration '" +
                    last.name + "' after " + std::to_string(last.checkpoints.size()) +
                    " checkpoint(s) of run " + std::to_string(std::max<size_t>(runs, 1)) + " of " +
                    std::to_string(c.runs) + "; " + std::to_string(results.size() - 1) + " of " +
                    std::to_string(configs.size()) +
                    " configuration(s) done before it. The rows below are what was measured until then.";
    }
    {
      // The device name, from a cheap context (the sessions are gone).
      vk::ContextOptions co;
      co.deviceName = base.device;
      device = vk::Context(co).deviceName();
    }
    writeCsv(dir / "converge.csv", results, refMean);
    const std::string sceneName =
        fs::path(base.scene.empty() ? defaultScenePath() : fs::path(base.scene)).filename().string();
    const std::string plotNote = writePlot(dir, results, sceneName);
    if (!plotNote.empty()) std::fprintf(stderr, "workbench converge: warning: %s\n", plotNote.c_str());
    ReportSetup setup;
    setup.scene = base.scene.empty() ? defaultScenePath().string() : base.scene;
    setup.width = base.params.render.width;
    setup.height = base.params.render.height;
    std::ostringstream budget;
    budget << c.seconds << " s per run";
    setup.budget = budget.str();
    setup.runs = c.runs;
    setup.device = device;
    setup.reference = refDescription;
    setup.referenceMean = refMean;
    setup.targetRelMse = c.targetRelMse;
    setup.plotNote = plotNote;
    setup.partialNote = partialNote;
    if (c.runs >= 2) {
      setup.notes.push_back(
          referenceSpp
              ? "Pixel tests: the reference's own variance per pixel is modelled as one run's times spp / " +
                    std::to_string(referenceSpp) + " (it is a render of the same path tracer)."
              : "Pixel tests: the reference file is taken as exact (its own noise, if any, makes more "
                "pixels look off: the raw image's rate shows how many).");
    }
    setup.moreSections = [&](std::ostream& md) { writeDenoiseComparison(md, results); };
    writeSummary(dir, results, setup, reference);
    std::printf("converge: %zu configuration(s) -> %s (converge.csv, converge.md%s)%s\n", results.size(),
                dir.string().c_str(), plotNote.empty() ? ", converge.png" : "",
                partialNote.empty() ? "" : ": partial, interrupted");
    if (!partialNote.empty()) return 128 + interrupt.signal();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "workbench converge: error: %s\n", e.what());
    removeIfEmptyAndNew();
    return 1;
  }
  return 0;
}

// ---- Hard cases ----

void applyHardCase(const scene::HardCase& hc, render::Parameters& params) {
  render::setParameters(params, hc.settings);
  if (params.render.maxBounces < hc.minBounces)
    render::setParameter(params, "max_bounces", std::to_string(hc.minBounces));
}

int ConvergeCommand::runHardCases() {
  const auto& c = converge;
  const fs::path dir(c.out);
  const uint32_t spp = base.params.render.spp;
  // Written whole after each case (common/atomic_file.h): the file shows the cases done so far.
  std::ostringstream md;
  md << "# Hard cases\n\n";
  md << "Each scene isolates one numerical risk. " << base.params.render.width << "x"
     << base.params.render.height << ", " << spp << " spp per configuration, max bounces "
     << base.params.render.maxBounces
     << " (furnaces: at least 64; the mirror corridor 256). Energy error: image mean against the analytic "
        "furnace value where "
        "the scene is a furnace (white, energy-preserving materials in a uniform environment of radiance 1: "
        "every pixel converges to 1). Firefly statistics on pixel luminance.\n\n";
  md << "| case | risk | config | NaN/Inf dropped | non-finite pixels | mean RGB | energy error | max/mean | "
        ">10x "
        "mean | time (s) |\n|---|---|---|---|---|---|---|---|---|---|\n";
  ProgressLine progress("converge");
  const auto cases = scene::hardCases();
  int failures = 0;
  for (size_t i = 0; i < cases.size(); ++i) {
    const auto& hc = cases[i];
    for (const auto& variant : hc.variants) {
      RenderOptions ro = parseConvergeRenderFlags(args, splitFlags(variant));
      applyHardCase(hc, ro.params);
      const render::RenderSettings& s = ro.params.render;
      render::SessionOptions so = sessionOptions(ro);
      so.sceneData = hc.scene;
      progress.update("[" + std::to_string(i + 1) + "/" + std::to_string(cases.size()) + "] " + hc.name, 0.0,
                      variant, true);
      render::RenderSession session(so);
      const double seconds = session.render(s.spp);
      const auto img = session.image();
      const auto counters = session.renderer().readCounters();
      const auto m = eval::meanRgb(img);
      const auto ff = eval::fireflyStats(img);
      std::string energy = "n/a";
      if (hc.furnaceValue > 0) {
        double e = 0;
        for (int k = 0; k < 3; ++k) e = std::max(e, std::abs(m[k] / hc.furnaceValue - 1.0));
        energy = fmt("%.2f%%", 100.0 * e);
      }
      failures += counters.droppedSamples ? 1 : 0;
      md << "| " << hc.name << " | " << hc.risk << " | `" << (variant.empty() ? "(default)" : variant)
         << "` | " << counters.droppedSamples << " | " << eval::countNonFinite(img) << " | "
         << fmt("%.4f", m[0]) << " " << fmt("%.4f", m[1]) << " " << fmt("%.4f", m[2]) << " | " << energy
         << " | " << fmt("%.1f", ff.maxOverMean) << " | " << fmt("%.2g", ff.fractionAbove10x) << " | "
         << fmt("%.2f", seconds) << " |\n";
      writeFileAtomically(dir / "hard_cases.md", md.str(), "converge --hard-cases");
      progress.update("[" + std::to_string(i + 1) + "/" + std::to_string(cases.size()) + "] " + hc.name, 1.0,
                      variant, true);
      progress.finish();
    }
  }
  md << "\n";
  std::string lastNote;
  for (const auto& hc : cases) {
    if (!hc.note.empty() && hc.note != lastNote) md << "- " << hc.name << ": " << hc.note << "\n";
    lastNote = hc.note;
  }
  md << "\nGoal: 0 NaN/Inf samples dropped everywhere. " << failures
     << " configuration(s) dropped samples.\n";
  writeFileAtomically(dir / "hard_cases.md", md.str(), "converge --hard-cases");
  std::printf("converge --hard-cases: %zu case(s) -> %s\n", cases.size(),
              (dir / "hard_cases.md").string().c_str());
  return 0;
}

}  // namespace wb::app
