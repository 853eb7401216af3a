// The path tracer's cost, print and asserts variants through the real `workbench` binary, on a private copy
// of shaders/ (WB_ROOT) that each test edits the way a user would: a closest-hit made expensive for one
// material, a wbPrint added, a zero-pdf bug injected.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>
#include <stb/stb_image.h>

#include "../common/run_command.h"
#include "../common/temp_folder.h"
#include "common/paths.h"
#include "eval/image.h"

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

fs::path tempDir(const std::string& name) {
  return wb::testing::tempFolder("wb_debug_variants", name);
}

std::string readText(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

json readJson(const fs::path& p) {
  return json::parse(readText(p));
}

// A private copy of shaders/ and assets/ with `edits` applied to shaders/<file>: each replaces the first
// occurrence of its `find` text (the test fails when the text is not there: the shader moved on).
struct Edit {
  std::string file, find, replace;
};
fs::path editedRoot(const std::string& name, const std::vector<Edit>& edits) {
  const fs::path root = tempDir(name);
  fs::copy(wb::projectRoot() / "shaders", root / "shaders", fs::copy_options::recursive);
  fs::create_directory_symlink(wb::projectRoot() / "assets", root / "assets");
  for (const auto& e : edits) {
    const fs::path f = root / "shaders" / e.file;
    std::string text = readText(f);
    const size_t at = text.find(e.find);
    if (at == std::string::npos) {
      ADD_FAILURE() << e.file << " no longer holds: " << e.find;
      continue;
    }
    text.replace(at, e.find.size(), e.replace);
    std::ofstream(f, std::ios::binary | std::ios::trunc) << text;
  }
  return root;
}

wb::testing::CommandResult workbench(const std::string& args, const fs::path& root = {}) {
  std::string env = "env";
  if (!root.empty()) env += " WB_ROOT=" + root.string() + " WB_SHADER_CACHE_DIR=" + (root / "cache").string();
  return wb::testing::runCommand(env + " timeout 600 " + std::string(WB_WORKBENCH_BIN) + " " + args);
}

double median(std::vector<double> v) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

const char* kAssertLabel = "pdf > 0";  // raygen's wbAssert on the continuation's pdf

}  // namespace

