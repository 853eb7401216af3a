#include "app/cmd_watch.h"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <sstream>
#include <thread>

#include "app/progress.h"
#include "app/reload_log.h"
#include "eval/image.h"
#include "app/render_options.h"
#include "common/file_io.h"
#include "common/json_text.h"
#include "common/paths.h"
#include "live/edit_loop.h"
#include "render/render_session.h"

namespace wb::app {
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

  live::ABBudget budget;
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
    live::EditLoopOptions lo;
    lo.ab = ab;
    lo.budget = budget;
    live::EditLoop loop(session, lo);  // every renderer's passes, the hybrid modes' raster ones too
    if (ab) loop.prepareAB();
    loop.start();
    // SIGINT/SIGTERM end the loop after the frame in progress (or, should it never finish, the process).
    InterruptRequest interrupt;
    std::printf("watching %s; rendering %s at %ux%u on %s\n", shaderDir().string().c_str(),
                session.scene().sourcePath.string().c_str(), ro.params.render.width, ro.params.render.height,
                session.context().deviceName().c_str());
    std::fflush(stdout);

    const auto start = std::chrono::steady_clock::now();
    size_t reloads = 0;
    // An output that fails during the session (a disk that fills up) is said once and in the exit status; the
    // session goes on.
    std::string outputError;
    auto writeDiffImages = [&](const live::CompletedReload& c) {
      for (size_t i = 0; i < c.ab.size() && !abDiffDir.empty() && outputError.empty(); ++i) {
        const std::string stem = "reload" + std::to_string(reloads) + "_" + std::to_string(i);
        const std::filesystem::path dir(abDiffDir);
        try {
          eval::writeExr(dir / (stem + "_old.exr"), c.ab[i].oldImage);
          eval::writeExr(dir / (stem + "_new.exr"), c.ab[i].newImage);
          eval::writeExr(dir / (stem + "_diff.exr"),
                         eval::differenceImage(c.ab[i].oldImage, c.ab[i].newImage));
        } catch (const std::exception& e) {
          outputError = e.what();
          std::fprintf(stderr,
                       "workbench watch: error: --ab-diff-dir: %s; later comparisons are not written\n",
                       e.what());
        }
      }
    };
    // Each reload once it is over (a failure at once; an install after its first frame and comparison), with
    // the comparison's images when asked for.
    auto writeCompleted = [&] {
      for (const auto& c : loop.takeCompleted()) {
        ++reloads;
        writeDiffImages(c);
        if (!c.abError.empty()) std::fprintf(stderr, "workbench watch: A/B failed: %s\n", c.abError.c_str());
        const std::string line = jsonText(reloadEventJson(c.event));
        std::printf("%s\n", line.c_str());
        std::fflush(stdout);
        if (log_.isOpen()) log_.writeLine(line);  // a failure is said once on stderr and in the exit status
      }
    };
    // While a rebuild compiles, rest after each frame where the device's policy says so (the compile then
    // gets the cores of a CPU device).
    const double restRatio = session.context().policy().watchRestRatio;
    uint64_t frame = 0;
    while (!interrupt.requested()) {
      if (frames && frame >= frames) break;
      if (seconds > 0 &&
          std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() >= seconds) {
        break;
      }
      loop.beginFrame();
      writeCompleted();
      const auto frameBegin = std::chrono::steady_clock::now();
      auto& renderer = session.renderer();
      const auto limit = loop.frameLimit();
      if (!session.context().submitAndWaitFor([&](VkCommandBuffer cmd) { renderer.record(cmd); }, limit)) {
        // No driver here cancels a running shader: say which edit did it, in the log too, and end.
        live::ReloadEvent e;
        e.ok = false;
        e.error = loop.hangMessage(std::chrono::duration<double>(limit).count());
        e.when = std::chrono::system_clock::now();
        if (const auto last = loop.hot().lastEvent()) e.filesChanged = last->filesChanged;
        const std::string line = jsonText(reloadEventJson(e));
        std::printf("%s\n", line.c_str());
        std::fprintf(stderr, "workbench watch: error: %s\n", e.error.c_str());
        if (log_.isOpen()) log_.writeLine(line);
        std::fflush(stdout);
        std::fflush(stderr);
        ::_exit(4);
      }
      renderer.advance();
      interrupt.noteWorkSeconds(
          std::chrono::duration<double>(std::chrono::steady_clock::now() - frameBegin).count());
      const auto frameEnd = std::chrono::steady_clock::now();
      loop.frameFinished(frameBegin);  // the frame's own time: the rest below is not part of it
      const auto until = loop.restUntil(frameBegin, frameEnd, restRatio);
      while (loop.compiling() && std::chrono::steady_clock::now() < until)
        std::this_thread::sleep_for(std::chrono::milliseconds(2));
      ++frame;
      writeCompleted();
    }
    loop.hot().stop();
    std::printf("watch: %llu frames, %zu reloads\n", static_cast<unsigned long long>(frame),
                loop.hot().history().size());
    if (log_.failed() || !outputError.empty()) return 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "workbench watch: error: %s\n", e.what());
    return 1;
  }
  return 0;
}

}  // namespace wb::app
