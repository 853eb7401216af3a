// The live workbench window as a user runs it: the real binary under xvfb-run on lavapipe, driven by
// --frames,
// --script and --stats. Checks what is presented (panel + image), accumulation resets, and shader hot reload
// with a broken edit.
#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>
#include <stb_image.h>

#include "../common/run_command.h"
#include "private_root.h"

namespace fs = std::filesystem;

namespace {

using wb::testing::CommandResult;
using wb::testing::privateRoot;

CommandResult runShell(const std::string& cmd) {
  return wb::testing::runCommand(cmd);
}

bool haveXvfb() {
  return std::string(WB_XVFB_RUN).size() > 0 && fs::exists(WB_XVFB_RUN);
}

// xvfb-run with its X authority file in a path of the test's own: xvfb-run then makes no temporary directory
// of its own, whose removal at exit can fail (exit status 5) when many of them start and stop at once.
// The files go when the test program ends.
std::string xvfbRun() {
  struct AuthFiles {
    std::vector<fs::path> paths;
    ~AuthFiles() {
      std::error_code ec;
      for (const auto& p : paths) fs::remove(p, ec);
    }
  };
  static AuthFiles files;
  const fs::path auth = fs::temp_directory_path() /
                        ("wb_xauth_" + std::to_string(::getpid()) + "_" + std::to_string(files.paths.size()));
  files.paths.push_back(auth);
  return std::string(WB_XVFB_RUN) + " -a -f " + auth.string() + " -s '-screen 0 1024x768x24' ";
}

// The workbench in a 320x240 window on a virtual display, under the validation layer (ctest sets
// WB_VALIDATION=1): a validation error makes the workbench exit with status 3.
// `limitSeconds` (> 0): the window is killed past it (a test of a hang enforces its own limit).
CommandResult runWindow(const std::string& args, const std::string& env = "", int limitSeconds = 0) {
  const std::string limit =
      limitSeconds > 0 ? "timeout -k 10 " + std::to_string(limitSeconds) + " " : std::string();
  return runShell(std::string(wb::testing::kOwnSession) + "env WB_VALIDATION=1 " + env + " " + limit +
                  xvfbRun() + WB_WORKBENCH_BIN + " --window 320x240 " + args);
}

// A closest-hit shader's text with a loop that never ends at the start of main (radiance only grows).
std::string withEndlessLoop(std::string text) {
  const auto body = text.find('{', text.find("void main()")) + 1;
  text.insert(body, "\n  while (payload.radiance.x >= 0.0) { payload.radiance.x += 1.0; }\n");
  return text;
}

// Mean brightness of the image area (right of the panel, above the status line) of a window screenshot.
double imageAreaMean(const fs::path& png, int panelWidth) {
  int w = 0, h = 0, n = 0;
  unsigned char* px = stbi_load(png.c_str(), &w, &h, &n, 4);
  if (!px) return -1;
  double sum = 0;
  size_t count = 0;
  for (int y = 0; y < h - 24; ++y) {
    for (int x = panelWidth + 4; x < w; ++x) {
      const unsigned char* p = px + 4 * (size_t(y) * w + x);
      sum += (p[0] + p[1] + p[2]) / 3.0;
      ++count;
    }
  }
  stbi_image_free(px);
  return count ? sum / double(count) : -1;
}

fs::path tempDir(const std::string& name) {
  fs::path d = fs::temp_directory_path() / ("wb_window_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

nlohmann::json readJson(const fs::path& p) {
  std::ifstream f(p);
  EXPECT_TRUE(f.good()) << p;
  return nlohmann::json::parse(f);
}

void writeFile(const fs::path& p, const std::string& text) {
  std::ofstream f(p);
  f << text;
}

std::string readFile(const fs::path& p) {
  std::ifstream f(p);
  return std::string(std::istreambuf_iterator<char>(f), {});
}

}  // namespace

#define REQUIRE_XVFB() \
  if (!haveXvfb()) GTEST_SKIP() << "xvfb-run not found"

TEST(Window, ScreenshotShowsPanelAndImage) {
  REQUIRE_XVFB();
  const auto dir = tempDir("shot");
  const auto png = dir / "window.png", stats = dir / "stats.json";
  auto r = runWindow("--frames 12 --screenshot " + png.string() + " --stats " + stats.string());
  ASSERT_EQ(r.code, 0) << r.output;
  ASSERT_TRUE(fs::exists(png)) << r.output;
  int w = 0, h = 0, n = 0;
  unsigned char* px = stbi_load(png.c_str(), &w, &h, &n, 4);
  ASSERT_NE(px, nullptr);
  EXPECT_EQ(w, 320);
  EXPECT_EQ(h, 240);
  const auto j = readJson(stats);
  const int panelWidth = 144;  // 45% of 320 (panels.cpp)
  // The panel: many pixels of ImGui's window background (0.11, 0.12, 0.14) -> (28, 31, 36).
  size_t panelBg = 0, panelPixels = 0;
  double imageSum = 0;
  size_t imagePixels = 0, imageBright = 0;
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      const unsigned char* p = px + 4 * (size_t(y) * w + x);
      if (x < panelWidth - 4) {
        ++panelPixels;
        panelBg += std::abs(p[0] - 28) <= 2 && std::abs(p[1] - 31) <= 2 && std::abs(p[2] - 36) <= 2;
      } else if (x > panelWidth + 4 && y < h - 24) {  // the image, above the status line
        ++imagePixels;
        imageSum += (p[0] + p[1] + p[2]) / 3.0;
        imageBright += (p[0] + p[1] + p[2]) > 60;
      }
    }
  }
  stbi_image_free(px);
  EXPECT_GT(double(panelBg) / double(panelPixels), 0.2) << "no ImGui panel background in the panel area";
  EXPECT_GT(imageSum / double(imagePixels), 20.0) << "the traced image is (nearly) black";
  EXPECT_GT(double(imageBright) / double(imagePixels), 0.3);
  EXPECT_EQ(j["frames"], 12);
  EXPECT_GT(j["samples"].get<int>() + (j["preview"].get<bool>() ? 1 : 0), 0);
  EXPECT_EQ(j["shader_error"], "");
  EXPECT_EQ(j["window_width"], 320);
  EXPECT_FALSE(fs::exists("imgui.ini"));
}

TEST(Window, ParameterChangeResetsAccumulationDisplayChangeDoesNot) {
  REQUIRE_XVFB();
  const auto dir = tempDir("reset");
  const auto script = dir / "script.txt";
  writeFile(script,
            "wait_samples 3 300\n"
            "stats " +
                (dir / "a.json").string() +
                "\n"
                "set exposure 1.5\nset tonemap reinhard\nset view albedo\n"
                "frames 4\n"
                "stats " +
                (dir / "b.json").string() +
                "\n"
                "set max_bounces 2\n"
                "frames 1\n"
                "stats " +
                (dir / "c.json").string() + "\n");
  auto r = runWindow("--script " + script.string());
  ASSERT_EQ(r.code, 0) << r.output;
  const auto a = readJson(dir / "a.json"), b = readJson(dir / "b.json"), c = readJson(dir / "c.json");
  ASSERT_GE(a["samples"].get<int>(), 3) << r.output;
  // Display-only changes: same accumulation, still growing.
  EXPECT_EQ(b["resets"], a["resets"]);
  EXPECT_GE(b["samples"].get<int>(), a["samples"].get<int>());
  EXPECT_EQ(b["parameters"]["tonemap"], "reinhard");
  EXPECT_EQ(b["parameters"]["view"], "albedo");
  // An image-altering change restarts it.
  EXPECT_EQ(c["resets"].get<int>(), b["resets"].get<int>() + 1);
  EXPECT_LT(c["samples"].get<int>(), b["samples"].get<int>());
  EXPECT_EQ(c["parameters"]["max_bounces"], 2);
}

