// Bad input as an adversarial user gives it (issue 17), through the real `workbench` binary: every case ends
// with a clear error or a correct image, never a hang, a crash, or a silent wrong result.
#include <gtest/gtest.h>

#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
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
  const std::vector<unsigned char> truncated(b.begin(), b.end() - 32 * 4 * 10);  // ten rows missing
  writeBytes(cut, truncated);
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
       {"render " + box() + kSmall + "--out /etc/hostname/x.png",
        "render " + box() + kSmall + "--out " + png + " --stats /proc/x.json",
        "render " + box() + kSmall + "--out " + png + " --stats " + tempDir().string(),
        "render " + box() + kSmall + "--out /etc/hostname/x.png --aov albedo"}) {
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

// 2. `shaders --json` on a binary file, or on a file whose name is not UTF-8, writes JSON (invalid bytes
// replaced) and exits 1 for the failed compile; it used to abort on nlohmann's type_error.316 (exit 134).
TEST(BadInput, ShadersJsonSurvivesBinaryFilesAndNames) {
  const fs::path dir = tempDir() / "binary_shaders";
  fs::create_directories(dir);
  std::vector<unsigned char> junk;
  for (int i = 0; i < 4096; ++i) junk.push_back(static_cast<unsigned char>((i * 7919 + 13) % 251 + 3));
  writeBytes(dir / "junk.rgen", junk);
  writeBytes(dir / "name_\xff.rgen", junk);
  const CommandResult r = wb::testing::runCommand(
      "timeout 300 " + std::string(WB_WORKBENCH_BIN) + " shaders --json " + dir.string(), false);
  EXPECT_EQ(r.code, 1) << r.output;
  nlohmann::json j;
  ASSERT_NO_THROW(j = nlohmann::json::parse(r.output)) << r.output;
  ASSERT_EQ(j.size(), 2u);
  for (const auto& f : j) EXPECT_EQ(f["status"], "error") << f.dump();
}

// 3. A shader cache entry replaced by a named pipe used to make `render` wait forever on it.
TEST(BadInput, NamedPipesInTheShaderCacheAreMisses) {
  const fs::path cache = tempDir() / "fifo_cache";
  fs::remove_all(cache);
  const std::string cmd = "env WB_SHADER_CACHE_DIR=" + cache.string() + " timeout 300 " + WB_WORKBENCH_BIN +
                          " render " + box() + kSmall + "--out " + (tempDir() / "fifo.png").string();
  ASSERT_EQ(wb::testing::runCommand(cmd).code, 0);
  size_t pipes = 0;
  for (const auto& e : fs::directory_iterator(cache)) {
    if (!e.is_regular_file()) continue;  // Mesa's folder stays
    const fs::path p = e.path();
    fs::remove(p);
    ASSERT_EQ(mkfifo(p.c_str(), 0644), 0);
    ++pipes;
  }
  EXPECT_GE(pipes, 3u);
  const CommandResult r = wb::testing::runCommand(cmd);
  EXPECT_NE(r.code, 124) << "hung on a named pipe";
  EXPECT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("named pipe"), std::string::npos) << r.output;
}

// 8. Every numeric flag is checked the same way: finite and in range.
TEST(BadInput, NumericFlagsAreFiniteAndInRange) {
  for (const std::string flags :
       {"--env-rotation nan", "--env-rotation inf", "--env-intensity nan", "--env-color 1,nan,1",
        "--mode hybrid --sun-angle -10", "--mode hybrid --sun-angle 91", "--reflection-roughness nan",
        "--reflection-metallic 2", "--ao-radius inf", "--rr-max 7"}) {
    const CommandResult r = run("render " + flags + kSmall + "--out " + (tempDir() / "n.png").string());
    EXPECT_EQ(r.code, 2) << flags << ": " << r.output;
    const std::string flag =
        flags.substr(flags.rfind("--"), flags.find(' ', flags.rfind("--")) - flags.rfind("--"));
    EXPECT_NE(r.output.find(flag), std::string::npos) << flags << ": " << r.output;
    EXPECT_EQ(r.output.find("rendered"), std::string::npos) << r.output;
  }
}

