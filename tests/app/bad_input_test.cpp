// Bad input as an adversarial user gives it (issue 17), through the real `workbench` binary: every case ends
// with a clear error or a correct image, never a hang, a crash, or a silent wrong result.
#include <gtest/gtest.h>

#include <sys/stat.h>
#include <unistd.h>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <functional>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>
#include <stb/stb_image.h>
#include <stb/stb_image_write.h>

#include "../common/run_command.h"
#include "common/paths.h"

namespace fs = std::filesystem;

namespace {

using wb::testing::CommandResult;

// Commands that used to hang run under `timeout`: a hang fails the test (status 124) instead of stalling it.
CommandResult run(const std::string& args) {
  return wb::testing::runCommand("timeout 300 " + std::string(WB_WORKBENCH_BIN) + " " + args);
}

fs::path tempDir() {
  fs::path d = fs::temp_directory_path() / ("wb_bad_input_" + std::to_string(::getpid()));
  fs::create_directories(d);
  return d;
}

std::string box() {
  return (wb::sharedDir() / "assets/gltf/Box/glTF-Embedded/Box.gltf").string();
}

std::string garden() {
  return (wb::sharedDir() / "assets/env/chinese_garden_1k.hdr").string();
}

std::vector<unsigned char> readBytes(const fs::path& p) {
  std::ifstream f(p, std::ios::binary);
  return std::vector<unsigned char>(std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>());
}

void writeBytes(const fs::path& p, const std::vector<unsigned char>& b) {
  std::ofstream f(p, std::ios::binary);
  f.write(reinterpret_cast<const char*>(b.data()), std::streamsize(b.size()));
}

nlohmann::json readJson(const fs::path& p) {
  std::ifstream f(p);
  return nlohmann::json::parse(f);
}

std::string base64(const std::vector<unsigned char>& in) {
  static const char* t = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  for (size_t i = 0; i < in.size(); i += 3) {
    uint32_t v = uint32_t(in[i]) << 16;
    if (i + 1 < in.size()) v |= uint32_t(in[i + 1]) << 8;
    if (i + 2 < in.size()) v |= in[i + 2];
    out += t[(v >> 18) & 63];
    out += t[(v >> 12) & 63];
    out += i + 1 < in.size() ? t[(v >> 6) & 63] : '=';
    out += i + 2 < in.size() ? t[v & 63] : '=';
  }
  return out;
}

// Box.gltf with an extra change made by `edit`, written to dir/name.
fs::path editedBox(const std::string& name, const std::function<void(nlohmann::json&)>& edit) {
  std::ifstream f(box());
  nlohmann::json j = nlohmann::json::parse(f);
  edit(j);
  const fs::path p = tempDir() / name;
  std::ofstream(p) << j.dump();
  return p;
}

// A 10 x 10 square lying in the XZ plane (a ground plane asset), dark grey, no camera.
fs::path groundPlane() {
  const std::vector<float> positions = {-5, 0, -5, 5, 0, -5, 5, 0, 5, -5, 0, 5};
  const std::vector<uint16_t> indices = {0, 2, 1, 0, 3, 2, 0, 0};  // padded to 4 bytes
  std::vector<unsigned char> buffer(positions.size() * 4 + indices.size() * 2);
  std::memcpy(buffer.data(), positions.data(), positions.size() * 4);
  std::memcpy(buffer.data() + positions.size() * 4, indices.data(), indices.size() * 2);
  nlohmann::json j = nlohmann::json::parse(R"({
    "asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
    "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1, "material": 0}]}],
    "materials": [{"pbrMetallicRoughness": {"baseColorFactor": [0.05, 0.05, 0.05, 1], "metallicFactor": 0}}],
    "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 48},
                    {"buffer": 0, "byteOffset": 48, "byteLength": 12}],
    "accessors": [{"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3",
                   "min": [-5, 0, -5], "max": [5, 0, 5]},
                  {"bufferView": 1, "componentType": 5123, "count": 6, "type": "SCALAR"}]})");
  j["buffers"] = nlohmann::json::array(
      {{{"byteLength", buffer.size()}, {"uri", "data:application/octet-stream;base64," + base64(buffer)}}});
  const fs::path p = tempDir() / "ground_plane.gltf";
  std::ofstream(p) << j.dump();
  return p;
}

const std::string kSmall = " --size 16x16 --spp 1 ";

}  // namespace