// wbAssert(pdf > 0) in raygen catches an injected bug (closest-hit hands back a zero pdf for the pixels of
// the image's first 4 columns) at every pixel where it happens and nowhere else; the unedited shaders pass.
TEST(DebugVariants, AssertCatchesAZeroPdfExactlyWhereItHappens) {
  const fs::path d = tempDir("asserts");
  const auto clean = workbench("render --size 24x24 --spp 2 --max-bounces 2 --asserts --out " +
                               (d / "clean.png").string() + " --stats " + (d / "clean.json").string());
  ASSERT_EQ(clean.code, 0) << clean.output;
  EXPECT_EQ(readJson(d / "clean.json")["asserts"]["failures"], 0);

  const fs::path root =
      editedRoot("asserts_root",
                 {{"pathtracer/closesthit.rchit", "  payload.pdf = s.pdf;",
                   "  payload.pdf = gl_LaunchIDEXT.x + pc.tileOffset.x < 4u ? 0.0 : s.pdf;  // the bug"}});
  const auto r = workbench("render --size 24x24 --spp 2 --max-bounces 2 --asserts --aov albedo --out " +
                               (d / "bug.exr").string() + " --stats " + (d / "bug.json").string(),
                           root);
  EXPECT_EQ(r.code, 1) << r.output;  // failures make the exit status 1
  EXPECT_NE(r.output.find("assert failed: 'pdf > 0' at pixel"), std::string::npos) << r.output;
  const json a = readJson(d / "bug.json")["asserts"];
  const uint32_t failures = a["failures"];
  ASSERT_GT(failures, 0u);
  ASSERT_EQ(a["recorded"], failures) << "the records hold every failure of this small image";
  std::set<std::pair<int, int>> failed;
  for (const auto& f : a["first"]) {
    const int x = f["pixel"][0], y = f["pixel"][1];
    EXPECT_LT(x, 4) << "a failure where the bug is not: " << f.dump();
    EXPECT_EQ(f["label"], kAssertLabel);
    EXPECT_EQ(f["stage"], "raygen");
    EXPECT_TRUE(f["bounce"].is_number());
    EXPECT_LT(f["sample"].get<int>(), 2);
    failed.insert({x, y});
  }
  // Where the bug happens: the pixels of the 4 columns whose camera path continues from its first vertex,
  // all but those on the ceiling light (black base colour: the path ends there with zero throughput, before
  // raygen looks at the pdf).
  const auto albedo = wb::eval::readExr(d / "bug.albedo.exr");
  std::set<std::pair<int, int>> continued;
  for (int y = 0; y < 24; ++y)
    for (int x = 0; x < 4; ++x)
      if (albedo.at(x, y, 0) + albedo.at(x, y, 1) + albedo.at(x, y, 2) > 0.0f) continued.insert({x, y});
  EXPECT_GT(continued.size(), 4u * 24u / 2);
  EXPECT_EQ(failed, continued);

  // Asked for launches of 4 samples, the asserts variant still traces one sample at a time: its failures come
  // in sample order, each with its own sample.
  const auto deep =
      workbench("render --size 24x24 --spp 4 --samples-per-launch 4 --max-bounces 2 --asserts --out " +
                    (d / "deep.png").string() + " --stats " + (d / "deep.json").string(),
                root);
  EXPECT_EQ(deep.code, 1) << deep.output;
  const json deepFirst = readJson(d / "deep.json")["asserts"]["first"];
  ASSERT_FALSE(deepFirst.empty());
  int lastSample = 0;
  for (const auto& f : deepFirst) {
    EXPECT_GE(f["sample"].get<int>(), lastSample) << f.dump();
    lastSample = f["sample"].get<int>();
  }
  EXPECT_EQ(lastSample, 3);

  // OUT.asserts.png marks exactly the failing pixels (magenta) on the dimmed image.
  int w = 0, h = 0, n = 0;
  unsigned char* px = stbi_load((d / "bug.asserts.png").c_str(), &w, &h, &n, 4);
  ASSERT_NE(px, nullptr);
  ASSERT_EQ(w, 24);
  std::set<std::pair<int, int>> marked;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const unsigned char* p = px + (size_t(y) * w + x) * 4;
      if (p[0] == 255 && p[1] == 0 && p[2] == 255) marked.insert({x, y});
    }
  stbi_image_free(px);
  EXPECT_EQ(marked, failed);
}

// wbPrint of closest-hit's BRDF sample at the inspected pixel equals what the path inspector records for the
// same vertex, in sample and bounce order.
TEST(DebugVariants, PrintEqualsTheInspectorsRecordOfTheVertex) {
  const fs::path root = editedRoot(
      "print_root", {{"pathtracer/closesthit.rchit", "  if (s.pdf <= 0.0 || dot(s.wi, ng) <= 0.0) {",
                      "  wbPrint(\"pdf\", s.pdf);\n  wbPrint(\"direction\", s.wi);\n"
                      "  if (s.pdf <= 0.0 || dot(s.wi, ng) <= 0.0) {"}});
  const fs::path d = tempDir("print");
  const auto r = workbench(
      "render --size 32x32 --spp 6 --inspect-pixel 16,20 --inspect-out " + (d / "i.json").string(), root);
  ASSERT_EQ(r.code, 0) << r.output;
  const json j = readJson(d / "i.json");
  ASSERT_EQ(j["samples"].size(), 6u);
  size_t compared = 0;
  for (const auto& s : j["samples"]) {
    const auto& vertices = s["vertices"];
    const auto& prints = s["prints"];
    // Two prints per closest-hit that got to sampling, in bounce order.
    ASSERT_EQ(prints.size(), 2 * vertices.size()) << s.dump();
    EXPECT_EQ(s["prints_made"], prints.size());
    for (size_t k = 0; k < vertices.size(); ++k) {
      const auto& pdf = prints[2 * k];
      const auto& dir = prints[2 * k + 1];
      EXPECT_EQ(pdf["label"], "pdf");
      EXPECT_EQ(dir["label"], "direction");
      EXPECT_EQ(pdf["stage"], "closest_hit");
      EXPECT_EQ(pdf["bounce"], k);
      EXPECT_EQ(pdf["type"], "float");
      EXPECT_EQ(pdf["value"], vertices[k]["pdf"]) << "sample " << s["sample"] << " vertex " << k;
      EXPECT_EQ(dir["value"], vertices[k]["direction"]) << "sample " << s["sample"] << " vertex " << k;
      ++compared;
    }
  }
  EXPECT_GE(compared, 6u);
  // The per-vertex cost: the shader clock's share of each trace call, within the sample's.
  ASSERT_NE(j["clock"], "none") << "lavapipe has VK_KHR_shader_clock";
  for (const auto& s : j["samples"]) {
    double parts = s["escape_clocks"].is_number() ? s["escape_clocks"].get<double>() : 0.0;
    for (const auto& v : s["vertices"]) {
      ASSERT_TRUE(v["cost"].is_object());
      parts += v["cost"]["trace_clocks"].get<double>() + v["cost"]["shade_clocks"].get<double>() +
               v["cost"]["shadow_clocks"].get<double>();
    }
    EXPECT_GT(parts, 0.0);
    EXPECT_LE(parts, s["clocks"].get<double>());
  }
}