TEST(Window, BrokenShaderShowsErrorKeepsRenderingAndRecovers) {
  REQUIRE_XVFB();
  const auto dir = tempDir("reload");
  const fs::path root = privateRoot(dir);
  const fs::path watched = root / "shaders/pathtracer/closesthit.rchit";
  const std::string good = readFile(watched);
  // A syntax error on line 2 (after #version).
  const auto firstNewline = good.find('\n');
  writeFile(dir / "broken.rchit",
            good.substr(0, firstNewline + 1) + "this is not glsl;\n" + good.substr(firstNewline + 1));
  // The fix is a real change too (the same text as before the break would rebuild nothing: its pipeline is
  // still the one in use).
  std::string fixedText = good;
  const std::string needle = "const float minCos = 1e-3;";
  ASSERT_NE(fixedText.find(needle), std::string::npos);
  fixedText.replace(fixedText.find(needle), needle.size(), "const float minCos = 1.0001e-3;");
  writeFile(dir / "good.rchit", fixedText);
  const auto script = dir / "script.txt";
  writeFile(script,
            "wait_samples 2 300\n"
            "copy " +
                (dir / "broken.rchit").string() + " " + watched.string() +
                "\n"
                "wait_reload 300\n"
                "stats " +
                (dir / "broken1.json").string() +
                "\n"
                "screenshot " +
                (dir / "broken.png").string() +
                "\n"
                "frames 12\n"
                "stats " +
                (dir / "broken2.json").string() +
                "\n"
                "copy " +
                (dir / "good.rchit").string() + " " + watched.string() +
                "\n"
                "wait_reload 300\n"
                "wait_samples 1 300\n"
                "stats " +
                (dir / "fixed.json").string() + "\n");
  auto r = runWindow("--script " + script.string(), "WB_ROOT=" + root.string());
  ASSERT_EQ(r.code, 0) << r.output;
  const auto b1 = readJson(dir / "broken1.json"), b2 = readJson(dir / "broken2.json");
  const auto fixed = readJson(dir / "fixed.json");
  const std::string err = b1["shader_error"];
  EXPECT_TRUE(std::regex_search(err, std::regex("closesthit\\.rchit:2:"))) << err;
  EXPECT_NE(b1["banner"].get<std::string>().find("closesthit.rchit:2"), std::string::npos);
  EXPECT_FALSE(b1["reloads"].back()["ok"].get<bool>());
  // The last good pipeline keeps rendering: samples keep increasing.
  EXPECT_GT(b2["samples"].get<int>(), b1["samples"].get<int>());
  EXPECT_EQ(b2["shader_error"], b1["shader_error"]);
  EXPECT_TRUE(fs::exists(dir / "broken.png"));
  // The fix recovers.
  EXPECT_EQ(fixed["shader_error"], "");
  EXPECT_EQ(fixed["banner"], "");
  EXPECT_TRUE(fixed["reloads"].back()["ok"].get<bool>());
  EXPECT_GE(fixed["samples"].get<int>(), 1);
  // The window's reload history measures its frames around each reload as watch's log does.
  const auto& applied = fixed["reloads"].back();
  EXPECT_GT(applied["first_new_frame_ms"].get<double>(), 0.0) << applied.dump();
  EXPECT_GT(applied["frame_ms_median_before"].get<double>(), 0.0) << applied.dump();
  EXPECT_TRUE(applied["edit_to_first_frame_ms"].is_number()) << applied.dump();
  EXPECT_TRUE(b1["reloads"].back()["first_new_frame_ms"].is_null()) << "a failed build draws no new frame";
}

// A save that changes no SPIR-V (the same bytes, or a comment) rebuilds nothing and keeps the accumulation.
// A closest-hit that never returns: its trial frame on the second device does not finish, the edit is refused
// with its file in the banner, the window keeps drawing with the last good pipeline, and the next good edit
// is installed.
TEST(Window, AnEndlessLoopIsRefusedAndTheWindowDrawsOn) {
  REQUIRE_XVFB();
  const auto dir = tempDir("endless");
  const fs::path root = privateRoot(dir);
  const fs::path watched = root / "shaders/pathtracer/closesthit.rchit";
  const std::string good = readFile(watched);
  const std::string endless = withEndlessLoop(good);
  writeFile(dir / "endless.rchit", endless);
  std::string fixedText = good;
  const std::string needle = "const float minCos = 1e-3;";
  ASSERT_NE(fixedText.find(needle), std::string::npos);
  fixedText.replace(fixedText.find(needle), needle.size(), "const float minCos = 1.0001e-3;");
  writeFile(dir / "good.rchit", fixedText);
  const auto script = dir / "script.txt";
  writeFile(script, "wait_samples 1 300\ncopy " + (dir / "endless.rchit").string() + " " + watched.string() +
                        "\nwait_reload 300\nstats " + (dir / "refused.json").string() + "\nframes 4\nstats " +
                        (dir / "after.json").string() + "\ncopy " + (dir / "good.rchit").string() + " " +
                        watched.string() + "\nwait_reload 300\nwait_samples 1 300\nstats " +
                        (dir / "fixed.json").string() + "\n");
  auto r = runWindow("--script " + script.string(), "WB_ROOT=" + root.string() + " WB_HANG_SECONDS=3", 500);
  ASSERT_EQ(r.code, 0) << r.output;
  const auto refused = readJson(dir / "refused.json"), after = readJson(dir / "after.json");
  const auto fixed = readJson(dir / "fixed.json");
  const std::string banner = refused["banner"];
  EXPECT_NE(banner.find("closesthit.rchit"), std::string::npos) << banner;
  EXPECT_NE(banner.find("endless loop"), std::string::npos) << banner;
  EXPECT_FALSE(refused["reloads"].back()["ok"].get<bool>());
  EXPECT_TRUE(refused["reloads"].back()["pipelines_rebuilt"].empty()) << "the hanging pipeline was installed";
  EXPECT_GT(after["frames"].get<int>(), refused["frames"].get<int>()) << "the window stopped drawing";
  EXPECT_TRUE(fixed["reloads"].back()["ok"].get<bool>()) << fixed["reloads"].back().dump();
  EXPECT_EQ(fixed["banner"], "");
}

