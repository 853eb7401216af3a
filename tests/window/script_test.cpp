// Scripted sessions (app/window/script.h) against a fake window: a screenshot captures the frame before the
// commands after it apply, and a wait that times out fails the script naming the line.
#include <gtest/gtest.h>

#include <chrono>
#include <thread>

#include "app/window/script.h"

namespace {

struct FakeHost : wb::app::ScriptHost {
  std::vector<std::string> log;
  uint32_t sampleCount = 0;
  size_t reloads = 0;
  void scriptSet(const std::string& n, const std::string& v) override { log.push_back("set " + n + " " + v); }
  void scriptScreenshot(const std::string& p) override { log.push_back("screenshot " + p); }
  void scriptSave(const std::string& b) override { log.push_back("save " + b); }
  void scriptStats(const std::string& p) override { log.push_back("stats " + p); }
  void scriptOrbit(float, float) override { log.push_back("orbit"); }
  void scriptResize(int, int) override { log.push_back("resize"); }
  void scriptCommand(const std::string& n) override { log.push_back(n); }
  size_t reloadCount() const override { return reloads; }
  uint32_t samples() const override { return sampleCount; }
};

}  // namespace

TEST(Script, AScreenshotIsTakenBeforeTheNextCommandsApply) {
  wb::app::Script s;
  s.addLine("set exposure 1", "t:1");
  s.addLine("screenshot a.png", "t:2");
  s.addLine("set exposure 2", "t:3");
  FakeHost host;
  EXPECT_TRUE(s.step(host));  // a frame is drawn (and captured) with exposure 1
  EXPECT_EQ(host.log, (std::vector<std::string>{"set exposure 1", "screenshot a.png"}));
  EXPECT_FALSE(s.step(host));
  EXPECT_EQ(host.log.back(), "set exposure 2");
}

TEST(Script, AWaitThatTimesOutFailsTheScript) {
  for (const char* line : {"wait_samples 5 0.05", "wait_reload 0.05"}) {
    wb::app::Script s;
    s.addLine(line, "t:7");
    FakeHost host;
    host.sampleCount = 1;
    bool threw = false;
    // Waits for the deadline to pass (the event), however long that takes on a busy machine.
    for (int i = 0; i < 100000 && !threw; ++i) {
      try {
        if (!s.step(host)) break;
      } catch (const std::runtime_error& e) {
        threw = true;
        EXPECT_NE(std::string(e.what()).find("t:7"), std::string::npos) << e.what();
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
    EXPECT_TRUE(threw) << line << " timed out silently";
  }
  wb::app::Script ok;
  ok.addLine("wait_samples 2 600", "t:1");
  FakeHost host;
  EXPECT_TRUE(ok.step(host));
  host.sampleCount = 2;
  EXPECT_FALSE(ok.step(host));
}