// A define that adds work to one material's closest-hit: the cost map ranks that material's pixels at least
// 3x their neighbours', and the frame's clocks grow with it. The path tracer's GPU time per sample
// (`pass_ms`) is printed beside them, not asserted: it is a wall time on a shared machine.
TEST(DebugVariants, CostRanksAnExpensiveMaterialAndTheFrameClocksGrow) {
  // The loop's value decides the status the shader returns (a value the loop can reach: it stays within
  // [-0.5, 1.5]), so that no compiler can prove it dead and drop it: a store the shader overwrites later,
  // or a comparison with a value out of sin()'s range, let NVIDIA's compiler remove it. Its trip count is the
  // material's (0 elsewhere) rather than a branch around a fixed-count loop, which a compiler may run for
  // every hit with the result selected afterwards.
  const fs::path root =
      editedRoot("cost_root",
                 {{"pathtracer/closesthit.rchit", "  const Material m = materials[g.materialIndex];\n",
                   "  const Material m = materials[g.materialIndex];\n"
                   "#ifdef WB_EXPENSIVE_MATERIAL\n"
                   "  float expensiveX = gl_HitTEXT;\n"
                   "  const int expensiveWork = g.materialIndex == WB_EXPENSIVE_MATERIAL ? 8000 : 0;\n"
                   "  for (int i = 0; i < expensiveWork; ++i) expensiveX = sin(expensiveX) * 1.0001 + 0.5;\n"
                   "#endif\n"},
                  {"pathtracer/closesthit.rchit", "  payload.status = PAYLOAD_CONTINUE;\n",
                   "#ifdef WB_EXPENSIVE_MATERIAL\n"
                   "  payload.status = expensiveX == 0.7071234 ? PAYLOAD_ABSORBED : PAYLOAD_CONTINUE;\n"
                   "#else\n"
                   "  payload.status = PAYLOAD_CONTINUE;\n"
                   "#endif\n"}});
  const fs::path d = tempDir("cost");
  struct Run {
    double redCost = 0, otherCost = 0, passMs = 0, frameClocks = 0;
    std::string lanes;  // "isolated" | "shared" (DevicePolicy::costIsolatesLanes)
  };
  auto render = [&](const std::string& name, const std::string& define) {
    const fs::path out = d / (name + ".exr");
    const auto r = workbench("render --size 48x48 --spp 6 --max-bounces 1 --aov albedo,cost --out " +
                                 out.string() + " --stats " + (d / (name + ".json")).string() + define,
                             root);
    EXPECT_EQ(r.code, 0) << r.output;
    const auto albedo = wb::eval::readExr(d / (name + ".albedo.exr"));
    const auto cost = wb::eval::readExr(d / (name + ".cost.exr"));
    std::vector<double> red, other;
    for (uint32_t y = 0; y < cost.height; ++y)
      for (uint32_t x = 0; x < cost.width; ++x) {
        // The red wall (material 1): base colour 0.63, 0.065, 0.05.
        const bool isRed = std::abs(albedo.at(x, y, 0) - 0.63f) < 0.01f && albedo.at(x, y, 1) < 0.1f;
        (isRed ? red : other).push_back(cost.at(x, y, 3));  // a: the pixel's median clocks per sample
      }
    EXPECT_GT(red.size(), 100u) << "the red wall is in view";
    const json s = readJson(d / (name + ".json"));
    return Run{median(red), median(other), s["pass_ms"]["pathtracer"].get<double>(),
               s["cost"]["frame_clocks"].get<double>(), s["cost"]["lanes"].get<std::string>()};
  };
  const Run plain = render("plain", "");
  const Run expensive = render("expensive", " --define WB_EXPENSIVE_MATERIAL=1");
  ASSERT_GT(plain.otherCost, 0.0);
  EXPECT_LT(plain.redCost, 2.0 * plain.otherCost) << "without the define the red wall costs as the rest";
  EXPECT_GE(expensive.redCost, 3.0 * expensive.otherCost);
  // The frame's clocks grow with the material's work, and the pass's GPU time with them.
  const double clockGrowth = expensive.frameClocks / plain.frameClocks;
  std::printf(
      "red wall / rest: %.2fx plain, %.2fx expensive; frame clocks x%.2f, pass_ms %.2f -> %.2f; lanes %s\n",
      plain.redCost / plain.otherCost, expensive.redCost / expensive.otherCost, clockGrowth, plain.passMs,
      expensive.passMs, expensive.lanes.c_str());
  EXPECT_TRUE(expensive.lanes == "isolated" || expensive.lanes == "shared") << expensive.lanes;
  EXPECT_GT(clockGrowth, 1.5);
  EXPECT_GT(plain.passMs, 0.0) << "the stats report the pass's GPU time";
  EXPECT_GT(expensive.passMs, 0.0);
}