// 1. A truncated run-length .hdr used to hang inside stb_image 2.27 (CVE-2021-42715).
TEST(BadInput, TruncatedHdrEnvironmentIsRefusedNotAHang) {
  const auto bytes = readBytes(garden());
  const fs::path half = tempDir() / "half.hdr";
  writeBytes(half, std::vector<unsigned char>(bytes.begin(), bytes.begin() + long(bytes.size() / 2)));
  const CommandResult r = run("render " + box() + " --env " + half.string() + kSmall + "--out " +
                              (tempDir() / "half.png").string());
  EXPECT_NE(r.code, 124) << "hung";
  EXPECT_NE(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("half.hdr"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("truncated"), std::string::npos) << r.output;
}

// 1. A glTF texture whose bytes are a truncated HDR used to hang scene loading the same way.
TEST(BadInput, TruncatedHdrTextureIsAWarningNotAHang) {
  const auto bytes = readBytes(garden());
  const std::vector<unsigned char> half(bytes.begin(), bytes.begin() + long(bytes.size() / 2));
  const fs::path gltf = editedBox("hdr_texture.gltf", [&](nlohmann::json& j) {
    j["images"] = {{{"uri", "data:image/png;base64," + base64(half)}}};
    j["textures"] = {{{"source", 0}}};
  });
  const CommandResult r = run("render " + gltf.string() + kSmall + "--out " + (tempDir() / "t.png").string());
  EXPECT_NE(r.code, 124) << "hung";
  EXPECT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("could not be decoded"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("truncated"), std::string::npos) << r.output;
}

// 4. A truncated uncompressed .hdr used to load with its missing rows filled from the last pixel read.
TEST(BadInput, TruncatedFlatHdrIsRefused) {
  std::string header = "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 16 +X 32\n";
  std::vector<unsigned char> b(header.begin(), header.end());
  for (int i = 0; i < 32 * 16; ++i)
    for (unsigned char c : {0, 0, 0, 0}) b.push_back(c);  // flat (not run-length) black pixels
  const fs::path full = tempDir() / "flat.hdr", cut = tempDir() / "flat_cut.hdr";
  writeBytes(full, b);
  b.resize(b.size() - 32 * 4 * 10);  // ten rows missing
  writeBytes(cut, b);
  const std::string out = " --out " + (tempDir() / "flat.png").string();
  const CommandResult ok = run("render " + box() + " --env " + full.string() + kSmall + out);
  EXPECT_EQ(ok.code, 0) << ok.output;
  const CommandResult r = run("render " + box() + " --env " + cut.string() + kSmall + out);
  EXPECT_NE(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("scanline 7 of 16"), std::string::npos) << r.output;
}

// 5. Very bright must be white: the tonemapper used to overflow to NaN and write black. Every pixel that is
// not black at the ordinary intensity (same seed: the same paths) is white.
TEST(BadInput, VeryBrightEnvironmentRendersWhite) {
  auto load = [](const fs::path& png) {
    int w = 0, h = 0, n = 0;
    unsigned char* px = stbi_load(png.c_str(), &w, &h, &n, 4);
    std::vector<unsigned char> v;
    if (px) v.assign(px, px + size_t(w) * size_t(h) * 4);
    stbi_image_free(px);
    return v;
  };
  const fs::path ordinary = tempDir() / "ordinary.png", bright = tempDir() / "bright.png";
  for (const std::string flags : {"--env-intensity 1e30", "--env-color 1e38,1e38,1e38"}) {
    const std::string base = (flags[6] == 'i' ? "" : "--env-color 1,1,1 ");
    const CommandResult a = run("render " + box() + " " + base + kSmall + "--out " + ordinary.string());
    ASSERT_EQ(a.code, 0) << a.output;
    const CommandResult r = run("render " + box() + " " + flags + kSmall + "--out " + bright.string());
    ASSERT_EQ(r.code, 0) << flags << ": " << r.output;
    const auto lit = load(ordinary), px = load(bright);
    ASSERT_EQ(lit.size(), px.size());
    ASSERT_FALSE(px.empty());
    size_t litPixels = 0, white = 0;
    for (size_t i = 0; i < px.size(); i += 4) {
      if (lit[i] == 0 && lit[i + 1] == 0 && lit[i + 2] == 0) continue;
      ++litPixels;
      white += px[i] == 255 && px[i + 1] == 255 && px[i + 2] == 255;
    }
    EXPECT_GT(litPixels, px.size() / 8);
    EXPECT_EQ(white, litPixels) << flags;
  }
}

// 6. A flat model lying in XZ used to be framed edge-on (looking down -Z) and render as empty sky.
TEST(BadInput, GroundPlaneIsFramedFromAbove) {
  const fs::path stats = tempDir() / "plane.json";
  const CommandResult r =
      run("render " + groundPlane().string() + " --env-color 1,1,1 --size 32x32 --spp 4 " + "--out " +
          (tempDir() / "plane.png").string() + " --stats " + stats.string());
  ASSERT_EQ(r.code, 0) << r.output;
  // Sky alone is 1.0; seen from above, the dark plane covers about half of the view.
  EXPECT_LT(readJson(stats)["mean_rgb"][1].get<double>(), 0.8) << r.output;
}

// 7. An 8-bit environment is loaded as linear radiance with a warning; a folder is said to be one.
TEST(BadInput, LdrEnvironmentIsAWarningAndAFolderIsNamed) {
  // A 2x1 PNG sky: one white and one black pixel.
  const unsigned char pixels[6] = {255, 255, 255, 0, 0, 0};
  const fs::path sky = tempDir() / "sky.png", stats = tempDir() / "ldr.json";
  ASSERT_TRUE(stbi_write_png(sky.c_str(), 2, 1, 3, pixels, 6));
  const CommandResult r = run("render " + box() + " --env " + sky.string() + kSmall + "--out " +
                              (tempDir() / "ldr.png").string() + " --stats " + stats.string());
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("warning: environment " + sky.string() + " is an 8-bit PNG image, not HDR"),
            std::string::npos)
      << r.output;
  EXPECT_GT(readJson(stats)["mean_rgb"][0].get<double>(), 0.01);
  const CommandResult dir = run("render " + box() + " --env " + tempDir().string() + kSmall + "--out " +
                                (tempDir() / "dir.png").string());
  EXPECT_NE(dir.code, 0);
  EXPECT_NE(dir.output.find("is a directory"), std::string::npos) << dir.output;
  EXPECT_EQ(dir.output.find("no such file"), std::string::npos) << dir.output;
}

