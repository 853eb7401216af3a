// Scripted sessions for tests and demos: one command per line, run at frame boundaries of the live window.
//   frames N                 render N frames
//   set NAME VALUE           a setting, as --set NAME=VALUE (see settingNamesHelp())
//   screenshot FILE.png      the window image (panel included) of the next frame, before later commands apply
//   save BASE                the render: BASE.png (tonemapped), BASE.exr (linear), BASE.json (parameters),
//                            written when the line runs (a failure ends the script with exit status 1)
//   stats FILE.json          the session's statistics now (samples, resets, shader errors, frame times)
//   copy SRC DST             copy a file (e.g. a broken shader over a watched one)
//   wait_reload [SECONDS]    render until the next shader reload is applied (default 20 s; past it the
//                            script fails: exit status 1 with the reason)
//   wait_samples N [SECONDS] render until N samples are accumulated (default 60 s; past it the script fails);
//                            +N: N more than when the wait begins
//   wait_denoised [SECONDS]  render until the image shown is the denoiser's output of the current image (paused:
//                            of all its samples; at once when denoise is off or a hybrid mode shows; default
//                            60 s, then fails)
//   wait_file PATH [SECONDS] render until PATH exists (another program's signal; default 60 s, then fails)
//   wait_clicks N [SECONDS]  render until N left clicks in all (since the window opened) are on screen: the
//                            frame that drew each click's effect finished (default 60 s, then fails)
//   sleep SECONDS            render for SECONDS of wall time (benchmarks pace edits with it; tests wait for
//                            events instead)
//   switch_mode NAME         switch the render mode as the panel does: the other mode's renderer is made off
//                            the frame loop while the current one keeps drawing; the script goes on at once
//   wait_mode [SECONDS]      render until a switch_mode is done (default 120 s; past it the script fails)
//   inspect FILE.json        the path inspector's records of the inspected pixel now (set inspect_pixel X,Y
//                            first), as `render --inspect-out` writes them plus the running estimate
//   orbit DX DY              drag the orbit camera by DX, DY pixels
//   resize W H               resize the window (the swapchain and the trace size follow)
//   reset_camera | reset | reload | quit
//   ab_revert | ab_accept          the A/B panel's Revert / Accept buttons
// Blank lines and lines starting with # are ignored.
#pragma once
#include <chrono>
#include <cstdint>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

namespace wb::app {

class ScriptHost {
 public:
  virtual ~ScriptHost() = default;
  virtual void scriptSet(const std::string& name, const std::string& value) = 0;
  virtual void scriptScreenshot(const std::string& path) = 0;
  virtual void scriptSave(const std::string& base) = 0;
  virtual void scriptStats(const std::string& path) = 0;
  virtual void scriptOrbit(float dx, float dy) = 0;
  virtual void scriptResize(int width, int height) = 0;
  virtual void scriptCommand(const std::string& name) = 0;  // reset_camera, reset, reload, quit, ab_*
  virtual void scriptInspect(const std::string& path) {
    (void)path;
    throw std::runtime_error("inspect: no path inspector here");
  }
  // Starts a mode switch that completes off the frame loop (switch_mode); modeSwitchPending() until it is
  // done.
  virtual void scriptSwitchMode(const std::string& mode) {
    (void)mode;
    throw std::runtime_error("switch_mode: no render modes here");
  }
  virtual bool modeSwitchPending() const { return false; }
  // Left clicks whose effect a finished frame drew, since the window opened (wait_clicks).
  virtual uint64_t clicksPresented() const { return 0; }
  virtual size_t reloadCount() const = 0;
  virtual uint32_t samples() const = 0;
  // The image shown is denoised as the settings ask (wait_denoised).
  virtual bool denoisedAsAsked() const { return true; }
};

// A file a script writes (save, screenshot, stats, inspect), and the line that writes it.
struct ScriptOutput {
  std::string path;
  std::string what;  // "file:line: save"
};

class Script {
 public:
  Script() = default;
  // Reads a regular file (a named pipe or a folder is refused, never waited on). Throws std::runtime_error
  // naming the file and line for unreadable files, unknown commands and arguments out of range.
  static Script fromFile(const std::filesystem::path& path);
  // Checks the line's command and arguments: counts and durations are finite decimal numbers in range
  // (frames at least 1; waits above 0 s; orbit within +-1e6 pixels).
  void addLine(const std::string& line, const std::string& where);
  // Every file the script writes, so that they can be checked before the session starts.
  std::vector<ScriptOutput> outputs() const;

  // Runs commands until one has to wait for frames. Call once per frame boundary. Returns false once every
  // command has run. Command failures throw std::runtime_error naming the script line. `eventsOnly` (between
  // drawn frames, where the window traces without presenting) checks the event waits and stops before any
  // other command: `frames N` counts drawn frames, and what a command acts on is what the last frame drew.
  bool step(ScriptHost& host, bool eventsOnly = false);
  bool finished() const { return next_ >= commands_.size(); }
  // Whether the current command waits for an event (a reload, samples, a file) rather than for frames: the
  // window may trace without presenting meanwhile.
  bool waitingForEvent() const;

 private:
  struct Command {
    std::vector<std::string> words;
    std::string where;  // file:line
  };
  std::vector<Command> commands_;
  size_t next_ = 0;
  // State of the waiting command.
  bool waiting_ = false;
  uint64_t framesLeft_ = 0;
  size_t reloadsAtStart_ = 0;
  uint32_t samplesAtStart_ = 0;
  std::chrono::steady_clock::time_point deadline_;
};

}  // namespace wb::app
