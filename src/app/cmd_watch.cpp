#include "app/cmd_watch.h"

#include <algorithm>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>

#include "app/reload_log.h"
#include "eval/image.h"
#include "app/render_options.h"
#include "common/json_text.h"
#include "common/paths.h"
#include "live/edit_loop.h"
#include "render/render_session.h"

namespace wb::app {
namespace {

std::atomic<bool> gInterrupted{false};

}  // namespace

void WatchCommand::addFlags(CLI::App& cli) {
  addRenderOptions(cli, options);
  cli.add_flag("--headless", headless, "render offscreen (no window)");
  auto* framesOpt = cli.add_option("--frames", frames, "stop after N frames");
  cli.add_option("--seconds", seconds, "stop after S seconds")->excludes(framesOpt);
  cli.add_option("--log", logPath, "append one JSON line per reload to this file");
  cli.add_flag(
      "--ab", ab,
      "after each reload, compare the old and the new pipeline (same seeds): image and speed verdicts in "
      "the log's \"ab\"");
  cli.add_option("--ab-size", abSize, "A/B trace size WxH")->capture_default_str();
  cli.add_option("--ab-spp", abSpp, "A/B samples per side (one seed each)")
      ->check(CLI::Range(1u, 1024u))
      ->capture_default_str();
  cli.add_option("--ab-rounds", abRounds, "A/B timing rounds (alternating old and new)")
      ->check(CLI::Range(1u, 1000u))
      ->capture_default_str();
  cli.add_option("--ab-diff-dir", abDiffDir,
                 "write each A/B comparison's old, new and difference images (EXR)");
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
  {
    uint32_t w = 0, h = 0;
    char x = 0;
    std::string extra;
    std::istringstream in(abSize);
    if (!(in >> w >> x >> h) || (x != 'x' && x != 'X') || (in >> extra) || w == 0 || h == 0 || w > 4096 ||
        h > 4096) {
      std::fprintf(stderr, "workbench watch: error: --ab-size: expected WxH with 1..4096, got '%s'\n",
                   abSize.c_str());
      return 1;
    }
    budget.width = w;
    budget.height = h;
  }
  if (!abDiffDir.empty()) {
    std::error_code ec;
    std::filesystem::create_directories(abDiffDir, ec);
    if (!std::filesystem::is_directory(abDiffDir)) {
      std::fprintf(stderr, "workbench watch: error: cannot create --ab-diff-dir '%s'\n", abDiffDir.c_str());
      return 1;
    }
  }
  std::ofstream log;
  if (!logPath.empty()) {
    log.open(logPath, std::ios::app);
    if (!log) {
      std::fprintf(stderr, "workbench watch: error: cannot open --log file '%s'\n", logPath.c_str());
      return 1;
    }
  }
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
    std::signal(SIGINT, [](int) { gInterrupted = true; });
    std::signal(SIGTERM, [](int) { gInterrupted = true; });
    std::printf("watching %s; rendering %s at %ux%u on %s\n", shaderDir().string().c_str(),
                session.scene().sourcePath.string().c_str(), ro.params.render.width, ro.params.render.height,
                session.context().deviceName().c_str());
    std::fflush(stdout);

    const auto start = std::chrono::steady_clock::now();
    size_t reloads = 0;
    // Each reload once it is over (a failure at once; an install after its first frame and comparison), with
    // the comparison's images when asked for.
    auto writeCompleted = [&] {
      for (const auto& c : loop.takeCompleted()) {
        ++reloads;
        for (size_t i = 0; i < c.ab.size() && !abDiffDir.empty(); ++i) {
          const std::string stem = "reload" + std::to_string(reloads) + "_" + std::to_string(i);
          const std::filesystem::path dir(abDiffDir);
          eval::writeExr(dir / (stem + "_old.exr"), c.ab[i].oldImage);
          eval::writeExr(dir / (stem + "_new.exr"), c.ab[i].newImage);
          eval::writeExr(dir / (stem + "_diff.exr"),
                         eval::differenceImage(c.ab[i].oldImage, c.ab[i].newImage));
        }
        if (!c.abError.empty()) std::fprintf(stderr, "workbench watch: A/B failed: %s\n", c.abError.c_str());
        const std::string line = jsonText(reloadEventJson(c.event));
        std::printf("%s\n", line.c_str());
        std::fflush(stdout);
        if (log) {
          log << line << "\n";
          log.flush();
        }
      }
    };
    // While a rebuild compiles, rest after each frame where the device's policy says so (the compile then
    // gets the cores of a CPU device).
    const double restRatio = session.context().policy().watchRestRatio;
    uint64_t frame = 0;
    while (!gInterrupted) {
      if (frames && frame >= frames) break;
      if (seconds > 0 &&
          std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() >= seconds) {
        break;
      }
      loop.beginFrame();
      writeCompleted();
      const auto frameBegin = std::chrono::steady_clock::now();
      auto& renderer = session.renderer();
      session.context().submitAndWait([&](VkCommandBuffer cmd) { renderer.record(cmd); });
      renderer.advance();
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
  } catch (const std::exception& e) {
    std::fprintf(stderr, "workbench watch: error: %s\n", e.what());
    return 1;
  }
  return 0;
}

}  // namespace wb::app