// Without the trial frame (WB_TRIAL_RUN=0) a closest-hit that never returns is installed, and the window's
// next frame never finishes. The frame loop may then be blocked in a call that waits for that frame
// (lavapipe's present does) rather than in its own wait with a limit: the watchdog still says which edit hung
// and ends the window with status 4, as `watch` does, instead of hanging for good.
TEST(Window, WithoutTheTrialFrameAnEndlessLoopEndsTheWindowSayingWhichEdit) {
  REQUIRE_XVFB();
  const auto dir = tempDir("endless_untried");
  const fs::path root = privateRoot(dir);
  const fs::path watched = root / "shaders/pathtracer/closesthit.rchit";
  const std::string endless = withEndlessLoop(readFile(watched));
  writeFile(dir / "endless.rchit", endless);
  const auto script = dir / "script.txt";
  // After the reload the script waits for samples that never come: only the hang ends the window.
  writeFile(script, "wait_samples 1 300\ncopy " + (dir / "endless.rchit").string() + " " + watched.string() +
                        "\nwait_reload 300\nwait_samples 1000000 600\n");
  auto r = runWindow("--script " + script.string(),
                     "WB_ROOT=" + root.string() + " WB_HANG_SECONDS=3 WB_TRIAL_RUN=0", 500);
  ASSERT_EQ(r.code, 4) << r.output;
  EXPECT_NE(r.output.find("did not finish"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("after the reload of"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("closesthit.rchit"), std::string::npos) << r.output;
}

TEST(Window, AnUnchangedSaveKeepsTheAccumulation) {
  REQUIRE_XVFB();
  const auto dir = tempDir("unchanged");
  const fs::path root = privateRoot(dir);
  const fs::path watched = root / "shaders/pathtracer/closesthit.rchit";
  writeFile(dir / "commented.rchit", readFile(watched) + "// a comment\n");
  const auto script = dir / "script.txt";
  writeFile(script, "wait_samples 2 300\nstats " + (dir / "before.json").string() + "\ncopy " +
                        (dir / "commented.rchit").string() + " " + watched.string() +
                        "\nwait_reload 300\nstats " + (dir / "after.json").string() + "\n");
  auto r = runWindow("--script " + script.string(), "WB_ROOT=" + root.string());
  ASSERT_EQ(r.code, 0) << r.output;
  const auto before = readJson(dir / "before.json"), after = readJson(dir / "after.json");
  ASSERT_FALSE(after["reloads"].empty());
  const auto& e = after["reloads"].back();
  EXPECT_TRUE(e["ok"].get<bool>()) << e.dump();
  EXPECT_TRUE(e["pipelines_rebuilt"].empty()) << e.dump();
  EXPECT_EQ(after["resets"], before["resets"]) << "the accumulation must go on";
  EXPECT_GE(after["samples"].get<int>(), before["samples"].get<int>());
}

// An edit that changes the image: the A/B panel's comparison (old against new, same seeds) says so, in the
// stats JSON as in watch's log; Revert reinstalls the old pipeline.
TEST(Window, AnEditShowsItsABVerdictAndReverts) {
  REQUIRE_XVFB();
  const auto dir = tempDir("ab");
  const fs::path root = privateRoot(dir);
  const fs::path watched = root / "shaders/pathtracer/closesthit.rchit";
  std::string brighter = readFile(watched);
  const std::string needle = "  sm.baseColor = baseColor.rgb;";
  ASSERT_NE(brighter.find(needle), std::string::npos);
  brighter.replace(brighter.find(needle), needle.size(), "  sm.baseColor = baseColor.rgb * 1.02;");
  writeFile(dir / "brighter.rchit", brighter);
  const auto script = dir / "script.txt";
  // The comparison runs after the new image's first frame, before the loop goes on: two samples after the
  // reload, it is done.
  writeFile(script, "wait_samples 2 300\ncopy " + (dir / "brighter.rchit").string() + " " + watched.string() +
                        "\nwait_reload 300\nwait_samples 2 300\nstats " + (dir / "ab.json").string() +
                        "\nab_revert\nframes 2\nstats " + (dir / "reverted.json").string() + "\n");
  auto r = runWindow("--script " + script.string(), "WB_ROOT=" + root.string());
  ASSERT_EQ(r.code, 0) << r.output;
  const auto ab = readJson(dir / "ab.json"), reverted = readJson(dir / "reverted.json");
  ASSERT_TRUE(ab["ab"].is_object()) << ab.dump();
  EXPECT_EQ(ab["ab"]["image_verdict"], "changed") << ab["ab"].dump();
  EXPECT_TRUE(ab["ab"]["mean_shift_significant"].get<bool>()) << ab["ab"].dump();
  EXPECT_TRUE(ab["ab"]["speed_verdict"].is_string());
  EXPECT_GT(ab["ab_ms"].get<double>(), 0.0);
  EXPECT_GT(ab["ab_edit_ms"].get<double>(), 0.0);
  EXPECT_TRUE(ab["ab_enabled"].is_boolean());
  EXPECT_EQ(ab["reloads"].back()["ab"], ab["ab"]) << "the reload history carries the same comparison";
  EXPECT_TRUE(reverted["reloads"].back()["reverted"].get<bool>()) << reverted["reloads"].back().dump();
  EXPECT_NE(r.output.find("A/B revert"), std::string::npos) << r.output;
}

TEST(Window, NoDisplayFallsBackToHeadlessRender) {
  const auto dir = tempDir("headless");
  const auto out = dir / "fallback.png";
  auto r = runShell("env -u DISPLAY -u WAYLAND_DISPLAY WB_VALIDATION=1 " + std::string(WB_WORKBENCH_BIN) +
                    " --size 32x24 --spp 1 --frames 3 --out " + out.string());
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("no display"), std::string::npos) << r.output;
  EXPECT_TRUE(fs::exists(out)) << r.output;
}

// A display the device cannot present to (a swapchain that cannot be made, as NVIDIA's driver on Xvfb): the
// window closes, says why, and renders headless as without a display.
TEST(Window, ADisplayTheDeviceCannotPresentToFallsBackToHeadlessRender) {
  REQUIRE_XVFB();
  const auto dir = tempDir("nopresent");
  const auto out = dir / "fallback.png";
  auto r = runWindow("--size 32x24 --spp 1 --out " + out.string(), "WB_SIMULATE_NO_PRESENT=1");
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("cannot present to a window on display"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("VK_ERROR_UNKNOWN"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("rendering headless instead"), std::string::npos) << r.output;
  EXPECT_TRUE(fs::exists(out)) << r.output;
}

TEST(Window, HybridAndReflectionModesRenderAndSwitchBack) {
  REQUIRE_XVFB();
  const auto dir = tempDir("modes");
  const auto script = dir / "script.txt";
  writeFile(script, "set mode hybrid\nframes 6\nstats " + (dir / "hybrid.json").string() + "\nscreenshot " +
                        (dir / "hybrid.png").string() +
                        "\nframes 1\n"
                        "set mode reflections\nframes 4\nstats " +
                        (dir / "reflections.json").string() + "\nscreenshot " +
                        (dir / "reflections.png").string() +
                        "\nframes 1\n"
                        "set mode pathtrace\nwait_samples 1 300\nstats " +
                        (dir / "pathtrace.json").string() + "\n");
  auto r = runWindow("--script " + script.string());
  ASSERT_EQ(r.code, 0) << r.output;
  const auto hy = readJson(dir / "hybrid.json"), rf = readJson(dir / "reflections.json");
  const auto pt = readJson(dir / "pathtrace.json");
  EXPECT_EQ(hy["mode"], "hybrid");
  EXPECT_GE(hy["samples"].get<int>(), 5) << "hybrid frames accumulate shadows and AO";
  EXPECT_TRUE(hy["parameters"].contains("hybrid"));
  EXPECT_EQ(rf["mode"], "reflections");
  EXPECT_GT(rf["resets"].get<int>(), hy["resets"].get<int>()) << "a mode switch restarts accumulation";
  EXPECT_LE(rf["samples"].get<int>(), 5);
  EXPECT_EQ(pt["mode"], "pathtrace");
  EXPECT_GE(pt["samples"].get<int>(), 1);
  EXPECT_EQ(pt["shader_error"], "");
  // Both hybrid images are lit (the default scene's room under the sun), not black.
  EXPECT_GT(imageAreaMean(dir / "hybrid.png", 144), 20.0);
  EXPECT_GT(imageAreaMean(dir / "reflections.png", 144), 20.0);
}

TEST(Window, RunningErrorAgainstAReferenceAndTheNoiseEstimate) {
  REQUIRE_XVFB();
  const auto dir = tempDir("error");
  // A converged-enough reference of the same view (another seed: independent of the window's samples) and
  // one of another size.
  auto ref =
      runShell("env WB_VALIDATION=1 " + std::string(WB_WORKBENCH_BIN) +
               " render --size 48x48 --spp 256 --seed 9 --sampler pcg --out " + (dir / "ref.exr").string());
  ASSERT_EQ(ref.code, 0) << ref.output;
  auto small = runShell(std::string(WB_WORKBENCH_BIN) + " render --size 32x32 --spp 1 --out " +
                        (dir / "small.exr").string());
  ASSERT_EQ(small.code, 0) << small.output;
  writeFile(dir / "a.txt", "wait_samples 16 300\nstats " + (dir / "a.json").string() + "\nset reference " +
                               (dir / "small.exr").string() + "\nframes 2\nstats " +
                               (dir / "c.json").string() + "\n");
  writeFile(dir / "b.txt", "wait_samples 16 300\nstats " + (dir / "b.json").string() + "\n");
  const std::string common = "--size 48x48 --scale 1 --sampler pcg ";
  auto ra = runWindow(common + "--reference " + (dir / "ref.exr").string() + " --script " +
                      (dir / "a.txt").string());
  ASSERT_EQ(ra.code, 0) << ra.output;
  auto rb = runWindow(common + "--script " + (dir / "b.txt").string());
  ASSERT_EQ(rb.code, 0) << rb.output;

  // Against the reference: a point at 1, 2, 4, 8, 16 spp, falling as the samples accumulate (the error of a
  // 1-spp image is about 4x that of a 16-spp one; the 256-spp reference adds a little noise of its own).
  const auto a = readJson(dir / "a.json")["live_error"];
  EXPECT_EQ(a["error"], "");
  std::vector<int> samples;
  for (const auto& p : a["history"]) {
    samples.push_back(p["samples"].get<int>());
    EXPECT_FALSE(p["estimated"].get<bool>());
  }
  ASSERT_GE(samples.size(), 5u) << a.dump();
  EXPECT_EQ(std::vector<int>(samples.begin(), samples.begin() + 5), (std::vector<int>{1, 2, 4, 8, 16}));
  const double first = a["history"][0]["rmse"], at16 = a["history"][4]["rmse"];
  EXPECT_LT(at16, 0.5 * first) << a.dump();
  EXPECT_GT(at16, 0.0);
  // A reference of another size is refused with a reason naming both sizes.
  const auto c = readJson(dir / "c.json")["live_error"];
  EXPECT_NE(c["error"].get<std::string>().find("32x32"), std::string::npos) << c.dump();
  EXPECT_NE(c["error"].get<std::string>().find("48x48"), std::string::npos) << c.dump();
  // Without a reference: the n vs n/2 noise estimate from 2 spp on, falling too.
  const auto b = readJson(dir / "b.json")["live_error"];
  ASSERT_GE(b["history"].size(), 4u) << b.dump();
  EXPECT_EQ(b["history"][0]["samples"], 2);
  EXPECT_TRUE(b["history"][0]["estimated"].get<bool>());
  EXPECT_LT(b["history"][3]["rmse"].get<double>(), b["history"][0]["rmse"].get<double>());
}

// A --reference that cannot be read is said on the terminal (the panel says it too) and the window goes on
// with the noise estimate.
TEST(Window, AnUnreadableReferenceIsSaidAndTheWindowGoesOn) {
  REQUIRE_XVFB();
  const auto dir = tempDir("noref");
  auto r = runWindow("--reference " + (dir / "missing.exr").string() + " --frames 3 --stats " +
                     (dir / "s.json").string());
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("reference " + (dir / "missing.exr").string() + " not used"), std::string::npos)
      << r.output;
  EXPECT_NE(readJson(dir / "s.json")["live_error"]["error"].get<std::string>(), "");
}

namespace {

int pngWidth(const fs::path& png, int* height = nullptr) {
  int w = 0, h = 0, n = 0;
  if (!stbi_info(png.c_str(), &w, &h, &n)) return -1;
  if (height) *height = h;
  return w;
}

// Mean absolute difference of two same-size screenshots over the image area (right of the panel).
double imageAreaDifference(const fs::path& a, const fs::path& b, int panelWidth) {
  int w = 0, h = 0, n = 0, w2 = 0, h2 = 0;
  unsigned char* pa = stbi_load(a.c_str(), &w, &h, &n, 4);
  unsigned char* pb = stbi_load(b.c_str(), &w2, &h2, &n, 4);
  double sum = 0;
  size_t count = 0;
  if (pa && pb && w == w2 && h == h2) {
    for (int y = 0; y < h - 24; ++y) {
      for (int x = panelWidth + 4; x < w; ++x) {
        for (int c = 0; c < 3; ++c)
          sum += std::abs(int(pa[4 * (y * w + x) + c]) - int(pb[4 * (y * w + x) + c]));
        ++count;
      }
    }
  }
  if (pa) stbi_image_free(pa);
  if (pb) stbi_image_free(pb);
  return count ? sum / double(3 * count) : -1;
}

}  // namespace

// Saving (the F12 key and the button run the same request), a debug view, resizing, and the panel layout
// file only when asked for.
TEST(Window, SaveDebugViewResizeAndImguiIni) {
  REQUIRE_XVFB();
  const auto dir = tempDir("save");
  const auto script = dir / "script.txt";
  writeFile(script, "wait_samples 1 300\nsave " + (dir / "saved").string() +
                        "\nset view albedo\nframes 2\nscreenshot " + (dir / "albedo.png").string() +
                        "\nframes 1\nset view beauty\nframes 2\nscreenshot " + (dir / "beauty.png").string() +
                        "\nframes 1\nresize 400 300\nframes 3\nstats " + (dir / "resized.json").string() +
                        "\nscreenshot " + (dir / "resized.png").string() + "\n");
  auto r = runWindow("--imgui-ini " + (dir / "layout.ini").string() + " --script " + script.string());
  ASSERT_EQ(r.code, 0) << r.output;
  // PNG (tonemapped), EXR (linear) and the parameters beside them.
  EXPECT_GT(pngWidth(dir / "saved.png"), 0);
  EXPECT_TRUE(fs::exists(dir / "saved.exr"));
  const auto params = readJson(dir / "saved.json");
  EXPECT_EQ(params["max_bounces"], 8);
  EXPECT_EQ(params["mode"], "pathtrace");
  EXPECT_TRUE(params.contains("camera"));
  // The albedo view shows something else than the beauty image.
  EXPECT_GT(imageAreaDifference(dir / "albedo.png", dir / "beauty.png", 144), 5.0);
  // The window was resized: the swapchain, the screenshot and the trace size follow.
  int h = 0;
  EXPECT_EQ(pngWidth(dir / "resized.png", &h), 400);
  EXPECT_EQ(h, 300);
  const auto j = readJson(dir / "resized.json");
  EXPECT_EQ(j["window_width"], 400);
  EXPECT_EQ(j["window_height"], 300);
  EXPECT_EQ(j["target_height"], 150);  // half the view (resolution scale 0.5)
  EXPECT_TRUE(fs::exists(dir / "layout.ini")) << "--imgui-ini names where the layout is kept";
}

// `save` then `quit` wrote nothing: the save waited for a frame that the quit never drew (issue 33). A save
// that fails is the script's error, naming its line.
TEST(Window, SaveThenQuitWritesTheFilesAndAFailedSaveEndsTheScript) {
  REQUIRE_XVFB();
  const auto dir = tempDir("save_quit");
  writeFile(dir / "s.txt", "wait_samples 1 300\nsave " + (dir / "saved").string() + "\nquit\n");
  auto r = runWindow("--script " + (dir / "s.txt").string());
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_GT(pngWidth(dir / "saved.png"), 0);
  EXPECT_TRUE(fs::exists(dir / "saved.exr"));
  EXPECT_TRUE(readJson(dir / "saved.json").contains("camera"));
  // A full disk (simulated: every file write of the workbench fails as on one; the outputs' checks before
  // the session pass, as they do on a disk that fills up later).
  writeFile(dir / "f.txt", "wait_samples 1 300\nsave " + (dir / "full").string() + "\nframes 1\n");
  auto f = runWindow("--script " + (dir / "f.txt").string(), "WB_SIMULATE_DISK_FULL=1");
  EXPECT_EQ(f.code, 1) << f.output;
  EXPECT_NE(f.output.find("script error: " + (dir / "f.txt").string() + ":2: cannot write '" +
                          (dir / "full.png").string() + "': No space left on device"),
            std::string::npos)
      << f.output;
  EXPECT_FALSE(fs::exists(dir / "full.png"));
}

TEST(Window, VsyncToggleRecreatesTheSwapchain) {
  REQUIRE_XVFB();
  const auto dir = tempDir("vsync");
  writeFile(dir / "s.txt", "frames 2\nstats " + (dir / "on.json").string() +
                               "\nset vsync off\nframes 3\nstats " + (dir / "off.json").string() + "\n");
  auto r = runWindow("--script " + (dir / "s.txt").string());
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_EQ(readJson(dir / "on.json")["present_mode"], "FIFO (vsync)");
  EXPECT_NE(readJson(dir / "off.json")["present_mode"], "FIFO (vsync)");
  EXPECT_FALSE(readJson(dir / "off.json")["parameters"].is_null());
}

TEST(Window, ModeFlagStartsInThatMode) {
  REQUIRE_XVFB();
  const auto dir = tempDir("modeflag");
  auto r =
      runWindow("--mode reflections --reflection-depth 3 --frames 4 --stats " + (dir / "s.json").string());
  ASSERT_EQ(r.code, 0) << r.output;
  const auto j = readJson(dir / "s.json");
  EXPECT_EQ(j["mode"], "reflections");
  EXPECT_EQ(j["parameters"]["hybrid"]["reflection_depth"], 3);
  EXPECT_GE(j["samples"].get<int>(), 3);
}

// --spp N is the window's target: it stops accumulating at N samples (it was listed by the window's help but
// ignored). The frames after the target is reached add nothing.
TEST(Window, SppFlagIsTheTargetSpp) {
  REQUIRE_XVFB();
  const auto dir = tempDir("spp");
  writeFile(dir / "script.txt", "wait_samples 2 300\nframes 30\nstats " + (dir / "s.json").string() + "\n");
  auto r = runWindow("--spp 2 --script " + (dir / "script.txt").string());
  ASSERT_EQ(r.code, 0) << r.output;
  const auto j = readJson(dir / "s.json");
  EXPECT_EQ(j["samples"].get<int>(), 2) << j.dump();
}

// At a few frames a second a quick key tap falls between two frames (the frame loop polled the key state
// and lost it): every tap of a window key lands, as synthetic X input through xdotool shows. Four Tab taps
// within one slow frame leave the panel shown and count four presses. Hiding the panel shows the same image
// larger: the accumulation goes on.
TEST(Window, QuickKeyTapsAtALowFrameRateAllLand) {
  REQUIRE_XVFB();
  ASSERT_EQ(runShell("command -v xdotool").code, 0) << "xdotool (scripts/setup.sh installs it) is missing";
  const auto dir = tempDir("taps");
  const fs::path go = dir / "go", script = dir / "s.txt", before = dir / "before.json",
                 stats = dir / "s.json";
  writeFile(script, "wait_samples 1 300\nstats " + before.string() + "\nwait_file " + go.string() +
                        " 300\nframes 3\nstats " + stats.string() + "\n");
  // A 300 ms trace budget: frames of about half a second, the four taps sent within one of them: one xdotool
  // call, 5 ms between keys (four calls took long enough to straddle a frame now and then, and a frame that
  // saw an odd number of taps resized the image; with no delay GLFW takes a release and a press of the same
  // time for the key's auto-repeat).
  const std::string inner = std::string(WB_WORKBENCH_BIN) +
                            " --window 640x480 --set budget_ms=300 --script " + script.string() +
                            " & pid=$!; while [ ! -e " + before.string() +
                            " ]; do sleep 0.05; done; "
                            "xdotool mousemove 500 200; xdotool key --delay 5 Tab Tab Tab Tab; touch " +
                            go.string() + "; wait $pid";
  auto r = runShell(std::string(wb::testing::kOwnSession) + "env WB_VALIDATION=1 " + xvfbRun() + "sh -c \"" +
                    inner + "\"");
  ASSERT_EQ(r.code, 0) << r.output;
  const auto s = readJson(stats);
  EXPECT_EQ(s["key_presses"], 4) << r.output;
  EXPECT_EQ(s["panel_visible"], true) << "an even number of Tab taps";
  EXPECT_EQ(s["resets"], readJson(before)["resets"]) << "hiding the panel restarted the accumulation";
}

// A mode switch as the panel makes it does not stop the window: the script goes on while the other mode's
// renderer is made off the frame loop (the stats written right after the request still show the old mode),
// then the new mode takes over and the stats time the switch from the request on (ModeSwitchTimer).
TEST(Window, AModeSwitchIsPreparedWhileTheWindowDraws) {
  REQUIRE_XVFB();
  const auto dir = tempDir("switch");
  const fs::path a = dir / "a.json", b = dir / "b.json";
  // The sleep puts seconds of path tracing before the switch: the hybrid mode's clock starts with it.
  writeFile(dir / "s.txt", "wait_samples 1 300\nsleep 3\nswitch_mode hybrid\nstats " + a.string() +
                               "\nwait_mode 600\nframes 3\nstats " + b.string() + "\nquit\n");
  auto r = runWindow("--script " + (dir / "s.txt").string());
  ASSERT_EQ(r.code, 0) << r.output;
  const auto ja = readJson(a), jb = readJson(b);
  EXPECT_EQ(ja["mode"], "pathtrace") << "the switch blocked the script until the hybrid renderer was made";
  ASSERT_EQ(ja["mode_switches"].size(), 1u);
  EXPECT_EQ(ja["mode_switches"][0]["done"], false);
  EXPECT_EQ(jb["mode"], "hybrid");
  ASSERT_EQ(jb["mode_switches"].size(), 1u);
  EXPECT_EQ(jb["mode_switches"][0]["to"], "hybrid");
  EXPECT_EQ(jb["mode_switches"][0]["done"], true);
  const double longest = jb["mode_switches"][0]["longest_frame_ms"].get<double>();
  EXPECT_GT(longest, 0.0);
  EXPECT_LE(longest, jb["mode_switches"][0]["total_ms"].get<double>()) << "timed from before the request";
  EXPECT_LT(jb["seconds_since_reset"].get<double>(), ja["seconds_since_reset"].get<double>())
      << "the hybrid mode's elapsed time counts from before the switch";
}

// A script that sleeps goes on afterwards; a switch to a mode that does not exist fails the script with the
// reason.
TEST(Window, ScriptSleepAndWaitModeCommands) {
  REQUIRE_XVFB();
  const auto dir = tempDir("sleep");
  writeFile(dir / "s.txt", "sleep 0.2\nframes 1\nstats " + (dir / "s.json").string() + "\nquit\n");
  auto r = runWindow("--script " + (dir / "s.txt").string());
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_TRUE(fs::exists(dir / "s.json"));
  writeFile(dir / "t.txt", "switch_mode nonsense\n");
  r = runWindow("--script " + (dir / "t.txt").string());
  EXPECT_EQ(r.code, 1) << r.output;
  EXPECT_NE(r.output.find("mode"), std::string::npos) << r.output;
}

// A wait that times out fails the script: exit status 1 with the line, not a script that goes on.
TEST(Window, AFailedWaitFailsTheSession) {
  REQUIRE_XVFB();
  const auto dir = tempDir("waitfail");
  writeFile(dir / "s.txt", "wait_reload 0.5\nstats " + (dir / "never.json").string() + "\n");
  auto r = runWindow("--script " + (dir / "s.txt").string());
  EXPECT_EQ(r.code, 1) << r.output;
  EXPECT_NE(r.output.find("wait_reload"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(dir / "never.json")) << "the script went on after the failed wait";
}

// A drag starts where the button went down: the motion made before the press is not part of it. The cursor
// jumps across the image and the button goes down there; frames pass with the button held still; the
// camera must not have moved.
TEST(Window, ADragStartsAtThePressPosition) {
  REQUIRE_XVFB();
  ASSERT_EQ(runShell("command -v xdotool").code, 0) << "xdotool (scripts/setup.sh installs it) is missing";
  const auto dir = tempDir("drag");
  const fs::path a = dir / "a.json", b = dir / "b.json", go = dir / "go", go2 = dir / "go2";
  writeFile(dir / "s.txt", "wait_samples 1 300\nstats " + a.string() + "\nwait_file " + go.string() +
                               " 300\nframes 4\nstats " + b.string() + "\nwait_file " + go2.string() +
                               " 300\n");
  auto waitFor = [](const fs::path& p) { return "while [ ! -e " + p.string() + " ]; do sleep 0.05; done; "; };
  const std::string inner =
      std::string(WB_WORKBENCH_BIN) + " --window 640x480 --script " + (dir / "s.txt").string() +
      " & pid=$!; " + waitFor(a) +
      "xdotool mousemove 420 80; sleep 1; xdotool mousemove 600 400 mousedown 1; touch " + go.string() +
      "; " + waitFor(b) + "xdotool mouseup 1; touch " + go2.string() + "; wait $pid";
  auto r = runShell(std::string(wb::testing::kOwnSession) + "env WB_VALIDATION=1 " + xvfbRun() + "sh -c \"" +
                    inner + "\"");
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_EQ(readJson(a)["parameters"]["camera"], readJson(b)["parameters"]["camera"])
      << "the jump before the press moved the camera";
}

// Every way out releases resources in a safe order: quitting after an environment change (the session was
// destroyed before the environment it pointed at: Aborted), after a mode switch, and after both.
TEST(Window, QuitsCleanlyAfterAnEnvironmentChangeAndAModeSwitch) {
  REQUIRE_XVFB();
  const auto dir = tempDir("quit");
  auto r = runWindow("--set env_color=1,0,0 --frames 5");
  EXPECT_EQ(r.code, 0) << r.output;
  writeFile(dir / "s.txt",
            "frames 2\nset mode hybrid\nframes 3\nset env_color 0,0,1\nframes 2\nset mode "
            "reflections\nframes 2\nquit\n");
  r = runWindow("--script " + (dir / "s.txt").string());
  EXPECT_EQ(r.code, 0) << r.output;
  writeFile(dir / "t.txt", "set mode hybrid\nframes 3\nquit\n");
  r = runWindow("--script " + (dir / "t.txt").string());
  EXPECT_EQ(r.code, 0) << r.output;
}

namespace {

// Pixels of the image area (right of the panel) in the inspector's pixel marker colour (pure yellow).
size_t markerPixels(const fs::path& png, int panelWidth) {
  int w = 0, h = 0, n = 0;
  unsigned char* px = stbi_load(png.c_str(), &w, &h, &n, 4);
  if (!px) return 0;
  size_t count = 0;
  for (int y = 0; y < h - 24; ++y) {
    for (int x = panelWidth + 4; x < w; ++x) {
      const unsigned char* p = px + 4 * (size_t(y) * w + x);
      count += p[0] > 235 && p[1] > 235 && p[2] < 40;
    }
  }
  stbi_image_free(px);
  return count;
}

}  // namespace

// The path inspector in the window: a pixel set by script is recorded by the inspecting variant while the
// image accumulates; the records' running estimate is the pixel's value, and the overlay marks the pixel.
TEST(Window, PathInspectorRecordsThePixelAndDrawsItsPath) {
  REQUIRE_XVFB();
  const auto dir = tempDir("inspect");
  const fs::path records = dir / "records.json", with = dir / "with.png", without = dir / "without.png";
  writeFile(dir / "s.txt", "set inspect_pixel 40,60\nwait_samples 4 300\nframes 2\ninspect " +
                               records.string() + "\nscreenshot " + with.string() +
                               "\nframes 1\nset inspect_pixel off\nframes 2\n" + "screenshot " +
                               without.string() + "\n");
  auto r = runWindow("--spp 4 --script " + (dir / "s.txt").string());
  ASSERT_EQ(r.code, 0) << r.output;
  const auto j = readJson(records);
  EXPECT_EQ(j["pixel"], nlohmann::json::array({40, 60}));
  ASSERT_EQ(j["samples"].size(), 4u) << "every sample of the target is kept";
  EXPECT_EQ(j["running_estimate"]["samples"].get<int>() + j["running_estimate"]["dropped"].get<int>(), 4);
  EXPECT_EQ(j["pixel_samples"], 4.0);
  for (int c = 0; c < 3; ++c) {
    const double pixel = j["pixel_value"][c], mean = j["running_estimate"]["mean"][c];
    EXPECT_NEAR(mean, pixel, 1e-5 * std::max(1.0, pixel)) << j.dump();
  }
  for (const auto& s : j["samples"]) EXPECT_FALSE(s["vertices"].empty()) << "pixel 40,60 sees the room";
  EXPECT_GT(markerPixels(with, 144), 8u) << "the inspected pixel is marked over the image";
  EXPECT_EQ(markerPixels(without, 144), 0u);
}

// A click on the image picks the pixel to inspect (synthetic X input through xdotool): the middle of the
// image area of a 640x480 window (panel 288 px wide, image 352x480, traced at 176x240).
TEST(Window, AClickPicksThePixelToInspect) {
  REQUIRE_XVFB();
  ASSERT_EQ(runShell("command -v xdotool").code, 0) << "xdotool (scripts/setup.sh installs it) is missing";
  const auto dir = tempDir("inspectclick");
  const fs::path ready = dir / "ready.json", go = dir / "go", records = dir / "records.json";
  writeFile(dir / "s.txt", "wait_samples 1 300\nstats " + ready.string() + "\nwait_file " + go.string() +
                               " 300\nframes 3\ninspect " + records.string() + "\n");
  const std::string inner = std::string(WB_WORKBENCH_BIN) + " --window 640x480 --script " +
                            (dir / "s.txt").string() + " & pid=$!; while [ ! -e " + ready.string() +
                            " ]; do sleep 0.05; done; xdotool mousemove 464 240 click 1; touch " +
                            go.string() + "; wait $pid";
  auto r = runShell(std::string(wb::testing::kOwnSession) + "env WB_VALIDATION=1 " + xvfbRun() + "sh -c \"" +
                    inner + "\"");
  ASSERT_EQ(r.code, 0) << r.output;
  const auto j = readJson(records);
  EXPECT_NEAR(j["pixel"][0].get<int>(), 88, 2) << j["pixel"];
  EXPECT_NEAR(j["pixel"][1].get<int>(), 120, 2) << j["pixel"];
}

// The heat-map views read their data in the display pass: each shows something else than the image, and
// nan_source on a scene without NaN/Inf is the image dimmed.
TEST(Window, HeatMapViewsShowTheirData) {
  REQUIRE_XVFB();
  const auto dir = tempDir("heatmaps");
  std::string script = "wait_samples 2 300\n";
  for (const char* view : {"beauty", "rr_end", "variance", "nan_source"}) {
    script += std::string("set view ") + view + "\nframes 2\nscreenshot " + (dir / view).string() +
              ".png\nframes 1\n";
  }
  writeFile(dir / "s.txt", script);
  auto r = runWindow("--spp 2 --rr-start 1 --script " + (dir / "s.txt").string());
  ASSERT_EQ(r.code, 0) << r.output;
  const auto beauty = dir / "beauty.png";
  EXPECT_GT(imageAreaDifference(dir / "rr_end.png", beauty, 144), 5.0);
  EXPECT_GT(imageAreaDifference(dir / "variance.png", beauty, 144), 5.0);
  EXPECT_GT(imageAreaDifference(dir / "rr_end.png", dir / "variance.png", 144), 5.0);
  EXPECT_LT(imageAreaMean(dir / "nan_source.png", 144), 0.6 * imageAreaMean(beauty, 144));
}

// In the hybrid modes the inspector records the pixel's shadow, AO and reflection rays.
TEST(Window, HybridModesRecordThePixelsRays) {
  REQUIRE_XVFB();
  const auto dir = tempDir("inspecthybrid");
  const fs::path records = dir / "records.json";
  writeFile(dir / "s.txt",
            "set inspect_pixel 40,60\nwait_samples 2 300\nframes 2\ninspect " + records.string() + "\n");
  auto r = runWindow("--mode reflections --ao-rays 4 --script " + (dir / "s.txt").string());
  ASSERT_EQ(r.code, 0) << r.output;
  const auto j = readJson(records);
  EXPECT_EQ(j["schema"], "workbench-hybrid-inspector/1");
  EXPECT_EQ(j["mode"], "reflections");
  EXPECT_EQ(j["pixel"], nlohmann::json::array({40, 60}));
  EXPECT_EQ(j["recorded"], true);
  ASSERT_EQ(j["covered"], true) << "pixel 40,60 sees the room";
  EXPECT_EQ(j["ao"]["rays"].size(), 4u);
  EXPECT_TRUE(j["shadow"]["ray"].contains("visible"));
}

// The cost views: the cost variant runs while one is shown and the legend's summary reaches --stats; the pass
// table's times too; the asserts toggle switches the asserts variant on (the unedited shaders pass).
TEST(Window, CostViewsPassTimesAndTheAssertsToggle) {
  REQUIRE_XVFB();
  const auto dir = tempDir("cost");
  const std::string d = dir.string() + "/";
  writeFile(dir / "s.txt",
            "set view cost\nwait_samples 3 300\nframes 2\nstats " + d + "cost.json\nscreenshot " + d +
                "cost.png\nframes 1\nset view inefficiency\nframes 2\nscreenshot " + d +
                "inefficiency.png\nframes 1\nset view beauty\nset asserts 1\nframes 1\nwait_samples 2 300\n"
                "frames 1\nstats " +
                d + "asserts.json\n");
  auto r = runWindow("--spp 4 --script " + (dir / "s.txt").string());
  ASSERT_EQ(r.code, 0) << r.output;
  const auto cost = readJson(dir / "cost.json");
  ASSERT_TRUE(cost["cost"].is_object()) << cost.dump();
  EXPECT_NE(cost["cost"]["clock"], "none") << "lavapipe has a shader clock";
  EXPECT_GT(cost["cost"]["frame_clocks"].get<double>(), 0.0);
  EXPECT_GT(cost["cost"]["clocks_per_sample"]["p95"].get<double>(), 0.0);
  EXPECT_GT(cost["pass_ms"]["pathtracer"].get<double>(), 0.0);
  EXPECT_GT(imageAreaDifference(dir / "cost.png", dir / "inefficiency.png", 144), 2.0);
  const auto asserts = readJson(dir / "asserts.json");
  ASSERT_TRUE(asserts["asserts"].is_object()) << asserts.dump();
  EXPECT_EQ(asserts["asserts"]["failures"], 0);
  EXPECT_TRUE(asserts["cost"].is_null()) << "the cost variant is off with the beauty view";
}

// With a zero-pdf bug injected into a copy of the shaders (the image's first 8 columns), the asserts toggle
// lists the failures there and nowhere else, and marks them on the image in magenta.
TEST(Window, TheAssertsToggleMarksTheFailingPixels) {
  REQUIRE_XVFB();
  const auto dir = tempDir("assert_marks");
  const fs::path root = dir / "root";
  fs::create_directories(root);
  fs::copy(fs::path(WB_SOURCE_DIR) / "shaders", root / "shaders", fs::copy_options::recursive);
  fs::create_directory_symlink(fs::path(WB_SOURCE_DIR) / "assets", root / "assets");
  const fs::path chit = root / "shaders/pathtracer/closesthit.rchit";
  std::string text = readFile(chit);
  const std::string line = "  payload.pdf = s.pdf;";
  ASSERT_NE(text.find(line), std::string::npos);
  text.replace(text.find(line), line.size(),
               "  payload.pdf = gl_LaunchIDEXT.x + pc.tileOffset.x < 8u ? 0.0 : s.pdf;");
  writeFile(chit, text);
  const std::string d = dir.string() + "/";
  writeFile(dir / "s.txt", "wait_samples 1 300\nframes 1\nscreenshot " + d +
                               "off.png\nframes 1\nset asserts 1\n"
                               "frames 1\nwait_samples 1 300\nframes 2\nstats " +
                               d + "on.json\nscreenshot " + d + "on.png\nframes 1\n");
  auto r = runWindow("--spp 1 --script " + (dir / "s.txt").string(),
                     "WB_ROOT=" + root.string() + " WB_SHADER_CACHE_DIR=" + (root / "cache").string());
  ASSERT_EQ(r.code, 0) << r.output;
  const auto a = readJson(dir / "on.json")["asserts"];
  ASSERT_TRUE(a.is_object());
  EXPECT_GT(a["failures"].get<int>(), 0);
  for (const auto& f : a["first"]) {
    EXPECT_LT(f["pixel"][0].get<int>(), 8) << f.dump();
    EXPECT_EQ(f["label"], "pdf > 0");
  }
  auto magenta = [](const fs::path& png) {
    int w = 0, h = 0, n = 0;
    unsigned char* px = stbi_load(png.c_str(), &w, &h, &n, 4);
    size_t count = 0;
    for (int y = 0; px && y < h - 24; ++y)
      for (int x = 148; x < w; ++x) {
        const unsigned char* p = px + 4 * (size_t(y) * w + x);
        count += p[0] > 235 && p[1] < 40 && p[2] > 235;
      }
    stbi_image_free(px);
    return count;
  };
  EXPECT_EQ(magenta(dir / "off.png"), 0u);
  EXPECT_GT(magenta(dir / "on.png"), 20u);
}

namespace {

// Per column of the image area: the mean absolute difference of two same-size screenshots (-1: unreadable).
std::vector<double> columnDifferences(const fs::path& a, const fs::path& b, int panelWidth) {
  int w = 0, h = 0, n = 0, w2 = 0, h2 = 0;
  unsigned char* pa = stbi_load(a.c_str(), &w, &h, &n, 4);
  unsigned char* pb = stbi_load(b.c_str(), &w2, &h2, &n, 4);
  std::vector<double> columns;
  if (pa && pb && w == w2 && h == h2) {
    for (int x = panelWidth + 4; x < w; ++x) {
      double sum = 0;
      for (int y = 0; y < h - 24; ++y)
        for (int c = 0; c < 3; ++c)
          sum += std::abs(int(pa[4 * (y * w + x) + c]) - int(pb[4 * (y * w + x) + c]));
      columns.push_back(sum / double(3 * (h - 24)));
    }
  }
  if (pa) stbi_image_free(pa);
  if (pb) stbi_image_free(pb);
  return columns;
}

// How noisy the image area is: the mean absolute difference between horizontally adjacent pixels.
double imageAreaRoughness(const fs::path& png, int panelWidth) {
  int w = 0, h = 0, n = 0;
  unsigned char* px = stbi_load(png.c_str(), &w, &h, &n, 4);
  if (!px) return -1;
  double sum = 0;
  size_t count = 0;
  for (int y = 0; y < h - 24; ++y)
    for (int x = panelWidth + 5; x < w; ++x)
      for (int c = 0; c < 3; ++c) {
        sum += std::abs(int(px[4 * (y * w + x) + c]) - int(px[4 * (y * w + x - 1) + c]));
        ++count;
      }
  stbi_image_free(px);
  return count ? sum / double(count) : -1;
}

}  // namespace

// The window denoises its view by default; `set denoise 0` (the panel's checkbox) shows the raw image, and
// denoise_split shows raw left of the split and denoised right of it. Paused at a few samples (where the
// denoiser's output differs from the raw image; at tens of samples, which a cold shader cache lets the image
// reach before the denoiser's first run, it hands over to the raw image): the same samples in every shot.
TEST(Window, DenoiseToggleAndSplitView) {
  REQUIRE_XVFB();
  const auto dir = tempDir("denoise");
  const auto raw = dir / "raw.png", den = dir / "den.png", split = dir / "split.png";
  writeFile(dir / "s.txt",
            "wait_samples 2 300\nset paused 1\nframes 1\nwait_denoised 300\nframes 3\nscreenshot " +
                den.string() + "\nframes 1\nset denoise 0\nframes 3\nscreenshot " + raw.string() +
                "\nstats " + (dir / "raw.json").string() +
                "\nframes 1\nset denoise 1\nset denoise_split 0.5\nframes 3\nscreenshot " + split.string() +
                "\nframes 1\nstats " + (dir / "s.json").string() + "\n");
  auto r = runWindow("--script " + (dir / "s.txt").string());
  ASSERT_EQ(r.code, 0) << r.output;
  const int panelWidth = 144;
  const double roughRaw = imageAreaRoughness(raw, panelWidth), roughDen = imageAreaRoughness(den, panelWidth);
  EXPECT_LT(roughDen, 0.6 * roughRaw) << "the denoised view is smoother than the raw one";
  EXPECT_GE(readJson(dir / "s.json")["samples"].get<int>(), 2);
  // The pass table's denoiser: its last run's GPU time while denoising, none while off.
  EXPECT_GT(readJson(dir / "s.json")["pass_ms"]["denoise"].get<double>(), 0.0);
  EXPECT_FALSE(readJson(dir / "raw.json")["pass_ms"].contains("denoise"))
      << readJson(dir / "raw.json").dump();
  // Split: each column of the image shows either the raw or the denoised image: raw on the left, denoised on
  // the right, both over a good part of the width.
  const auto toRaw = columnDifferences(split, raw, panelWidth),
             toDen = columnDifferences(split, den, panelWidth);
  ASSERT_EQ(toRaw.size(), toDen.size());
  ASSERT_FALSE(toRaw.empty());
  size_t rawColumns = 0, denColumns = 0, lastRaw = 0, firstDen = toRaw.size();
  for (size_t x = 0; x < toRaw.size(); ++x) {
    const bool isRaw = toRaw[x] < 0.5 && toDen[x] > 1.0, isDen = toDen[x] < 0.5 && toRaw[x] > 1.0;
    if (isRaw) ++rawColumns, lastRaw = x;
    if (isDen) ++denColumns, firstDen = std::min(firstDen, x);
  }
  EXPECT_GT(rawColumns, toRaw.size() / 5) << "raw columns on the left of the split";
  EXPECT_GT(denColumns, toRaw.size() / 5) << "denoised columns on the right of the split";
  EXPECT_LT(lastRaw, firstDen) << "raw left of the split, denoised right of it";
}

// The window's denoiser runs when the image gains samples, not every frame: paused, frame after frame shows
// the same output and filters nothing again; its GPU time is measured apart from the trace's (the trace's
// time paces the strips).
TEST(Window, DenoiserRunsOnlyForNewSamples) {
  REQUIRE_XVFB();
  const auto dir = tempDir("denoise_runs");
  const auto a = dir / "a.json", b = dir / "b.json", c = dir / "c.json";
  writeFile(dir / "s.txt", "wait_samples 2 300\nwait_denoised 300\nset paused 1\nframes 3\nstats " +
                               a.string() + "\nframes 12\nstats " + b.string() +
                               "\nset paused 0\nwait_samples 4 300\nframes 3\n" + "stats " + c.string() +
                               "\n");
  auto r = runWindow("--script " + (dir / "s.txt").string());
  ASSERT_EQ(r.code, 0) << r.output;
  const auto ja = readJson(a), jb = readJson(b), jc = readJson(c);
  EXPECT_GE(ja["denoise_runs"].get<int>(), 1) << "the denoiser ran once the image had a whole sample";
  EXPECT_EQ(jb["denoise_runs"], ja["denoise_runs"]) << "twelve frames of a paused image filter nothing again";
  EXPECT_GT(jb["frames"].get<int>(), ja["frames"].get<int>() + 10);
  EXPECT_GT(ja["denoise_gpu_ms_last"].get<double>(), 0.0);
  // pass_ms: the trace's passes, the denoiser's last run and the display pass (the Presenter's timestamps).
  EXPECT_GT(ja["pass_ms"]["pathtracer"].get<double>(), 0.0);
  EXPECT_GT(jb["pass_ms"]["denoise"].get<double>(), 0.0) << "paused: the last run's time stays shown";
  EXPECT_GT(ja["pass_ms"]["display"].get<double>(), 0.0);
  EXPECT_GE(jc["samples"].get<int>(), 4);
  EXPECT_GE(jc["denoise_runs"].get<int>(), ja["denoise_runs"].get<int>()) << jc.dump();
}
