#include "app/bench_window.h"
#include "app/progress.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <functional>
#include <map>
#include <sstream>
#include <stdexcept>
#include <thread>

#include "app/process.h"
#include "common/atomic_file.h"
#include "common/env.h"
#include "common/paths.h"
#include "common/statistics.h"
#include "render/render_session.h"

namespace fs = std::filesystem;
using nlohmann::json;

namespace wb::app {

std::string readText(const fs::path& p) {
  std::ifstream f(p);
  std::stringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

std::string closestHitEdit(const std::string& original, int i) {
  static const std::string needle = "const float minCos = 1e-3;";
  std::string text = original;
  const auto pos = text.find(needle);
  if (pos == std::string::npos) throw std::runtime_error("bench: closesthit.rchit has no '" + needle + "'");
  char value[64];
  std::snprintf(value, sizeof(value), "const float minCos = %.9g;", 1e-3 * (1.0 + 1e-4 * (i + 1)));
  text.replace(pos, needle.size(), value);
  return text;
}

namespace {

using Clock = std::chrono::steady_clock;

json readJson(const fs::path& p) {
  return json::parse(readText(p));
}

// Polls `done` until it holds; false after `seconds` or once `child` has ended.
bool waitFor(const std::function<bool()>& done, double seconds, ChildProcess* child = nullptr) {
  const auto start = Clock::now();
  while (!done()) {
    if (child && child->exited()) return done();
    if (std::chrono::duration<double>(Clock::now() - start).count() > seconds) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  return true;
}

// The display the window runs on: the user's ($DISPLAY), or an Xvfb server started for the bench.
class BenchDisplay {
 public:
  explicit BenchDisplay(const fs::path& work) {
    if (const auto d = env::get("DISPLAY")) {
      name_ = *d;
      return;
    }
    const std::string xvfb = findProgram("Xvfb");
    if (xvfb.empty())
      throw std::runtime_error(
          "bench window: no DISPLAY and no Xvfb to start one (scripts/setup.sh installs xvfb)");
    for (int n = 90; n < 190; ++n) {
      const fs::path socket = "/tmp/.X11-unix/X" + std::to_string(n);
      if (fs::exists(socket) || fs::exists("/tmp/.X" + std::to_string(n) + "-lock")) continue;
      name_ = ":" + std::to_string(n);
      server_ = ChildProcess::spawn(xvfb, {name_, "-screen", "0", "1920x1080x24", "-nolisten", "tcp"}, {},
                                    (work / "xvfb.log").string());
      if (waitFor([&] { return fs::exists(socket); }, 30, &server_)) {
        started_ = true;
        return;
      }
      server_.terminate();  // another server took the number meanwhile: the next one
    }
    throw std::runtime_error("bench window: could not start Xvfb: " + readText(work / "xvfb.log"));
  }
  ~BenchDisplay() { server_.terminate(); }
  BenchDisplay(const BenchDisplay&) = delete;
  BenchDisplay& operator=(const BenchDisplay&) = delete;
  const std::string& name() const { return name_; }
  bool started() const { return started_; }

 private:
  std::string name_;
  ChildProcess server_;
  bool started_ = false;
};

// Two busy loops in a session of their own (the kernel schedules another session's processes as a group, as
// it would another user's build beside the workbench); stopped with the object.
class BusyLoops {
 public:
  explicit BusyLoops(const fs::path& work)
      : p_(ChildProcess::spawn("sh", {"-c", "yes >/dev/null & yes >/dev/null & wait"}, {},
                               (work / "busy.log").string(), true)) {}
  ~BusyLoops() { p_.terminate(); }
  BusyLoops(const BusyLoops&) = delete;
  BusyLoops& operator=(const BusyLoops&) = delete;

 private:
  ChildProcess p_;
};

// A private copy of shaders/ and assets/ with its own caches, so that edits and the driver's caches of one
// run do not meet another's.
struct PrivateRoot {
  fs::path root, chit;
  std::string original;
  std::map<std::string, std::string> env;

  PrivateRoot(const fs::path& work, const std::string& name, const std::string& display, bool ownMesaCache) {
    root = work / name;
    fs::remove_all(root);
    fs::create_directories(root / "shader_cache");
    fs::copy(shaderDir(), root / "shaders", fs::copy_options::recursive);
    fs::copy(assetDir(), root / "assets", fs::copy_options::recursive);
    chit = root / "shaders/pathtracer/closesthit.rchit";
    original = readText(chit);
    env = {{"WB_ROOT", root.string()},
           {"WB_SHADER_CACHE_DIR", (root / "shader_cache").string()},
           {"DISPLAY", display}};
    if (ownMesaCache) env["MESA_SHADER_CACHE_DIR"] = (root / "shader_cache/mesa").string();
  }

  // A real code change of the closest-hit shader (a different constant), so that the driver really builds a
  // new pipeline: the file of edit `i`, for the script to copy over the watched one.
  fs::path edit(int i) const {
    const std::string text = closestHitEdit(original, i);
    const fs::path p = root / ("edit" + std::to_string(i) + ".rchit");
    writeFileAtomically(p, text, "bench window");
    return p;
  }
};

// Runs the window (default size, as the README's command opens it) with a script; `during` runs meanwhile
// (synthetic input). Throws with the log when it fails.
void runWindow(const PrivateRoot& pr, const std::string& script, const std::vector<std::string>& extra,
               const fs::path& log, const std::function<void(ChildProcess&)>& during = {}) {
  const fs::path scriptFile = pr.root / "script.txt";
  writeFileAtomically(scriptFile, script, "bench window");
  std::vector<std::string> args = {"--script", scriptFile.string()};
  args.insert(args.end(), extra.begin(), extra.end());
  auto child = ChildProcess::spawn(selfExecutable(), args, pr.env, log.string());
  try {
    if (during) during(child);
  } catch (...) {
    child.terminate();
    throw;
  }
  if (!waitFor([&] { return child.exited(); }, 3600)) {
    child.terminate();
    throw std::runtime_error("bench window: the window did not finish its script within an hour");
  }
  if (child.exitStatus != 0)
    throw std::runtime_error("bench window: the window exited with status " +
                             std::to_string(child.exitStatus) + ":\n" + readText(log));
}

// Paths per second of the headless path tracer at the window's trace size, after a warm-up; `denoise` as the
// window's setting (the denoiser's inputs are then written with every sample, as in the window).
double headlessPathsPerSecond(uint32_t w, uint32_t h, bool denoise, int samples, const std::string& device,
                              json& info) {
  render::SessionOptions o;
  o.scenePath = defaultScenePath().string();
  o.settings.width = w;
  o.settings.height = h;
  o.settings.denoise = denoise;
  o.context.deviceName = device;
  o.quiet = true;
  render::RenderSession s(o);
  info["device"] = s.context().deviceName();
  info["driver"] = s.context().driverInfo();
  s.render(2);  // the driver compiles the pipeline at its first trace
  const double seconds = s.render(uint32_t(samples));
  return double(w) * h * samples / seconds;  // one camera path per pixel and sample
}

struct EditTimes {
  std::vector<double> toFirstFrame, pipelineBuild, compile;
};

EditTimes editTimes(const json& stats, size_t first, size_t count) {
  EditTimes t;
  const auto& r = stats["reloads"];
  for (size_t i = first; i < std::min(r.size(), first + count); ++i) {
    if (!r[i]["ok"].get<bool>() || !r[i]["edit_to_first_frame_ms"].is_number()) continue;
    t.toFirstFrame.push_back(r[i]["edit_to_first_frame_ms"].get<double>());
    t.pipelineBuild.push_back(r[i]["pipeline_ms"].get<double>());
    t.compile.push_back(r[i]["compile_ms"].get<double>());
  }
  return t;
}

std::string editScript(const PrivateRoot& pr, int first, int count) {
  std::string s;
  for (int i = first; i < first + count; ++i) {
    s += "copy " + pr.edit(i).string() + " " + pr.chit.string() + "\nwait_reload 300\nframes 3\nsleep 1\n";
  }
  return s;
}

// Clicks on real widgets while the image converges, each timed from just before xdotool starts to the end of
// the frame that drew its effect (the window's click_screen_ns, on the same steady clock), and checked in the
// state the window reports after it: the "preview after changes" checkbox, the tonemap combo and one of its
// items in turn, then points of the image (the inspector's pixel) for the last quarter of the clicks. A click
// whose effect is missing is lost; a click the window never draws fails the run (its script's wait_clicks
// times out).
struct ClickFigures {
  std::vector<double> ms;
  int sent = 0, lost = 0;
  json perClick = json::array();  // what each click hit, its time to the screen, whether it landed
};

ClickFigures clickSession(const PrivateRoot& pr, int clicks, const std::vector<std::string>& deviceArgs,
                          const fs::path& log, const std::string& display) {
  auto statsFile = [&](int i) { return pr.root / ("clicks" + std::to_string(i) + ".json"); };
  std::string script = "wait_samples 1 1800\nsleep 2\nstats " + statsFile(0).string() + "\n";
  for (int i = 1; i <= clicks; ++i)
    script += "wait_clicks " + std::to_string(i) + " 120\nframes 2\nstats " + statsFile(i).string() + "\n";
  script += "quit\n";
  ClickFigures f;
  const int imageClicks = std::max(1, clicks / 4);
  runWindow(pr, script, deviceArgs, log, [&](ChildProcess& child) {
    json last;
    std::string chosenTonemap;
    for (int i = 0; i < clicks; ++i) {
      if (!waitFor([&] { return fs::exists(statsFile(i)); }, 1800, &child))
        throw std::runtime_error("bench window: the session ended before click " + std::to_string(i + 1) +
                                 ": " + readText(log));
      last = readJson(statsFile(i));
      // The window is back to converging untouched (it presents about once a second) before the next click.
      std::this_thread::sleep_for(std::chrono::milliseconds(1500));
      const auto& widgets = last["widgets"];
      auto centre = [&](const std::string& name) {
        if (!widgets.contains(name))
          throw std::runtime_error("bench window: no widget '" + name + "' on screen: " + widgets.dump());
        const auto& r = widgets[name];
        return std::vector<std::string>{std::to_string(int(r[0].get<double>() + r[2].get<double>() / 2)),
                                        std::to_string(int(r[1].get<double>() + r[3].get<double>() / 2))};
      };
      std::vector<std::string> at;
      // The widgets in turn, then the image: a pick opens the Inspect section and scrolls the panel to it,
      // so the widgets go first.
      const int kind = i < clicks - imageClicks ? i % 3 : 3;
      switch (kind) {
        case 0:
          at = centre("preview");
          break;
        case 1:
          at = centre("param.tonemap");
          break;
        case 2:
          chosenTonemap = last["parameters"]["tonemap"] == "aces" ? "reinhard" : "aces";
          at = widgets.contains("param.tonemap." + chosenTonemap) ? centre("param.tonemap." + chosenTonemap)
                                                                  : centre("param.tonemap");
          break;
        default: {
          // A point of the image, another each time.
          const auto& r = widgets["image"];
          const double fx = 0.2 + 0.15 * double((clicks - i) % 4);
          at = {std::to_string(int(r[0].get<double>() + fx * r[2].get<double>())),
                std::to_string(int(r[1].get<double>() + 0.6 * r[3].get<double>()))};
        }
      }
      std::vector<std::string> args = {"mousemove", at[0], at[1], "click", "1"};
      const int64_t sent =
          std::chrono::duration_cast<std::chrono::nanoseconds>(Clock::now().time_since_epoch()).count();
      auto xdotool =
          ChildProcess::spawn("xdotool", args, {{"DISPLAY", display}}, (pr.root / "xdotool.log").string());
      if (xdotool.wait() != 0)
        throw std::runtime_error("bench window: xdotool failed: " + readText(pr.root / "xdotool.log"));
      ++f.sent;
      if (!waitFor([&] { return fs::exists(statsFile(i + 1)); }, 1800, &child))
        throw std::runtime_error("bench window: click " + std::to_string(i + 1) +
                                 " never reached the screen: " + readText(log));
      const json after = readJson(statsFile(i + 1));
      f.ms.push_back(double(after["click_screen_ns"][size_t(i)].get<int64_t>() - sent) / 1e6);
      bool landed = false;
      switch (kind) {
        case 0:
          landed = after["preview_enabled"] != last["preview_enabled"];
          break;
        case 1:
          landed = after["widgets"].contains("param.tonemap.aces");
          break;
        case 2:
          landed = after["parameters"]["tonemap"] == chosenTonemap;
          break;
        default:
          landed = after["inspect_pixel"].is_array() && after["inspect_pixel"] != last["inspect_pixel"];
      }
      f.lost += landed ? 0 : 1;
      static const char* kWhat[] = {"checkbox", "combo", "combo item", "image"};
      // The part of it the click waited for the window's loop to take it (a trace or a frame in flight).
      const auto& events = after["click_event_ns"];
      const double toEvent =
          events.size() > size_t(i) ? double(events[size_t(i)].get<int64_t>() - sent) / 1e6 : -1.0;
      f.perClick.push_back(
          {{"what", kWhat[kind]}, {"ms", f.ms.back()}, {"to_event_ms", toEvent}, {"landed", landed}});
    }
  });
  return f;
}

void putClickFigures(json& result, const ClickFigures& f, const std::string& suffix) {
  result["click_to_screen_p50_ms" + suffix] = median(f.ms);
  result["click_to_screen_p95_ms" + suffix] = percentile(f.ms, 0.95);
  result["click_to_screen_max_ms" + suffix] = *std::max_element(f.ms.begin(), f.ms.end());
  result["clicks_sent" + suffix] = f.sent;
  result["clicks_lost" + suffix] = f.lost;
  result["clicks" + suffix] = f.perClick;
}

}  // namespace

int windowBenchSteps(const WindowBenchOptions& o) {
  const bool clicks = o.clicks > 0;
  return o.rounds + 1 + (o.underLoad ? 1 : 0) + (clicks ? 1 : 0) + (clicks && o.underLoad ? 1 : 0);
}

json benchWindow(const WindowBenchOptions& o, const fs::path& work, bool ownMesaCache,
                 StepProgress& progress) {
  BenchDisplay display(work);
  json result;
  result["display"] =
      display.started() ? "Xvfb " + display.name() + " (started by the bench)" : display.name();
  const std::vector<std::string> deviceArgs =
      o.device.empty() ? std::vector<std::string>{} : std::vector<std::string>{"--device", o.device};

  // 1. Trace rate: the window converging untouched against headless rendering at the same size, alternating.
  // Both are timed once started: the headless session after its warm-up samples, the window after two
  // samples and its first denoised view (the denoiser's first dispatch compiles it on a lazy driver).

  std::vector<double> windowRates, headlessRates, ratios;
  uint32_t traceW = 0, traceH = 0;
  json windowInfo;
  for (int round = 0; round < o.rounds; ++round) {
    progress.step("window trace rate against headless, round " + std::to_string(round + 1) + "/" +
                  std::to_string(o.rounds));
    PrivateRoot pr(work, "rate", display.name(), ownMesaCache);
    const fs::path a = pr.root / "a.json", b = pr.root / "b.json";
    runWindow(pr,
              "wait_samples 2 900\nwait_denoised 900\nstats " + a.string() + "\nwait_samples +" +
                  std::to_string(o.samples) + " 1800\nstats " + b.string() + "\nquit\n",
              deviceArgs, work / "window_rate.log");
    const json ja = readJson(a), jb = readJson(b);
    if (ja["resets"] != jb["resets"]) throw std::runtime_error("bench window: the accumulation restarted");
    const double paths = jb["paths_traced"].get<double>() - ja["paths_traced"].get<double>();
    const double secs = jb["seconds_since_reset"].get<double>() - ja["seconds_since_reset"].get<double>();
    windowRates.push_back(paths / secs);
    traceW = jb["trace_width"].get<uint32_t>();
    traceH = jb["trace_height"].get<uint32_t>();
    windowInfo = {{"window_size", std::to_string(jb["window_width"].get<int>()) + "x" +
                                      std::to_string(jb["window_height"].get<int>())},
                  {"trace_size", std::to_string(traceW) + "x" + std::to_string(traceH)},
                  {"present_mode", jb["present_mode"]},
                  {"trace_budget_ms", jb["trace_budget_ms"]}};
    const bool denoise = jb["parameters"]["denoise"].get<bool>();
    windowInfo["denoise"] = denoise;
    headlessRates.push_back(headlessPathsPerSecond(traceW, traceH, denoise, o.samples, o.device, result));
    ratios.push_back(windowRates.back() / headlessRates.back());
  }
  result["window"] = windowInfo;
  result["window_paths_per_second"] = median(windowRates);
  result["headless_paths_per_second"] = median(headlessRates);
  result["window_vs_headless_paths_ratio"] = median(ratios);
  result["window_vs_headless_paths_ratio_per_round"] = ratios;

  // 2. Edits, five quick saves, a mode switch and key taps, in one window session on an idle machine.
  progress.step("window edits, quick saves, mode switch, key taps");
  PrivateRoot pr(work, "live", display.name(), ownMesaCache);
  const fs::path stats = pr.root / "stats.json", before = pr.root / "taps_before.json",
                 after = pr.root / "taps_after.json", go = pr.root / "go";
  std::string script = "wait_samples 2 900\nsleep 2\n" + editScript(pr, 0, o.edits);
  // Five saves a second apart: only the last one's content needs to reach the screen.
  const int quick = o.edits;
  script += "sleep 2\n";
  for (int i = 0; i < 5; ++i) {
    script += "copy " + pr.edit(quick + i).string() + " " + pr.chit.string() + "\n";
    script += i < 4 ? "sleep 1\n" : "wait_reload 300\nframes 3\nsleep 2\n";
  }
  script += "switch_mode hybrid\nwait_mode 600\nframes 5\nswitch_mode pathtrace\nwait_mode 600\nframes 3\n";
  const bool taps = o.keyTaps > 0 && !findProgram("xdotool").empty();
  if (taps) {
    // Frames of about half a second: each tap falls between two polls of the keyboard.
    script += "set budget_ms 300\nframes 3\nstats " + before.string() + "\nwait_file " + go.string() +
              " 600\nframes 3\nset budget_ms 60\n";
    script += "stats " + after.string() + "\n";
  }
  script += "stats " + stats.string() + "\nquit\n";
  runWindow(pr, script, deviceArgs, work / "window_live.log", [&](ChildProcess& child) {
    if (!taps) return;
    if (!waitFor([&] { return fs::exists(before); }, 3600, &child))
      throw std::runtime_error("bench window: the session ended before the key taps: " +
                               readText(work / "window_live.log"));
    std::vector<std::string> args = {"mousemove", "900", "300", "key", "--delay", "30"};
    for (int i = 0; i < o.keyTaps; ++i) args.push_back("Tab");
    auto xdotool =
        ChildProcess::spawn("xdotool", args, {{"DISPLAY", display.name()}}, (work / "xdotool.log").string());
    if (xdotool.wait() != 0)
      throw std::runtime_error("bench window: xdotool failed: " + readText(work / "xdotool.log"));
    writeFileAtomically(go, "go\n", "bench window");
  });
  const json live = readJson(stats);
  const EditTimes idle = editTimes(live, 0, size_t(o.edits));
  std::vector<double> perEdit;
  for (size_t i = 0; i < idle.toFirstFrame.size(); ++i)
    perEdit.push_back(idle.toFirstFrame[i] / idle.pipelineBuild[i]);
  const double buildIdle = median(idle.pipelineBuild);
  result["edits"] = idle.toFirstFrame.size();
  result["edit_to_first_frame_ms_p50"] = median(idle.toFirstFrame);
  result["edit_to_first_frame_ms_p95"] = percentile(idle.toFirstFrame, 0.95);
  result["pipeline_build_ms_p50"] = buildIdle;
  result["compile_ms_p50"] = median(idle.compile);
  result["edit_to_first_frame_vs_pipeline_build_p50"] = median(perEdit);
  // The quick saves: the reload after the fifth save is the last in the history.
  const auto& reloads = live["reloads"];
  if (reloads.size() > size_t(o.edits) && reloads.back()["edit_to_first_frame_ms"].is_number()) {
    const double last = reloads.back()["edit_to_first_frame_ms"].get<double>();
    result["superseded_edits_last_to_screen_ms"] = last;
    result["superseded_edits_reloads_installed"] = reloads.size() - size_t(o.edits);
    result["superseded_edits_last_to_screen_vs_single"] = last / median(idle.toFirstFrame);
  }
  const auto& switches = live["mode_switches"];
  if (!switches.empty()) {
    result["mode_switch_longest_frame_ms"] = switches[0]["longest_frame_ms"];
    result["mode_switch_prepare_ms"] = switches[0]["prepare_ms"];
    result["mode_switch_back_longest_frame_ms"] =
        switches.size() > 1 ? switches[1]["longest_frame_ms"] : json();
  }
  result["frame_ms_p50"] = live["frame_ms"]["p50"];
  if (taps) {
    const int handled =
        readJson(after)["key_presses"].get<int>() - readJson(before)["key_presses"].get<int>();
    result["key_taps_sent"] = o.keyTaps;
    result["key_taps_lost"] = o.keyTaps - handled;
  } else {
    result["key_taps_lost"] = nullptr;
    result["key_taps_note"] = "not measured: xdotool is missing (scripts/setup.sh installs it)";
  }

  // 3. Clicks while the image converges.
  const bool clicks = o.clicks > 0 && !findProgram("xdotool").empty();
  if (clicks) {
    progress.step("window clicks while the image converges");
    PrivateRoot cr(work, "clicks", display.name(), ownMesaCache);
    putClickFigures(result,
                    clickSession(cr, o.clicks, deviceArgs, work / "window_clicks.log", display.name()), "");
  } else if (o.clicks > 0) {
    result["clicks_lost"] = nullptr;
    result["clicks_note"] = "not measured: xdotool is missing (scripts/setup.sh installs it)";
  }

  // 4. The same edits and clicks with two busy loops in another session.
  if (o.underLoad) {
    progress.step("window edits with two busy loops in another session");
    PrivateRoot lr(work, "load", display.name(), ownMesaCache);
    const fs::path loadStats = lr.root / "stats.json";
    BusyLoops busy(work);
    runWindow(lr,
              "wait_samples 2 1800\nsleep 2\n" + editScript(lr, 0, o.edits) + "stats " + loadStats.string() +
                  "\nquit\n",
              deviceArgs, work / "window_load.log");
    const EditTimes load = editTimes(readJson(loadStats), 0, size_t(o.edits));
    std::vector<double> loadPerEdit;
    for (size_t i = 0; i < load.toFirstFrame.size(); ++i)
      loadPerEdit.push_back(load.toFirstFrame[i] / load.pipelineBuild[i]);
    result["under_load_edits"] = load.toFirstFrame.size();
    result["edit_to_first_frame_ms_under_load_p50"] = median(load.toFirstFrame);
    result["pipeline_build_ms_under_load_p50"] = median(load.pipelineBuild);
    // As the idle ratio: each edit against the driver's build of the same reload, here under the same load.
    result["edit_to_first_frame_vs_pipeline_build_under_load_p50"] = median(loadPerEdit);
    // Against the driver's build on the idle machine: what the user waits for, loaded, relative to the least
    // the driver needs (its single-threaded JIT alone slows down under the load).
    result["edit_to_first_frame_under_load_vs_idle_pipeline_build_p50"] =
        median(load.toFirstFrame) / buildIdle;
    if (clicks) {
      progress.step("window clicks with two busy loops in another session");
      PrivateRoot cr(work, "clicks_load", display.name(), ownMesaCache);
      putClickFigures(result,
                      clickSession(cr, o.clicks, deviceArgs, work / "window_clicks_load.log", display.name()),
                      "_under_load");
    }
  }
  result["what"] =
      "window: the README's run command (default window size) under a script, on the display or on Xvfb, "
      "its rate timed from its first denoised view (two samples at least) over the next samples; "
      "headless: the path tracer in this process at the window's trace size and denoise setting (with "
      "denoise on, the denoiser's inputs are written every sample on both sides; the window's own denoiser "
      "runs count against the window); ratios are medians of rounds that alternate the two. Edit: a "
      "closest-hit constant changed; first frame: the first frame drawn with "
      "the new pipeline; pipeline build: the driver's build of it (warm-up included), from the same reload. "
      "Click to screen: from just before xdotool starts (its start-up included) to the end of the frame that "
      "drew the click's effect, clicks 1.5 s apart while the image converges.";
  return result;
}

}  // namespace wb::app
