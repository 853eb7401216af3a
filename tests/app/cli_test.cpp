// The `workbench` binary as outside scripts use it: flags, exit codes, one-line errors, written files.
#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

#include "common/paths.h"

namespace fs = std::filesystem;

namespace {

struct CommandResult {
  int code = -1;
  std::string output;  // stdout + stderr
};

CommandResult run(const std::string& args) {
  CommandResult r;
  std::string cmd = std::string(WB_WORKBENCH_BIN) + " " + args + " 2>&1";
  FILE* p = popen(cmd.c_str(), "r");
  if (!p) return r;
  std::array<char, 4096> buf;
  size_t n;
  while ((n = fread(buf.data(), 1, buf.size(), p)) > 0) r.output.append(buf.data(), n);
  int status = pclose(p);
  r.code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  return r;
}

fs::path tempDir() {
  fs::path d = fs::temp_directory_path() / ("wb_cli_" + std::to_string(::getpid()));
  fs::create_directories(d);
  return d;
}

size_t lineCount(const std::string& s) {
  size_t n = 0;
  for (char c : s) n += c == '\n';
  return n;
}

}  // namespace

TEST(Cli, RenderWritesPngAndStats) {
  const auto dir = tempDir();
  const auto png = dir / "box.png", stats = dir / "box.json";
  CommandResult r = run("render " + (wb::sharedDir() / "assets/gltf/Box/glTF-Embedded/Box.gltf").string() +
                        " --size 32x24 --spp 2 --out " + png.string() + " --stats " + stats.string());
  ASSERT_EQ(r.code, 0) << r.output;
  ASSERT_TRUE(fs::exists(png));
  EXPECT_GT(fs::file_size(png), 100u);
  std::ifstream f(stats);
  auto j = nlohmann::json::parse(f);
  EXPECT_EQ(j["width"], 32);
  EXPECT_EQ(j["height"], 24);
  EXPECT_EQ(j["spp"], 2);
  EXPECT_FALSE(j["device"].get<std::string>().empty());
  EXPECT_GT(j["seconds"].get<double>(), 0.0);
  EXPECT_GT(j["samples_per_second"].get<double>(), 0.0);
  EXPECT_GT(j["rays_per_second"].get<double>(), 0.0);
  EXPECT_EQ(j["nan_inf_dropped"], 0);
  ASSERT_EQ(j["mean_rgb"].size(), 3u);
}

TEST(Cli, RenderWritesExr) {
  const auto exr = tempDir() / "box.exr";
  CommandResult r = run("render " + (wb::sharedDir() / "assets/gltf/Box/glTF-Embedded/Box.gltf").string() +
                        " --size 16x16 --spp 1 --env-color 0.5,0.5,0.5 --out " + exr.string());
  ASSERT_EQ(r.code, 0) << r.output;
  std::ifstream f(exr, std::ios::binary);
  char magic[4] = {};
  f.read(magic, 4);
  EXPECT_EQ(static_cast<unsigned char>(magic[0]), 0x76);  // OpenEXR magic 76 2f 31 01
  EXPECT_EQ(static_cast<unsigned char>(magic[1]), 0x2f);
}

TEST(Cli, UnknownFlagIsAOneLineError) {
  CommandResult r = run("render --size 8x8 --out /tmp/x.png --no-such-flag");
  EXPECT_NE(r.code, 0);
  EXPECT_NE(r.output.find("no-such-flag"), std::string::npos) << r.output;
  EXPECT_EQ(lineCount(r.output), 1u) << r.output;
}

TEST(Cli, BadSizeAndColourAreRefused) {
  for (const char* args :
       {"render --size 0x8 --out /tmp/x.png", "render --size big --out /tmp/x.png",
        "render --env-color 1,2 --out /tmp/x.png", "render --env-color a,b,c --out /tmp/x.png",
        "render --size 8x8 --out /tmp/x.bmp", "render --sampler halton --out /tmp/x.png"}) {
    CommandResult r = run(args);
    EXPECT_NE(r.code, 0) << args;
    EXPECT_EQ(lineCount(r.output), 1u) << args << ": " << r.output;
    EXPECT_NE(r.output.find("error"), std::string::npos) << r.output;
  }
}

TEST(Cli, MissingSceneFileIsAOneLineError) {
  CommandResult r = run("render /nonexistent/scene.gltf --size 8x8 --out /tmp/x.png");
  EXPECT_NE(r.code, 0);
  EXPECT_LT(r.code, 128) << "must exit, not crash: " << r.output;
  EXPECT_NE(r.output.find("/nonexistent/scene.gltf"), std::string::npos) << r.output;
  EXPECT_EQ(lineCount(r.output), 1u) << r.output;
}

TEST(Cli, EveryMalformedGltfIsRefusedOrRenderedWithoutCrashing) {
  int files = 0;
  for (const auto& e : fs::recursive_directory_iterator(wb::sharedDir() / "assets/gltf-malformed")) {
    const auto ext = e.path().extension();
    if (ext != ".gltf" && ext != ".glb") continue;
    files++;
    CommandResult r = run("render \"" + e.path().string() + "\" --size 8x8 --spp 1 --out " +
                          (tempDir() / "m.png").string());
    SCOPED_TRACE(e.path().string() + ": " + r.output);
    EXPECT_LT(r.code, 128) << "crashed";
    if (r.code != 0) {
      EXPECT_NE(r.output.find("error"), std::string::npos);
      // One line of reason (loader warnings for features it skipped may precede it).
      EXPECT_EQ(r.output.substr(r.output.find("workbench render: error")).find('\n'),
                r.output.substr(r.output.find("workbench render: error")).size() - 1);
    }
  }
  EXPECT_GE(files, 10);
}
