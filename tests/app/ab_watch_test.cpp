// `workbench watch --ab` end to end on a private copy of shaders/ and assets/ (WB_ROOT): each edit's log line
// says whether the image changed and whether the new pipeline is faster. Edits: a comment (no rebuild), a
// refactor (same values), an albedo and an emission scaled by 1.02 (changed, a significant mean shift,
// exactly on the affected pixels), wasted work in closest-hit (slower) and its revert.
#include <gtest/gtest.h>

#include <signal.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <nlohmann/json.hpp>

#include "../common/run_command.h"
#include "../common/watch_log.h"
#include "common/paths.h"
#include "eval/image.h"

namespace fs = std::filesystem;

namespace {

using wb::testing::readFile;
using wb::testing::readLog;
using wb::testing::writeFile;

// Events are waited for with a generous cap (a busy machine makes a reload plus its comparison take tens of
// seconds), never for a fixed time.
constexpr double kEventCapSeconds = 400;

std::vector<nlohmann::json> waitForLog(const fs::path& p, size_t n) {
  return wb::testing::waitForLog(p, n, kEventCapSeconds);
}

std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return text;
}

// A `watch --headless --ab` child on a private copy of the shaders, stopped (SIGINT, by its process id) when
// the test ends, also after a failed assertion.
class WatchChild {
 public:
  explicit WatchChild(const std::string& flags) {
    root = fs::temp_directory_path() / ("wb_abwatch_" + std::to_string(::getpid()));
    fs::remove_all(root);
    fs::create_directories(root / "shader_cache");
    fs::copy(wb::projectRoot() / "shaders", root / "shaders", fs::copy_options::recursive);
    fs::copy(wb::projectRoot() / "assets", root / "assets", fs::copy_options::recursive);
    log = root / "reloads.jsonl";
    out = root / "watch.out";
    const fs::path pidFile = root / "watch.pid";
    const std::string cmd = "WB_ROOT=" + root.string() + " " + wb::testing::kOwnSession +
                            "sh -c 'echo $$ > " + pidFile.string() + "; exec " + WB_WORKBENCH_BIN +
                            " watch --headless " + flags + " --log " + log.string() + "' > " + out.string() +
                            " 2>&1";
    proc_ = popen(cmd.c_str(), "r");
    const auto started = std::chrono::steady_clock::now();
    while (proc_ && readFile(out).find("watching") == std::string::npos &&
           readFile(out).find("error") == std::string::npos &&
           std::chrono::steady_clock::now() - started < std::chrono::seconds(int(kEventCapSeconds))) {
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
    pid_ = std::atoi(readFile(pidFile).c_str());
  }
  ~WatchChild() {
    stop();
    fs::remove_all(root);
  }
  bool running() const { return proc_ && readFile(out).find("watching") != std::string::npos; }
  int stop() {
    if (!proc_) return -1;
    if (pid_ > 0) kill(pid_, SIGINT);
    const int status = pclose(proc_);
    proc_ = nullptr;
    return status;
  }

  fs::path root, log, out;

 private:
  FILE* proc_ = nullptr;
  pid_t pid_ = 0;
};

const char* kAbKeys[] = {"image_verdict",
                         "rmse",
                         "rel_mse",
                         "max_abs_diff",
                         "changed_pixel_fraction",
                         "mean_shift_significant",
                         "speed_ratio",
                         "speed_ratio_spread",
                         "speed_verdict"};

// The line has an "ab" with exactly the documented keys, and the same in its per-pipeline list.
void expectAbShape(const nlohmann::json& line) {
  ASSERT_TRUE(line.contains("ab")) << line.dump();
  const auto& ab = line["ab"];
  EXPECT_EQ(ab.size(), std::size(kAbKeys)) << ab.dump();
  for (const char* k : kAbKeys) EXPECT_TRUE(ab.contains(k)) << k << ": " << ab.dump();
  EXPECT_EQ(ab["speed_ratio_spread"].size(), 2u);
  ASSERT_GE(line["ab_pipelines"].size(), 1u) << line.dump();
  EXPECT_EQ(line["ab_pipelines"][0]["ab"], ab);
  EXPECT_TRUE(line["ab_pipelines"][0]["active"].get<bool>());
  EXPECT_GT(line["ab_ms"].get<double>(), 0.0);
}

}  // namespace