// 10. A scene of POINTS and LINES: the loader's warnings come before the refusal.
TEST(BadInput, NoTrianglesSaysWhy) {
  const fs::path gltf = editedBox("points.gltf", [](nlohmann::json& j) {
    for (auto& m : j["meshes"])
      for (auto& p : m["primitives"]) p["mode"] = 0;
  });
  const CommandResult r = run("render " + gltf.string() + kSmall + "--out " + (tempDir() / "p.png").string());
  EXPECT_NE(r.code, 0);
  const size_t warning = r.output.find("primitive mode POINTS (0) unsupported");
  ASSERT_NE(warning, std::string::npos) << r.output;
  EXPECT_LT(warning, r.output.find("has no triangles")) << r.output;
}

// 11. Outputs are checked before the render; nothing says "rendered" and then fails.
TEST(BadInput, UnwritableOutputsFailBeforeRendering) {
  const std::string png = (tempDir() / "ok.png").string();
  for (const std::string& args :
       {"render " + box() + kSmall + "--out /nonexistent/x.png",
        "render " + box() + kSmall + "--out " + png + " --stats /proc/x.json",
        "render " + box() + kSmall + "--out " + png + " --stats " + tempDir().string(),
        "render " + box() + kSmall + "--out /nonexistent/x.png --aov albedo"}) {
    fs::remove(png);
    const CommandResult r = run(args);
    EXPECT_NE(r.code, 0) << args;
    EXPECT_EQ(r.output.find("rendered"), std::string::npos) << args << ": " << r.output;
    EXPECT_NE(r.output.find("cannot write"), std::string::npos) << args << ": " << r.output;
    EXPECT_FALSE(fs::exists(png)) << args;
  }
}

// 12. A texture whose image is missing (used by no material) is a warning, not a refusal.
TEST(BadInput, TextureWithoutImageLoadsWithAWarning) {
  const fs::path gltf = editedBox("texture_without_image.gltf", [](nlohmann::json& j) {
    j["textures"] = {{{"source", 0}, {"name", "tex"}}};
  });
  const CommandResult r = run("render " + gltf.string() + kSmall + "--out " + (tempDir() / "t.png").string());
  EXPECT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("warning: texture 0 refers to image 0, which does not exist"), std::string::npos)
      << r.output;
}
