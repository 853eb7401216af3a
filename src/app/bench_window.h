// `bench --only window`: the live window measured as a user meets it: its trace rate
// against headless rendering at the same size, edit to first new frame against the driver's pipeline build
// (idle, and with two busy loops in another session), five quick saves, a mode switch, quick key taps, and
// clicks on real widgets timed to the screen while the image converges (idle and under the same load).
// The window runs as a child process on the display, or on an Xvfb server of its own when there is none.
#pragma once
#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>

namespace wb::app {

class StepProgress;

struct WindowBenchOptions {
  int rounds = 3;    // throughput: window and headless runs, alternating
  int samples = 8;   // throughput: samples timed per run (after two to warm up)
  int edits = 5;     // edits timed, idle and under load
  int keyTaps = 10;  // Tab taps sent within slow frames (even: the panel ends as it began)
  int clicks = 12;   // synthetic clicks on widgets and the image while the image converges (0: none)
  bool underLoad = true;
  std::string device;  // Vulkan device name (substring) for the headless runs and the window
};

// What the bench sections share: a whole file's text ("" when unreadable), and the closest-hit source with
// edit `i` made (a different constant, so that the driver really builds a new pipeline; throws when the
// source has no such constant).
std::string readText(const std::filesystem::path& p);
std::string closestHitEdit(const std::string& original, int i);

// The steps benchWindow announces on `progress`.
int windowBenchSteps(const WindowBenchOptions& o);
// Throws std::runtime_error when a run fails (its log is in the message).
nlohmann::json benchWindow(const WindowBenchOptions& o, const std::filesystem::path& work, bool ownMesaCache,
                           StepProgress& progress);

}  // namespace wb::app