TEST(ABWatch, EditsAnswerBothQuestions) {
  WatchChild w("--size 32x32 --ab");
  ASSERT_TRUE(w.running()) << readFile(w.out);
  const fs::path chit = w.root / "shaders/pathtracer/closesthit.rchit";
  const std::string good = readFile(chit);

  // A comment: the SPIR-V is the same, nothing is rebuilt and there is nothing to compare.
  writeFile(chit, good + "\n// a comment only\n");
  auto lines = waitForLog(w.log, 1);
  ASSERT_EQ(lines.size(), 1u) << readFile(w.out);
  EXPECT_TRUE(lines[0]["pipelines_rebuilt"].empty()) << lines[0].dump();
  EXPECT_FALSE(lines[0].contains("ab")) << lines[0].dump();

  // A refactor computing the same values in another order (a*b + c as c + b*a): other SPIR-V, a rebuild, and
  // the same image up to float rounding.
  const std::string refactored = replaced(good, "ns = normalize(ns + (minCos - nsDotWo) * wo);",
                                          "ns = normalize(wo * (minCos - nsDotWo) + ns);");
  writeFile(chit, refactored);
  lines = waitForLog(w.log, 2);
  ASSERT_EQ(lines.size(), 2u) << readFile(w.out);
  EXPECT_EQ(lines[1]["pipelines_rebuilt"], nlohmann::json::array({"pathtracer"}));
  expectAbShape(lines[1]);
  const std::string refactorVerdict = lines[1]["ab"]["image_verdict"].get<std::string>();
  EXPECT_TRUE(refactorVerdict == "identical" || refactorVerdict == "rounding") << lines[1]["ab"].dump();
  EXPECT_EQ(lines[1]["ab"]["changed_pixel_fraction"].get<double>(), 0.0);
  EXPECT_FALSE(lines[1]["ab"]["mean_shift_significant"].get<bool>());

  // Every albedo scaled by 1.02: changed, and the mean moved far beyond its noise.
  writeFile(chit, replaced(refactored, "  sm.baseColor = baseColor.rgb;",
                           "  sm.baseColor = baseColor.rgb * 1.02;"));
  lines = waitForLog(w.log, 3);
  ASSERT_EQ(lines.size(), 3u) << readFile(w.out);
  expectAbShape(lines[2]);
  EXPECT_EQ(lines[2]["ab"]["image_verdict"], "changed") << lines[2]["ab"].dump();
  EXPECT_TRUE(lines[2]["ab"]["mean_shift_significant"].get<bool>()) << lines[2]["ab"].dump();
  EXPECT_GT(lines[2]["ab"]["changed_pixel_fraction"].get<double>(), 0.0);
  EXPECT_GT(lines[2]["ab"]["rmse"].get<double>(), 0.0);
  EXPECT_GT(lines[2]["ab"]["max_abs_diff"].get<double>(), 0.0);

  // Wasted work in closest-hit (a long chain of sines whose result decides a branch the compiler cannot rule
  // out, never taken): the same image, and many times the work per hit. Every timing round must see the new
  // pipeline slower by more than the margin: with thousands of dependent sines per hit the new pipeline is
  // several times slower, far beyond what two busy loops beside the test do to alternating back-to-back
  // measurements (they slow both sides of a round alike).
  const std::string wasteful =
      replaced(good, "  payload.geoNormal = ng;\n",
               "  payload.geoNormal = ng;\n"
               "  float wbWaste = gl_HitTEXT;\n"
               "  for (int i = 0; i < 3000; ++i) wbWaste = sin(wbWaste) * 0.999 + 0.5;\n"
               "  if (wbWaste > 1e30) payload.hitT = wbWaste;\n");
  writeFile(chit, good);  // back to the start: the wasted work is compared against the original
  lines = waitForLog(w.log, 4);
  ASSERT_EQ(lines.size(), 4u) << readFile(w.out);
  writeFile(chit, wasteful);
  lines = waitForLog(w.log, 5);
  ASSERT_EQ(lines.size(), 5u) << readFile(w.out);
  expectAbShape(lines[4]);
  EXPECT_EQ(lines[4]["ab"]["speed_verdict"], "slower") << lines[4]["ab"].dump();
  EXPECT_LT(lines[4]["ab"]["speed_ratio"].get<double>(), 1.0);
  EXPECT_LT(lines[4]["ab"]["speed_ratio_spread"][1].get<double>(), 1.0);
  const std::string wasteVerdict = lines[4]["ab"]["image_verdict"].get<std::string>();
  EXPECT_TRUE(wasteVerdict == "identical" || wasteVerdict == "rounding") << lines[4]["ab"].dump();

  // The revert: never "slower" (it removes the work; "faster" is what it measures, but the assertion is only
  // the robust half: whether a change is called faster or within noise depends on the load beside it).
  writeFile(chit, good);
  lines = waitForLog(w.log, 6);
  ASSERT_EQ(lines.size(), 6u) << readFile(w.out);
  expectAbShape(lines[5]);
  EXPECT_NE(lines[5]["ab"]["speed_verdict"], "slower") << lines[5]["ab"].dump();
  EXPECT_GT(lines[5]["ab"]["speed_ratio"].get<double>(), 1.0);

  EXPECT_EQ(WEXITSTATUS(w.stop()), 0) << readFile(w.out);
}

