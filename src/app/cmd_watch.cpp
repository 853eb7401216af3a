#include "app/cmd_watch.h"

#include <algorithm>
#include <chrono>
#include <deque>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <thread>

#include "app/reload_log.h"
#include "app/render_options.h"
#include "app/render_session.h"
#include "common/json_text.h"
#include "common/paths.h"
#include "render/hot_reload.h"

namespace wb::app {
namespace {

std::atomic<bool> gInterrupted{false};

}  // namespace

int runWatchCommand(const std::vector<std::string>& args) {
  CLI::App cli("Render continuously offscreen while watching the shaders; log every reload",
               "workbench watch");
  RenderOptions ro;
  ro.size = "256x256";
  bool headless = false;
  uint64_t frames = 0;
  double seconds = 0;
  std::string logPath;
  addRenderOptions(cli, ro);
  cli.add_flag("--headless", headless, "render offscreen (no window)");
  auto* framesOpt = cli.add_option("--frames", frames, "stop after N frames");
  cli.add_option("--seconds", seconds, "stop after S seconds")->excludes(framesOpt);
  cli.add_option("--log", logPath, "append one JSON line per reload to this file");
  try {
    std::vector<std::string> reversed(args.rbegin(), args.rend());
    cli.parse(reversed);
    finishRenderOptions(ro);
  } catch (const CLI::CallForHelp&) {
    std::printf("%s", cli.help().c_str());
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "workbench watch: error: %s\n", e.what());
    return 2;
  }
  if (!headless)
    std::printf("workbench watch: rendering headless (the live window is the plain `workbench`)\n");

  std::ofstream log;
  if (!logPath.empty()) {
    log.open(logPath, std::ios::app);
    if (!log) {
      std::fprintf(stderr, "workbench watch: error: cannot open --log file '%s'\n", logPath.c_str());
      return 1;
    }
  }
  try {
    SessionOptions so;
    so.scenePath = ro.scene;
    so.settings = ro.settings;
    so.context.deviceName = ro.device;
    so.mode = ro.mode;
    so.hybrid = ro.hybrid;
    RenderSession session(so);
    auto& tracer = session.pathTracer();
    render::HotReload hot(session.library(), {shaderDir()});
    tracer.addHotReloadTarget(hot);
    // The hybrid modes' raster and ray tracing pipelines reload through the same shader library.
    if (auto* hybrid = session.hybrid()) hybrid->addHotReloadTargets(hot);
    hot.start();
    std::signal(SIGINT, [](int) { gInterrupted = true; });
    std::signal(SIGTERM, [](int) { gInterrupted = true; });
    std::printf("watching %s; rendering %s at %ux%u on %s\n", shaderDir().string().c_str(),
                session.scene().sourcePath.string().c_str(), ro.settings.width, ro.settings.height,
                session.context().deviceName().c_str());
    std::fflush(stdout);

    const auto start = std::chrono::steady_clock::now();
    std::optional<render::ReloadEvent> unlogged;
    auto writeEvent = [&](const render::ReloadEvent& e) {
      const std::string line = jsonText(reloadEventJson(e));
      std::printf("%s\n", line.c_str());
      std::fflush(stdout);
      if (log) {
        log << line << "\n";
        log.flush();
      }
    };
    // While a rebuild compiles on a CPU device, sleep after each frame so that the frames keep
    // kCpuRenderShareWhileCompiling of the time (render/hot_reload.h).
    const double yieldRatio = render::rebuildRestRatio(session.context().cpuDevice());
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
      if (auto* hybrid = session.hybrid()) {
        session.context().submitAndWait([&](VkCommandBuffer cmd) { hybrid->record(cmd); });
        hybrid->advanceFrame();
      } else {
        session.context().submitAndWait([&](VkCommandBuffer cmd) { tracer.record(cmd); });
        tracer.advanceSample();
      }
      hot.frameFinished(frameBegin);  // the frame's own time: the yield below is not part of it
      const auto frameEnd = std::chrono::steady_clock::now();
      if (yieldRatio > 0 && hot.compiling()) {
        const auto until = frameEnd + (frameEnd - frameBegin) * yieldRatio;
        while (hot.compiling() && std::chrono::steady_clock::now() < until)
          std::this_thread::sleep_for(std::chrono::milliseconds(2));
      }
      ++frame;
      if (unlogged) {
        writeEvent(hot.history().back());
        unlogged.reset();
      }
    }
    hot.stop();
    std::printf("watch: %llu frames, %zu reloads\n", static_cast<unsigned long long>(frame),
                hot.history().size());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "workbench watch: error: %s\n", e.what());
    return 1;
  }
  return 0;
}

}  // namespace wb::app
