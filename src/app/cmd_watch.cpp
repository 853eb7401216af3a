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
    // Frame timings, to show what a rebuild costs the frames rendered meanwhile.
    struct FrameTime {
      std::chrono::steady_clock::time_point begin, end;
    };
    std::deque<FrameTime> frameTimes;
    auto ms = [](auto a, auto b) { return std::chrono::duration<double, std::milli>(b - a).count(); };
    auto writeEvent = [&](const render::ReloadEvent& e) {
      auto j = reloadEventJson(e);
      std::vector<double> before;
      double duringMax = 0, firstNew = -1, controlMax = 0;
      // The control: the slowest frame in as long a span right before the edit (what a rebuild's frames are
      // compared with: frame times vary without any rebuild too).
      const double span = frameTimes.empty() ? 0.0 : ms(e.editSeen, frameTimes.back().end);
      for (const auto& f : frameTimes) {
        if (f.end <= e.editSeen) {
          before.push_back(ms(f.begin, f.end));
          if (ms(f.end, e.editSeen) <= span) controlMax = std::max(controlMax, ms(f.begin, f.end));
        } else if (&f == &frameTimes.back() && !e.pipelinesRebuilt.empty()) {
          firstNew = ms(f.begin, f.end);  // includes the driver's compile of the new pipeline
        } else {
          duringMax = std::max(duringMax, ms(f.begin, f.end));
        }
      }
      if (before.size() > 20) before.erase(before.begin(), before.end() - 20);
      std::sort(before.begin(), before.end());
      j["frame_ms_median_before"] = before.empty() ? 0.0 : before[before.size() / 2];
      j["frame_ms_max_during_rebuild"] = duringMax;
      j["frame_ms_max_before_same_span"] = controlMax;
      j["first_new_frame_ms"] = firstNew;
      const std::string line = j.dump();
      std::printf("%s\n", line.c_str());
      std::fflush(stdout);
      if (log) {
        log << line << "\n";
        log.flush();
      }
    };
    // While a rebuild compiles on a CPU device, sleep after each frame so that the frames keep
    // kCpuRenderShareWhileCompiling of the time (render/hot_reload.h).
    double yieldRatio = session.context().cpuDevice() ? (1.0 - render::kCpuRenderShareWhileCompiling) /
                                                            render::kCpuRenderShareWhileCompiling
                                                      : 0.0;
    if (const char* y = std::getenv("WB_REBUILD_YIELD")) yieldRatio = std::atof(y);
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
      frameTimes.push_back({frameBegin, std::chrono::steady_clock::now()});
      if (yieldRatio > 0 && hot.compiling()) {
        const auto until = frameTimes.back().end + (frameTimes.back().end - frameBegin) * yieldRatio;
        while (hot.compiling() && std::chrono::steady_clock::now() < until)
          std::this_thread::sleep_for(std::chrono::milliseconds(2));
      }
      // Keep ten seconds of frames (a rebuild on a fast GPU spans thousands of sub-millisecond frames).
      while (frameTimes.size() > 2 && ms(frameTimes.front().end, frameTimes.back().end) > 10000.0)
        frameTimes.pop_front();
      ++frame;
      hot.frameFinished();
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