TEST(ABWatch, EmissionScaleChangesExactlyTheEmitterPixels) {
  // Only the emission seen by camera rays: a black environment, no bounce, no light sampling. The pixels an
  // emission edit affects are then exactly those where the old image is not black.
  const std::string diffDir =
      (fs::temp_directory_path() / ("wb_abwatch_diff_" + std::to_string(::getpid()))).string();
  fs::remove_all(diffDir);
  WatchChild w("--size 32x32 --ab --ab-size 48x48 --ab-spp 3 --ab-diff-dir " + diffDir +
               " --env-color 0,0,0 --max-bounces 0 --no-nee");
  ASSERT_TRUE(w.running()) << readFile(w.out);
  const fs::path chit = w.root / "shaders/pathtracer/closesthit.rchit";
  writeFile(chit, replaced(readFile(chit), "radiance += emissive * w;", "radiance += emissive * 1.02 * w;"));
  const auto lines = waitForLog(w.log, 1);
  ASSERT_EQ(lines.size(), 1u) << readFile(w.out);
  expectAbShape(lines[0]);
  const auto& ab = lines[0]["ab"];
  EXPECT_EQ(ab["image_verdict"], "changed") << ab.dump();
  EXPECT_TRUE(ab["mean_shift_significant"].get<bool>()) << ab.dump();

  const auto oldImage = wb::eval::readExr(fs::path(diffDir) / "reload1_0_old.exr");
  const auto diff = wb::eval::readExr(fs::path(diffDir) / "reload1_0_diff.exr");
  ASSERT_EQ(oldImage.width, 48u);
  ASSERT_EQ(diff.height, 48u);
  size_t lit = 0, mismatched = 0;
  for (uint32_t y = 0; y < 48; ++y) {
    for (uint32_t x = 0; x < 48; ++x) {
      bool emitter = false, changed = false;
      for (int c = 0; c < 3; ++c) {
        emitter = emitter || oldImage.at(x, y, c) > 0.0f;
        changed = changed || diff.at(x, y, c) > 0.0f;
      }
      lit += emitter;
      mismatched += emitter != changed;
    }
  }
  EXPECT_GT(lit, 0u) << "the camera sees the light";
  EXPECT_LT(lit, 48u * 48u);
  EXPECT_EQ(mismatched, 0u) << "the difference is non-zero exactly on the emitter's pixels";
  EXPECT_DOUBLE_EQ(ab["changed_pixel_fraction"].get<double>(), double(lit) / (48.0 * 48.0)) << ab.dump();
  EXPECT_EQ(WEXITSTATUS(w.stop()), 0) << readFile(w.out);
  fs::remove_all(diffDir);
}

// The hybrid mode, through the same renderer interface: an include shared by several of its pipelines (the
// alpha test, in the G-buffer and the shadow/AO pass) rewritten to an equivalent comparison rebuilds each of
// them and compares each one (same image); an edit of the composite pass changes the image.
TEST(ABWatch, HybridPipelinesAndASharedIncludeAreCompared) {
  WatchChild w("--size 32x32 --ab --mode hybrid");
  ASSERT_TRUE(w.running()) << readFile(w.out);
  const fs::path common = w.root / "shaders/hybrid/common.glsl";
  writeFile(
      common,
      replaced(readFile(common), "{ return alphaRejected(m, alpha, WB_ALPHA_BLEND_AS_MASK); }",
               "{\n  return m.alphaMode != WB_ALPHA_OPAQUE &&\n         (m.alphaMode == WB_ALPHA_MASK ? "
               "m.alphaCutoff : WB_ALPHA_BLEND_AS_MASK) > alpha;\n}"));
  auto lines = waitForLog(w.log, 1);
  ASSERT_EQ(lines.size(), 1u) << readFile(w.out);
  ASSERT_TRUE(lines[0]["ok"].get<bool>()) << lines[0].dump();
  const auto& rebuilt = lines[0]["pipelines_rebuilt"];
  ASSERT_GE(rebuilt.size(), 2u) << lines[0].dump();
  expectAbShape(lines[0]);
  EXPECT_EQ(lines[0]["ab_pipelines"].size(), rebuilt.size()) << "one comparison per rebuilt pipeline";
  for (const auto& p : lines[0]["ab_pipelines"]) {
    const std::string v = p["ab"]["image_verdict"].get<std::string>();
    EXPECT_TRUE(v == "identical" || v == "rounding") << p.dump();
  }

  const fs::path composite = w.root / "shaders/hybrid/composite.comp";
  writeFile(composite, replaced(readFile(composite), "vec3 background = envRadiance(dir);",
                                "vec3 background = envRadiance(dir) * 1.02;"));
  lines = waitForLog(w.log, 2);
  ASSERT_EQ(lines.size(), 2u) << readFile(w.out);
  expectAbShape(lines[1]);
  EXPECT_EQ(lines[1]["ab"]["image_verdict"], "changed") << lines[1].dump();
  EXPECT_GT(lines[1]["ab"]["changed_pixel_fraction"].get<double>(), 0.0) << lines[1].dump();
  EXPECT_EQ(WEXITSTATUS(w.stop()), 0) << readFile(w.out);
}
