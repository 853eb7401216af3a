// `workbench converge` as a user runs it: files written, CSV columns, one-line errors for bad configurations.
#include <gtest/gtest.h>

#include <unistd.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>

#include "../common/run_command.h"
#include <vector>

namespace fs = std::filesystem;

namespace {

using Result = wb::testing::CommandResult;

// `workbench converge ARGS`, with optional NAME=VALUE environment settings before it.
Result run(const std::string& args, const std::string& env = "") {
  return wb::testing::runCommand("env " + env + " " + WB_WORKBENCH_BIN + " converge " + args);
}

fs::path tempDir(const std::string& name) {
  fs::path d = fs::temp_directory_path() / ("wb_converge_" + std::to_string(::getpid())) / name;
  fs::remove_all(d);
  return d;
}

}  // namespace

TEST(ConvergeCli, WritesCsvPlotSummaryAndErrorImages) {
  const auto dir = tempDir("ok");
  const Result r =
      run("--size 16x16 --seconds 0.3 --runs 2 --reference-spp 32 --config 'a:' --config "
          "'b4:--max-bounces 4' --out " +
          dir.string());
  ASSERT_EQ(r.code, 0) << r.output;
  // Progress lines (plain lines, not a terminal) name the phase and give an ETA.
  EXPECT_NE(r.output.find("converge: [2/2] b4 run 2 ["), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("ETA"), std::string::npos) << r.output;
  ASSERT_TRUE(fs::exists(dir / "converge.csv"));
  ASSERT_TRUE(fs::exists(dir / "converge.md"));
  EXPECT_TRUE(fs::exists(dir / "error_a.png"));
  EXPECT_TRUE(fs::exists(dir / "error_b4.png"));
  std::ifstream csv(dir / "converge.csv");
  std::string header, first;
  std::getline(csv, header);
  std::getline(csv, first);
  EXPECT_EQ(header.rfind("config,flags,spp,seconds,", 0), 0u) << header;
  EXPECT_NE(header.find(",rmse,relmse,variance,"), std::string::npos) << header;
  EXPECT_EQ(first.rfind("a,\"\",1,", 0), 0u) << first;  // the first checkpoint is 1 spp
  std::ifstream md(dir / "converge.md");
  const std::string text((std::istreambuf_iterator<char>(md)), std::istreambuf_iterator<char>());
  EXPECT_NE(text.find("Reference: "), std::string::npos);
  EXPECT_NE(text.find("| b4 | `--max-bounces 4` |"), std::string::npos) << text;
  if (std::system("command -v gnuplot > /dev/null 2>&1") == 0) {
    EXPECT_TRUE(fs::exists(dir / "converge.png")) << r.output;
  } else {
    EXPECT_NE(text.find("Plot missing"), std::string::npos);
  }
}

TEST(ConvergeCli, BadConfigurationsAreOneLineErrors) {
  const auto dir = tempDir("bad");
  for (const char* cfg : {"--config nocolon", "--config 'x:--size 8x8'", "--config 'x:--bogus'",
                          "--config 'x:--sampler nope'"}) {
    const Result r = run(std::string("--size 16x16 --reference-spp 4 ") + cfg + " --out " + dir.string());
    EXPECT_EQ(r.code, 2) << cfg << ": " << r.output;
    EXPECT_NE(r.output.find("workbench converge: error:"), std::string::npos) << r.output;
  }
  const Result both = run("--reference x.exr --reference-spp 4 --out " + dir.string());
  EXPECT_EQ(both.code, 2) << both.output;
}

// Hybrid modes are configurations like any other: compared with the path-traced reference at equal time. With
// hard shadows and no AO the hybrid image is deterministic (no variance between runs), unlike the path
// tracer's, and its error is the approximation's bias.
TEST(ConvergeCli, HybridModeConfigurationsRunTheHybridRenderer) {
  const auto dir = tempDir("modes");
  const Result r =
      run("--size 16x16 --seconds 0.3 --runs 2 --reference-spp 32 --config 'pt:' --config 'hy:--mode hybrid "
          "--ao-rays 0 --sun-angle 0' --out " +
          dir.string());
  ASSERT_EQ(r.code, 0) << r.output;
  std::ifstream csv(dir / "converge.csv");
  std::string line;
  std::getline(
      csv, line);  // header: config,flags,spp,seconds,seconds_min,seconds_max,runs,mse,rmse,relmse,variance
  std::map<std::string, std::vector<std::string>> last;
  while (std::getline(csv, line)) {
    // flags are quoted and contain no commas here
    std::vector<std::string> cols;
    std::stringstream ss(line);
    for (std::string c; std::getline(ss, c, ',');) cols.push_back(c);
    ASSERT_GE(cols.size(), 11u) << line;
    last[cols[0]] = cols;
  }
  ASSERT_TRUE(last.count("pt") && last.count("hy")) << r.output;
  EXPECT_GT(std::stod(last["pt"][10]), 0.0) << "the path tracer's runs differ";
  EXPECT_LT(std::stod(last["hy"][10]), 1e-10) << "deterministic hybrid frames are identical between runs";
  EXPECT_GT(std::stod(last["hy"][7]), 0.0) << "the hybrid image is not the reference";
}

// Without --reference the command renders a reference once and caches it; the key includes the shaders'
// sources, so an edit of any shader renders a new one instead of comparing against a stale image.
TEST(ConvergeCli, CachedReferenceIsReusedUntilAShaderChanges) {
  const auto root = tempDir("root");
  fs::create_directories(root);
  fs::copy(fs::path(WB_SOURCE_DIR) / "shaders", root / "shaders", fs::copy_options::recursive);
  fs::copy(fs::path(WB_SOURCE_DIR) / "assets", root / "assets", fs::copy_options::recursive);
  const std::string env =
      "WB_ROOT=" + root.string() + " WB_SHADER_CACHE_DIR=" + (root / "cache").string() + " ";
  auto converge = [&](const std::string& out) {
    const Result r = run(
        "--size 8x8 --seconds 0.05 --runs 1 --reference-spp 4 --config 'a:' --out " + (root / out).string(),
        env);
    std::ifstream md(root / out / "converge.md");
    return std::make_pair(
        r, std::string((std::istreambuf_iterator<char>(md)), std::istreambuf_iterator<char>()));
  };
  auto [r1, md1] = converge("one");
  ASSERT_EQ(r1.code, 0) << r1.output;
  EXPECT_NE(md1.find("rendered now by this command and cached"), std::string::npos) << md1;
  auto [r2, md2] = converge("two");
  ASSERT_EQ(r2.code, 0) << r2.output;
  EXPECT_NE(md2.find("cached render of the same scene"), std::string::npos) << md2;
  std::ofstream(root / "shaders/pathtracer/closesthit.rchit", std::ios::app) << "\n// an edit\n";
  auto [r3, md3] = converge("three");
  ASSERT_EQ(r3.code, 0) << r3.output;
  EXPECT_NE(md3.find("rendered now by this command and cached"), std::string::npos) << md3;
}
