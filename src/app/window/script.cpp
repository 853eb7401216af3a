#include "app/window/script.h"

#include <cstdio>
#include <optional>
#include <set>
#include <sstream>
#include <stdexcept>

#include "common/file_io.h"
#include "common/numbers.h"
#include "common/printable.h"

namespace wb::app {
namespace {

const std::set<std::string> kCommands = {
    "frames",    "set",         "screenshot",   "save",         "stats",        "copy",
    "orbit",     "wait_reload", "wait_samples", "reset_camera", "reset",        "reload",
    "quit",      "resize",      "wait_file",    "inspect",      "sleep",        "switch_mode",
    "wait_mode", "ab_revert",   "ab_accept",    "wait_clicks",  "wait_denoised"};

// The commands that wait for an event (a reload, samples, a file, time) rather than for drawn frames.
bool isEventWait(const std::string& cmd) {
  return cmd == "wait_reload" || cmd == "wait_samples" || cmd == "wait_file" || cmd == "sleep" ||
         cmd == "wait_mode" || cmd == "wait_clicks" || cmd == "wait_denoised";
}

// Arguments are checked when the script is read (Script::addLine): every number here is a finite decimal.
double numberArg(const std::vector<std::string>& w, size_t i, double fallback, const std::string& where) {
  if (i >= w.size()) return fallback;
  const auto v = parseDecimal(w[i]);
  if (!v) throw std::runtime_error(where + ": '" + w[i] + "' is not a finite decimal number");
  return *v;
}

// A script line as messages show it: at most 80 characters of it, control characters made visible.
std::string shownText(const std::string& text) {
  return printableExcerpt(text, 80);
}

// A number argument in [lo, hi] (an integer where `integer`), or the reason it is not.
void checkNumber(const std::vector<std::string>& w, size_t i, const std::string& what, double lo, double hi,
                 bool integer, const std::string& where) {
  if (i >= w.size()) return;
  const auto v = integer ? std::optional<double>() : parseDecimal(w[i]);
  const auto u = integer ? parseDecimalUnsigned(w[i]) : std::optional<uint64_t>();
  const double value = integer ? (u ? double(*u) : -1.0) : v.value_or(lo - 1.0);
  if ((integer && !u) || (!integer && !v) || value < lo || value > hi) {
    char range[96];
    std::snprintf(range, sizeof range, integer ? "%.0f .. %.0f" : "%g .. %g", lo, hi);
    throw std::runtime_error(where + ": " + w[0] + ": " + what + " must be " +
                             (integer ? "a whole decimal number " : "a decimal number ") + range + ", got '" +
                             shownText(w[i]) + "'");
  }
}

// The longest wait a script may ask for (about 11 days): longer is a typo, and still a finite time.
constexpr double kMaxWaitSeconds = 1e6;

}  // namespace

Script Script::fromFile(const std::filesystem::path& path) {
  std::string why;
  // A regular file only: a named pipe would block the window before it opens, a folder is no script.
  const auto text = readRegularFile(path, &why, uint64_t{64} << 20);
  if (!text) throw std::runtime_error("--script: cannot read '" + path.string() + "': " + why);
  Script s;
  std::istringstream f(*text);
  std::string line;
  int n = 0;
  while (std::getline(f, line)) s.addLine(line, path.string() + ":" + std::to_string(++n));
  return s;
}

void Script::addLine(const std::string& line, const std::string& where) {
  std::istringstream ss(line);
  Command c;
  c.where = where;
  for (std::string w; ss >> w;) c.words.push_back(w);
  if (c.words.empty() || c.words[0][0] == '#') return;
  if (!kCommands.count(c.words[0]))
    throw std::runtime_error(where + ": unknown command '" + shownText(c.words[0]) + "'");
  const std::string& cmd = c.words[0];
  const size_t need = cmd == "set" || cmd == "copy" || cmd == "orbit" || cmd == "resize" ? 3
                      : cmd == "frames" || cmd == "screenshot" || cmd == "save" || cmd == "stats" ||
                              cmd == "wait_samples" || cmd == "wait_file" || cmd == "inspect" ||
                              cmd == "sleep" || cmd == "switch_mode" || cmd == "wait_clicks"
                          ? 2
                          : 1;
  if (c.words.size() < need) throw std::runtime_error(where + ": '" + cmd + "' needs more arguments");
  if (cmd == "set" && c.words.size() > 3) {  // values with spaces (paths)
    for (size_t i = 3; i < c.words.size(); ++i) c.words[2] += " " + c.words[i];
    c.words.resize(3);
  }
  // Every count and duration is finite and in range: a script that never ends is refused when read.
  const auto& w = c.words;
  if (cmd == "frames") checkNumber(w, 1, "N", 1, 1e9, true, where);
  if (cmd == "wait_samples") {
    // +N: relative to the samples when the wait begins (the number is checked without its sign).
    if (w[1].size() > 1 && w[1][0] == '+') {
      auto plain = w;
      plain[1] = w[1].substr(1);
      checkNumber(plain, 1, "+N", 0, UINT32_MAX, true, where);
    } else {
      checkNumber(w, 1, "N", 0, UINT32_MAX, true, where);
    }
  }
  if (cmd == "wait_reload" || cmd == "wait_mode" || cmd == "wait_denoised")
    checkNumber(w, 1, "SECONDS", 1e-3, kMaxWaitSeconds, false, where);
  if (cmd == "wait_clicks") checkNumber(w, 1, "N", 0, 1e9, true, where);
  if (cmd == "wait_samples" || cmd == "wait_file" || cmd == "wait_clicks")
    checkNumber(w, 2, "SECONDS", 1e-3, kMaxWaitSeconds, false, where);
  if (cmd == "sleep") checkNumber(w, 1, "SECONDS", 0, kMaxWaitSeconds, false, where);
  if (cmd == "orbit") {
    checkNumber(w, 1, "DX", -1e6, 1e6, false, where);
    checkNumber(w, 2, "DY", -1e6, 1e6, false, where);
  }
  if (cmd == "resize") {
    checkNumber(w, 1, "W", 64, 16384, true, where);
    checkNumber(w, 2, "H", 64, 16384, true, where);
  }
  commands_.push_back(std::move(c));
}

std::vector<ScriptOutput> Script::outputs() const {
  std::vector<ScriptOutput> out;
  for (const auto& c : commands_) {
    const std::string& cmd = c.words[0];
    const std::string what = c.where + ": " + cmd;
    if (cmd == "save") {
      for (const char* ext : {".png", ".exr", ".json"}) out.push_back({c.words[1] + ext, what});
    } else if (cmd == "screenshot" || cmd == "stats" || cmd == "inspect") {
      out.push_back({c.words[1], what});
    }
  }
  return out;
}

bool Script::waitingForEvent() const {
  return waiting_ && next_ < commands_.size() && isEventWait(commands_[next_].words[0]);
}

bool Script::step(ScriptHost& host, bool eventsOnly) {
  using clock = std::chrono::steady_clock;
  while (next_ < commands_.size()) {
    const Command& c = commands_[next_];
    const auto& w = c.words;
    const std::string& cmd = w[0];
    if (eventsOnly && !isEventWait(cmd)) return true;  // the next drawn frame runs it
    if (cmd == "frames") {
      if (!waiting_) {
        waiting_ = true;
        framesLeft_ = uint64_t(numberArg(w, 1, 1, c.where));
      }
      if (framesLeft_ > 0) {
        --framesLeft_;
        return true;
      }
    } else if (cmd == "wait_reload") {
      if (!waiting_) {
        waiting_ = true;
        reloadsAtStart_ = host.reloadCount();
        deadline_ = clock::now() + std::chrono::milliseconds(int64_t(1000 * numberArg(w, 1, 20, c.where)));
      }
      if (host.reloadCount() == reloadsAtStart_) {
        if (clock::now() < deadline_) return true;
        throw std::runtime_error(c.where + ": wait_reload: no shader reload within " +
                                 std::to_string(numberArg(w, 1, 20, c.where)) + " s");
      }
    } else if (cmd == "wait_samples") {
      const bool relative = w[1][0] == '+';
      if (!waiting_) {
        waiting_ = true;
        samplesAtStart_ = host.samples();
        deadline_ = clock::now() + std::chrono::milliseconds(int64_t(1000 * numberArg(w, 2, 60, c.where)));
      }
      const uint32_t want = uint32_t(numberArg({relative ? w[1].substr(1) : w[1]}, 0, 1, c.where)) +
                            (relative ? samplesAtStart_ : 0u);
      if (host.samples() < want) {
        if (clock::now() < deadline_) return true;
        throw std::runtime_error(c.where + ": wait_samples: " + std::to_string(host.samples()) + " of " +
                                 std::to_string(want) + " samples after " +
                                 std::to_string(numberArg(w, 2, 60, c.where)) + " s");
      }
    } else if (cmd == "wait_denoised") {
      if (!waiting_) {
        waiting_ = true;
        deadline_ = clock::now() + std::chrono::milliseconds(int64_t(1000 * numberArg(w, 1, 60, c.where)));
      }
      if (!host.denoisedAsAsked()) {
        if (clock::now() < deadline_) return true;
        throw std::runtime_error(c.where + ": wait_denoised: the denoised image is not shown after " +
                                 std::to_string(numberArg(w, 1, 60, c.where)) + " s");
      }
    } else if (cmd == "wait_file") {
      if (!waiting_) {
        waiting_ = true;
        deadline_ = clock::now() + std::chrono::milliseconds(int64_t(1000 * numberArg(w, 2, 60, c.where)));
      }
      std::error_code ec;
      if (!std::filesystem::exists(w[1], ec)) {
        if (clock::now() < deadline_) return true;
        throw std::runtime_error(c.where + ": wait_file: no '" + w[1] + "' after " +
                                 std::to_string(numberArg(w, 2, 60, c.where)) + " s");
      }
    } else if (cmd == "wait_clicks") {
      if (!waiting_) {
        waiting_ = true;
        deadline_ = clock::now() + std::chrono::milliseconds(int64_t(1000 * numberArg(w, 2, 60, c.where)));
      }
      const uint64_t want = uint64_t(numberArg(w, 1, 1, c.where));
      if (host.clicksPresented() < want) {
        if (clock::now() < deadline_) return true;
        throw std::runtime_error(c.where + ": wait_clicks: " + std::to_string(host.clicksPresented()) +
                                 " of " + std::to_string(want) + " clicks on screen after " +
                                 std::to_string(numberArg(w, 2, 60, c.where)) + " s");
      }
    } else if (cmd == "sleep") {
      if (!waiting_) {
        waiting_ = true;
        deadline_ = clock::now() + std::chrono::milliseconds(int64_t(1000 * numberArg(w, 1, 0, c.where)));
      }
      if (clock::now() < deadline_) return true;
    } else if (cmd == "wait_mode") {
      if (!waiting_) {
        waiting_ = true;
        deadline_ = clock::now() + std::chrono::milliseconds(int64_t(1000 * numberArg(w, 1, 120, c.where)));
      }
      if (host.modeSwitchPending()) {
        if (clock::now() < deadline_) return true;
        throw std::runtime_error(c.where + ": wait_mode: the mode switch is not done after " +
                                 std::to_string(numberArg(w, 1, 120, c.where)) + " s");
      }
    } else {
      try {
        if (cmd == "set") {
          host.scriptSet(w[1], w[2]);
        } else if (cmd == "screenshot") {
          // The frame drawn next is captured: the commands after this one wait for it.
          host.scriptScreenshot(w[1]);
          waiting_ = false;
          ++next_;
          return true;
        } else if (cmd == "switch_mode") {
          host.scriptSwitchMode(w[1]);
        } else if (cmd == "save") {
          host.scriptSave(w[1]);
        } else if (cmd == "stats") {
          host.scriptStats(w[1]);
        } else if (cmd == "inspect") {
          host.scriptInspect(w[1]);
        } else if (cmd == "copy") {
          std::filesystem::copy_file(w[1], w[2], std::filesystem::copy_options::overwrite_existing);
        } else if (cmd == "resize") {
          const double rw = numberArg(w, 1, 0, c.where), rh = numberArg(w, 2, 0, c.where);
          if (rw < 64 || rh < 64 || rw > 16384 || rh > 16384)
            throw std::runtime_error("resize: expected W H of 64..16384");
          host.scriptResize(int(rw), int(rh));
        } else if (cmd == "orbit") {
          host.scriptOrbit(float(numberArg(w, 1, 0, c.where)), float(numberArg(w, 2, 0, c.where)));
        } else {
          host.scriptCommand(cmd);
        }
      } catch (const std::exception& e) {
        throw std::runtime_error(c.where + ": " + e.what());
      }
    }
    waiting_ = false;
    ++next_;
  }
  return false;
}

}  // namespace wb::app