// The cost variant renders the default variant's image: its clocks change no path (and with lane isolation,
// WB_COST_ISOLATE=1 on a device that has it, the lane that traces a pixel does not change its random
// numbers). The default scene has an alpha-tested leaf: any-hit's stochastic transparency reads the pixel
// too.
TEST(DebugVariants, TheCostVariantRendersTheDefaultImage) {
  const fs::path d = tempDir("cost_image");
  auto render = [&](const std::string& name, const std::string& flags) {
    const auto r = wb::testing::runCommand(
        "timeout 600 " + std::string(WB_WORKBENCH_BIN) + " render --size 40x40 --spp 4 --out " +
        (d / (name + ".exr")).string() + " --stats " + (d / (name + ".json")).string() + flags);
    EXPECT_EQ(r.code, 0) << r.output;
    return wb::eval::readExr(d / (name + ".exr"));
  };
  const auto plain = render("plain", "");
  const auto cost = render("cost", " --aov cost");
  ASSERT_EQ(plain.pixels.size(), cost.pixels.size());
  double meanPlain = 0, meanCost = 0, maxRel = 0;
  for (size_t i = 0; i < plain.pixels.size(); ++i) {
    if (i % 4 == 3) continue;
    meanPlain += plain.pixels[i];
    meanCost += cost.pixels[i];
    // Equal up to floating-point reassociation in the compiled code.
    maxRel = std::max(maxRel, std::abs(double(plain.pixels[i]) - cost.pixels[i]) /
                                  (std::abs(double(plain.pixels[i])) + 1e-2));
  }
  const std::string lanes = readJson(d / "cost.json")["cost"]["lanes"].get<std::string>();
  std::printf("cost variant (lanes %s) against the default: largest relative difference %.3g\n",
              lanes.c_str(), maxRel);
  EXPECT_GT(meanPlain, 0.0);
  EXPECT_NEAR(meanCost / meanPlain, 1.0, 1e-4) << "lanes " << lanes;
  EXPECT_LT(maxRel, 1e-2) << "lanes " << lanes;
}

// Without a shader clock (WB_SHADER_CLOCK=0 stands for a device without VK_KHR_shader_clock) the cost map
// says so and the render still works.
TEST(DebugVariants, CostWithoutAShaderClockSaysSo) {
  const fs::path d = tempDir("noclock");
  const auto r =
      wb::testing::runCommand("env WB_SHADER_CLOCK=0 timeout 600 " + std::string(WB_WORKBENCH_BIN) +
                              " render --size 16x16 --spp 1 --aov cost --out " + (d / "o.png").string() +
                              " --stats " + (d / "s.json").string());
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("no shader clock"), std::string::npos) << r.output;
  const json s = readJson(d / "s.json");
  EXPECT_EQ(s["cost"]["clock"], "none");
  EXPECT_EQ(s["cost"]["lanes"], "shared") << "without a clock nothing is isolated";
  EXPECT_TRUE(fs::exists(d / "o.cost.png"));
  EXPECT_TRUE(s["pass_ms"]["pathtracer"].is_number());
}
