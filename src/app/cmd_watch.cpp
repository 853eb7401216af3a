#include "app/cmd_watch.h"

#include <algorithm>
#include <chrono>
#include <deque>
#include <csignal>
#include <cstdio>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <sstream>
#include <thread>

#include "app/reload_log.h"
#include "eval/image.h"
#include "render/ab_comparison.h"
#include "app/render_options.h"
#include "common/file_io.h"
#include "common/json_text.h"
#include "common/paths.h"
#include "render/hot_reload.h"
#include "render/render_session.h"

namespace wb::app {
namespace {

std::atomic<bool> gInterrupted{false};

}  // namespace

void WatchCommand::addFlags(CLI::App& cli) {
  addRenderOptions(cli, options);
  cli.add_flag("--headless", headless, "render offscreen (no window)");
  framesOption_ = cli.add_option("--frames", frames, "stop after N frames (at least 1)");
  secondsOption_ =
      cli.add_option("--seconds", seconds, "stop after S seconds (more than 0)")->excludes(framesOption_);
  cli.add_option("--log", logPath, "append one JSON line per reload to this file");
  cli.add_flag(
      "--ab", ab,
      "after each reload, compare the old and the new pipeline (same seeds): image and speed verdicts in "
      "the log's \"ab\"");
  abOptions_ = {cli.add_option("--ab-size", abSize, "A/B trace size WxH")->capture_default_str(),
                cli.add_option("--ab-spp", abSpp, "A/B samples per side (one seed each)")
                    ->check(CLI::Range(1u, 1024u))
                    ->capture_default_str(),
                cli.add_option("--ab-rounds", abRounds, "A/B timing rounds (alternating old and new)")
                    ->check(CLI::Range(1u, 1000u))
                    ->capture_default_str(),
                cli.add_option("--ab-diff-dir", abDiffDir,
                               "write each A/B comparison's old, new and difference images (EXR)")};
}

void WatchCommand::finish() {
  finishRenderOptions(options);
  if (framesOption_->count() && frames == 0) throw std::invalid_argument("--frames: at least 1");
  if (secondsOption_->count() && !(seconds > 0 && std::isfinite(seconds)))
    throw std::invalid_argument("--seconds: a finite number of seconds above 0");
  if (!options.aov.empty()) throw std::invalid_argument("--aov: watch writes no images (render --aov does)");
  for (const CLI::Option* o : abOptions_) {
    if (o->count() && !ab) throw std::invalid_argument(o->get_name() + ": needs --ab");
  }
  uint32_t w = 0, h = 0;
  char x = 0;
  std::string extra;
  std::istringstream in(abSize);
  if (!(in >> w >> x >> h) || (x != 'x' && x != 'X') || (in >> extra) || w == 0 || h == 0 || w > 4096 ||
      h > 4096) {
    throw std::invalid_argument("--ab-size: expected WxH with 1..4096, got '" + abSize + "'");
  }
  abWidth = w;
  abHeight = h;
  // The outputs, before any work: the diff folder must take files (it is written at each reload).
  if (!abDiffDir.empty()) requireWritableDirectory(abDiffDir, "--ab-diff-dir");
  if (!logPath.empty()) log_ = AppendLog(logPath, "--log");
}

int runWatchCommand(const std::vector<std::string>& args) {
  WatchCommand c;
  return runCommand(c, args);
}

int WatchCommand::run() {
  const RenderOptions& ro = options;
  if (!headless)
    std::printf("workbench watch: rendering headless (the live window is the plain `workbench`)\n");

  render::ABBudget budget;
  budget.spp = abSpp;
  budget.rounds = abRounds;
  budget.width = abWidth;
  budget.height = abHeight;
  try {
    render::SessionOptions so;
    so.scenePath = ro.scene;
    so.settings = ro.params.render;
    so.context.deviceName = ro.device;
    so.mode = ro.params.mode;
    so.hybrid = ro.params.hybrid;
    render::RenderSession session(so);
    render::HotReload hot(session.library(), {shaderDir()});
    session.attachHotReload(&hot);  // every renderer's pipelines, the hybrid modes' raster ones too
    std::optional<render::ABComparison> comparison;
    if (ab) {
      comparison.emplace(session, budget);
      comparison->prepare();
    }
    hot.start();
    std::signal(SIGINT, [](int) { gInterrupted = true; });
    std::signal(SIGTERM, [](int) { gInterrupted = true; });
    std::printf("watching %s; rendering %s at %ux%u on %s\n", shaderDir().string().c_str(),
                session.scene().sourcePath.string().c_str(), ro.params.render.width, ro.params.render.height,
                session.context().deviceName().c_str());
    std::fflush(stdout);

    const auto start = std::chrono::steady_clock::now();
    std::optional<render::ReloadEvent> unlogged;
    auto writeEvent = [&](const render::ReloadEvent& e) {
      const std::string line = jsonText(reloadEventJson(e));
      std::printf("%s\n", line.c_str());
      std::fflush(stdout);
      if (log_.isOpen()) log_.writeLine(line);  // a failure is said once on stderr and in the exit status
    };
    // While a rebuild compiles, rest after each frame where the device's policy says so (the compile then
    // gets the cores of a CPU device).
    const double yieldRatio = session.context().policy().watchRestRatio;
    uint64_t frame = 0;
    while (!gInterrupted) {
      if (frames && frame >= frames) break;
      if (seconds > 0 &&
          std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() >= seconds) {
        break;
      }
      if (auto e = hot.poll()) {
        if (unlogged) writeEvent(*unlogged);
        unlogged.reset();
        if (e->pipelinesRebuilt.empty()) {
          writeEvent(*e);  // nothing to draw with: a failure keeps the old pipeline
        } else {
          unlogged = e;
        }
      }
      const auto frameBegin = std::chrono::steady_clock::now();
      auto& renderer = session.renderer();
      session.context().submitAndWait([&](VkCommandBuffer cmd) { renderer.record(cmd); });
      renderer.advance();
      hot.frameFinished(frameBegin);  // the frame's own time: the yield below is not part of it
      const auto frameEnd = std::chrono::steady_clock::now();
      if (yieldRatio > 0 && hot.compiling()) {
        const auto until = frameEnd + (frameEnd - frameBegin) * yieldRatio;
        while (hot.compiling() && std::chrono::steady_clock::now() < until)
          std::this_thread::sleep_for(std::chrono::milliseconds(2));
      }
      ++frame;
      if (unlogged) {
        // The new image is on screen (its first frame finished): now the A/B comparison, which the log line
        // carries.
        if (comparison) {
          const auto t0 = std::chrono::steady_clock::now();
          std::vector<render::ReloadAB> results;
          const auto outcomes = comparison->compare(hot.lastInstalled());
          const size_t reload = hot.history().size();
          for (size_t i = 0; i < outcomes.size(); ++i) {
            results.push_back(outcomes[i].result);
            if (abDiffDir.empty()) continue;
            const std::string stem = "reload" + std::to_string(reload) + "_" + std::to_string(i);
            const std::filesystem::path dir(abDiffDir);
            eval::writeExr(dir / (stem + "_old.exr"), outcomes[i].oldImage);
            eval::writeExr(dir / (stem + "_new.exr"), outcomes[i].newImage);
            eval::writeExr(dir / (stem + "_diff.exr"),
                           eval::differenceImage(outcomes[i].oldImage, outcomes[i].newImage));
          }
          hot.attachAB(
              std::move(results),
              std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
        }
        writeEvent(hot.history().back());
        unlogged.reset();
      }
    }
    hot.stop();
    session.attachHotReload(nullptr);
    std::printf("watch: %llu frames, %zu reloads\n", static_cast<unsigned long long>(frame),
                hot.history().size());
    if (log_.failed()) return 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "workbench watch: error: %s\n", e.what());
    return 1;
  }
  return 0;
}

}  // namespace wb::app