// 13. Defines are checked: an identifier, one line; the message names the flag.
TEST(BadInput, DefinesAreValidated) {
  const std::string shader = (wb::projectRoot() / "shaders/pathtracer/miss.rmiss").string();
  for (const std::string define : {"=5", "5X=1", "'A=1\n#error injected'", "'A B=1'"}) {
    const CommandResult s = run("shaders --define " + define + " " + shader);
    EXPECT_EQ(s.code, 2) << define << ": " << s.output;
    EXPECT_NE(s.output.find("--define"), std::string::npos) << s.output;
    EXPECT_EQ(s.output.find("-1:"), std::string::npos) << s.output;
    EXPECT_EQ(s.output.find("\n#error"), std::string::npos) << s.output;
    EXPECT_EQ(s.output.find("error: #error"), std::string::npos)
        << "the define injected a line: " << s.output;
    const CommandResult r =
        run("render --define " + define + kSmall + "--out " + (tempDir() / "d.png").string());
    EXPECT_EQ(r.code, 2) << define << ": " << r.output;
    EXPECT_NE(r.output.find("--define"), std::string::npos) << r.output;
  }
  EXPECT_EQ(run("shaders --define WB_OK=1 --define WB_FLAG " + shader).code, 0);
}

// 16. A typo of a command is not a scene; bench takes the README's comma form and refuses unknown sections.
TEST(BadInput, UnknownCommandsAndBenchSections) {
  const CommandResult typo = run("shader x.rgen");
  EXPECT_EQ(typo.code, 2) << typo.output;
  EXPECT_NE(typo.output.find("unknown command 'shader'"), std::string::npos) << typo.output;
  EXPECT_NE(typo.output.find("render, shaders, watch, converge, bench"), std::string::npos) << typo.output;
  const CommandResult bench = run("bench --quick --only pathtracer,nonsense");
  EXPECT_EQ(bench.code, 2) << bench.output;
  EXPECT_NE(bench.output.find("nonsense not in"), std::string::npos) << bench.output;
  EXPECT_EQ(bench.output.find("pathtracer,nonsense"), std::string::npos) << "not split at the comma";
}

// 11. bench --out and converge --out are checked before any work.
TEST(BadInput, BenchAndConvergeOutputsAreCheckedFirst) {
  const CommandResult bench = run("bench --quick --only startup --out /etc/hostname/bench.json");
  EXPECT_EQ(bench.code, 2) << bench.output;
  EXPECT_NE(bench.output.find("cannot write"), std::string::npos) << bench.output;
  EXPECT_EQ(bench.output.find("start-up"), std::string::npos) << "ran before failing: " << bench.output;
  const fs::path blocker = tempDir() / "blocker";
  std::ofstream(blocker) << "a file, not a folder";
  const CommandResult converge =
      run("converge --size 8x8 --seconds 0.05 --reference-spp 4 --out " + (blocker / "report").string());
  EXPECT_NE(converge.code, 0) << converge.output;
  EXPECT_NE(converge.output.find("--out"), std::string::npos) << converge.output;
  EXPECT_EQ(converge.output.find("reference"), std::string::npos) << "rendered first: " << converge.output;
}

// 9. A shader that declares and uses a resource the path tracer does not bind is refused at load, at the
// declaration's file:line (it rendered, reading an unbound descriptor: VUID-vkCmdTraceRaysKHR-None-02699).
TEST(BadInput, UnboundResourceIsACompileErrorAtItsDeclaration) {
  const fs::path root = tempDir() / "unbound_root";
  fs::remove_all(root);
  fs::create_directories(root);
  fs::copy(wb::projectRoot() / "shaders", root / "shaders", fs::copy_options::recursive);
  fs::copy(wb::projectRoot() / "assets", root / "assets", fs::copy_options::recursive);
  const fs::path chit = root / "shaders/pathtracer/closesthit.rchit";
  std::ifstream in(chit);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const size_t afterIncludes = text.find('\n', text.rfind("#include")) + 1;
  const int line = 1 + int(std::count(text.begin(), text.begin() + long(afterIncludes), '\n'));
  text.insert(afterIncludes, "layout(set = 0, binding = 30, std430) buffer WbExtra { vec4 v[]; } wbExtra;\n");
  text.insert(text.find('\n', text.find("void main()")) + 1, "  if (wbExtra.v[0].x > 1e30) return;\n");
  std::ofstream(chit, std::ios::trunc) << text;
  const CommandResult r = wb::testing::runCommand(
      "env WB_ROOT=" + root.string() + " WB_SHADER_CACHE_DIR=" + (root / "cache").string() + " timeout 300 " +
      WB_WORKBENCH_BIN + " render" + kSmall + "--out " + (root / "x.png").string());
  EXPECT_EQ(r.code, 1) << r.output;
  EXPECT_NE(r.output.find("closesthit.rchit:" + std::to_string(line) + ": error: set 0 binding 30"),
            std::string::npos)
      << r.output;
  EXPECT_EQ(r.output.find("rendered"), std::string::npos) << r.output;
  fs::remove_all(root);
}
