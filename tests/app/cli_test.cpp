// The `workbench` binary as outside scripts use it: flags, exit codes, one-line errors, written files.
#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

#include "../common/run_command.h"
#include "common/paths.h"

namespace fs = std::filesystem;

namespace {

// Any shell command line (stdout + stderr captured unless it redirects them itself).
using wb::testing::CommandResult;

CommandResult shell(const std::string& line, bool captureStderr = true) {
  return wb::testing::runCommand(line, captureStderr);
}

CommandResult run(const std::string& args) {
  return shell(std::string(WB_WORKBENCH_BIN) + " " + args);
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

// The bench says which step of how many runs, with the elapsed time and an ETA (plain lines off a terminal).
TEST(Cli, BenchShowsItsStepsWithAnEta) {
  const fs::path out = tempDir() / "bench_progress.json";
  const auto r = run("bench --quick --only startup --out " + out.string());
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("bench: ["), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("step 1/1: start-up"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("ETA"), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find("\r"), std::string::npos) << "a terminal line rewritten in a log";
  const auto j = nlohmann::json::parse(std::ifstream(out));
  EXPECT_TRUE(j.contains("startup"));
}

// `bench --only denoise`'s keys, a contract with outside scripts: the denoiser's GPU time against one
// sample's, per size, its share of the sample (the median of each submission's own share, with their range)
// and each pass's time.
TEST(Cli, BenchDenoiseReportsItsCostAgainstASample) {
  const fs::path out = tempDir() / "bench_denoise.json";
  const auto r = run("bench --quick --only denoise --size 48x48 --repeats 3 --out " + out.string());
  ASSERT_EQ(r.code, 0) << r.output;
  const auto j = nlohmann::json::parse(std::ifstream(out))["denoise"];
  ASSERT_TRUE(j["cost"].is_array() && !j["cost"].empty()) << j.dump();
  for (const auto& c : j["cost"]) {
    const double d = c["denoise_ms"].get<double>(), t = c["sample_ms"].get<double>();
    EXPECT_GT(d, 0.0) << c.dump();
    EXPECT_GT(t, 0.0) << c.dump();
    // Each submission's share lies in the range, and so do their median and the medians' ratio (every
    // submission's denoise is at least the lowest share times its sample).
    const double share = c["denoise_share_of_sample"].get<double>();
    const double lowest = c["denoise_share_of_sample_range"][0].get<double>(),
                 highest = c["denoise_share_of_sample_range"][1].get<double>();
    EXPECT_GT(lowest, 0.0) << c.dump();
    EXPECT_LE(lowest, share) << c.dump();
    EXPECT_LE(share, highest) << c.dump();
    EXPECT_LE(lowest, d / t * (1 + 1e-9)) << c.dump();
    EXPECT_LE(d / t, highest * (1 + 1e-9)) << c.dump();
    // Every pass's own GPU time, each a part of the whole.
    for (const char* pass : {"prepare", "variance", "atrous", "final", "gain", "scale"}) {
      ASSERT_TRUE(c["denoise_pass_ms"].contains(pass)) << pass << " " << c.dump();
      EXPECT_GT(c["denoise_pass_ms"][pass].get<double>(), 0.0) << pass << " " << c.dump();
    }
    EXPECT_EQ(c["denoise_pass_ms"].size(), 6u) << c.dump();
  }
  EXPECT_EQ(j["denoise_ms"], j["cost"][0]["denoise_ms"]);
  EXPECT_EQ(j["denoise_share_of_sample"], j["cost"][0]["denoise_share_of_sample"]);
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

namespace {

nlohmann::json readJsonFile(const fs::path& p) {
  std::ifstream f(p);
  return nlohmann::json::parse(f);
}

size_t filesUnder(const fs::path& dir) {
  size_t n = 0;
  std::error_code ec;
  if (!fs::exists(dir, ec)) return 0;
  for (auto it = fs::recursive_directory_iterator(dir, ec); it != fs::recursive_directory_iterator(); ++it) {
    n += it->is_regular_file(ec);
  }
  return n;
}

}  // namespace

// A warm start of the default scene performs zero glslang compiles, and Mesa's own shader cache goes under
// the shader cache unless the user set MESA_SHADER_CACHE_DIR.
TEST(Cli, WarmStartOfTheDefaultSceneCompilesNothing) {
  const auto dir = tempDir() / "warm";
  fs::remove_all(dir);
  const std::string env =
      "env -u MESA_SHADER_CACHE_DIR WB_SHADER_CACHE_DIR=" + (dir / "cache").string() + " ";
  const std::string args = " render --size 16x16 --spp 1 --out " + (dir / "o.png").string() + " --stats ";
  auto cold = shell(env + WB_WORKBENCH_BIN + args + (dir / "cold.json").string());
  ASSERT_EQ(cold.code, 0) << cold.output;
  auto warm = shell(env + WB_WORKBENCH_BIN + args + (dir / "warm.json").string());
  ASSERT_EQ(warm.code, 0) << warm.output;
  const auto c = readJsonFile(dir / "cold.json")["shader_cache"],
             w = readJsonFile(dir / "warm.json")["shader_cache"];
  EXPECT_GT(c["compiles"].get<int>(), 0) << c.dump();
  EXPECT_EQ(w["compiles"].get<int>(), 0) << w.dump();
  EXPECT_GT(w["hits"].get<int>(), 0) << w.dump();
  EXPECT_GT(filesUnder(dir / "cache" / "mesa"), 0u) << "Mesa's disk cache is not under the shader cache";
  // A user's MESA_SHADER_CACHE_DIR is kept.
  const fs::path mine = dir / "users_mesa_cache";
  auto user = shell("env MESA_SHADER_CACHE_DIR=" + mine.string() + " WB_SHADER_CACHE_DIR=" +
                    (dir / "cache2").string() + " " + WB_WORKBENCH_BIN + args + (dir / "user.json").string());
  ASSERT_EQ(user.code, 0) << user.output;
  EXPECT_GT(filesUnder(mine), 0u);
  EXPECT_EQ(filesUnder(dir / "cache2" / "mesa"), 0u);
}

// llvmpipe compiles 4 lanes wide unless the user chose a width or a Mesa cache of their own
// (vk/driver_env.h), and Mesa's cache goes to a folder per width (its key leaves the width out: code of one
// width loaded by a process of the other corrupts the heap). The stats' device name carries llvmpipe's width.
TEST(Cli, LavapipeVectorWidthAndAMesaCacheFolderPerWidth) {
  const auto dir = tempDir() / "vector_width";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const std::string cache = " WB_SHADER_CACHE_DIR=" + (dir / "cache").string();
  auto device = [&](const std::string& env, const std::string& name) {
    const fs::path stats = dir / (name + ".json");
    auto r = shell("env " + env + " " + WB_WORKBENCH_BIN + " render --size 8x8 --spp 1 --out " +
                   (dir / (name + ".png")).string() + " --stats " + stats.string());
    EXPECT_EQ(r.code, 0) << r.output;
    return r.code == 0 ? readJsonFile(stats)["device"].get<std::string>() : std::string();
  };
  // An empty MESA_SHADER_CACHE_DIR counts as unset (how `bench` hands the choice back to its children).
  const std::string ours = device("-u LP_NATIVE_VECTOR_WIDTH MESA_SHADER_CACHE_DIR=" + cache, "ours");
  if (ours.find("llvmpipe") == std::string::npos) GTEST_SKIP() << "not lavapipe: " << ours;
  EXPECT_NE(ours.find("128 bits"), std::string::npos) << ours;
  EXPECT_GT(filesUnder(dir / "cache" / "mesa" / "lp128"), 0u);
  const std::string users = device("-u MESA_SHADER_CACHE_DIR LP_NATIVE_VECTOR_WIDTH=256" + cache, "users");
  EXPECT_NE(users.find("256 bits"), std::string::npos) << users;
  EXPECT_GT(filesUnder(dir / "cache" / "mesa" / "lp256"), 0u);
  // A Mesa cache of the user's own may hold code of Mesa's default width: the width is left alone.
  const std::string own =
      device("-u LP_NATIVE_VECTOR_WIDTH MESA_SHADER_CACHE_DIR=" + (dir / "own").string() + cache, "own");
  EXPECT_EQ(own.find("128 bits"), std::string::npos) << own;
  EXPECT_GT(filesUnder(dir / "own"), 0u);
}

// `shaders --json`: per file the stage, status, compile ms, cache hit or miss and the reflected bindings; a
// define is a separate cache entry; a broken file is status "error" with file:line and a non-zero exit.
TEST(Cli, ShadersJsonReportsEachFile) {
  const auto dir = tempDir() / "shaders_json";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const std::string env = "WB_SHADER_CACHE_DIR=" + (dir / "cache").string() + " ";
  const std::string target = (fs::path(WB_SOURCE_DIR) / "shaders/pathtracer").string();
  auto shaders = [&](const std::string& extra, const std::string& out) {
    return shell("env " + env + WB_WORKBENCH_BIN + " shaders --json " + extra + " " + target + " > " +
                 (dir / out).string());
  };
  ASSERT_EQ(shaders("", "first.json").code, 0);
  ASSERT_EQ(shaders("", "second.json").code, 0);
  ASSERT_EQ(shaders("--define WB_TEST_ONLY=1", "defined.json").code, 0);
  const auto first = readJsonFile(dir / "first.json"), second = readJsonFile(dir / "second.json");
  const auto defined = readJsonFile(dir / "defined.json");
  ASSERT_GE(first.size(), 5u);  // raygen, 2 miss, closest-hit, any-hit
  bool sawClosestHit = false;
  for (size_t i = 0; i < first.size(); ++i) {
    const auto& f = first[i];
    EXPECT_EQ(f["status"], "ok") << f.dump();
    EXPECT_TRUE(f["ms"].is_number());
    EXPECT_EQ(f["cache"], "miss") << f["file"];
    EXPECT_EQ(second[i]["cache"], "hit") << second[i]["file"];
    EXPECT_EQ(defined[i]["cache"], "miss") << "a define is part of the key: " << defined[i]["file"];
    EXPECT_TRUE(f["bindings"].is_array());
    // Active resources per stage: raygen traces every ray (shadow rays too), so only it binds the TLAS.
    bool tlas = false;
    for (const auto& b : f["bindings"]) tlas |= b["type"] == "acceleration-structure";
    if (f["stage"] == "rgen") {
      EXPECT_TRUE(tlas) << f["file"] << ": " << f["bindings"].dump();
    }
    if (f["stage"] == "rchit") {
      sawClosestHit = true;
      EXPECT_FALSE(tlas) << f["file"] << ": " << f["bindings"].dump();
    }
  }
  EXPECT_TRUE(sawClosestHit);
  std::ofstream(dir / "bad.rgen")
      << "#version 460\n#extension GL_EXT_ray_tracing : require\nvoid main() { nope(); }\n";
  auto bad = shell("env " + env + WB_WORKBENCH_BIN + " shaders --json " + (dir / "bad.rgen").string() +
                       " > " + (dir / "bad.json").string() + " 2> " + (dir / "bad.err").string(),
                   false);
  EXPECT_EQ(bad.code, 1);
  const auto b = readJsonFile(dir / "bad.json");
  ASSERT_EQ(b.size(), 1u);
  EXPECT_EQ(b[0]["status"], "error");
  EXPECT_EQ(b[0]["stage"], "rgen");
  EXPECT_EQ(b[0]["diagnostics"][0]["line"], 3);
  std::ifstream err(dir / "bad.err");
  const std::string text((std::istreambuf_iterator<char>(err)), {});
  EXPECT_NE(text.find("bad.rgen:3: error"), std::string::npos) << text;
}

// The render flags through the binary: each one reaches the stats, --aov writes the AOVs it names, a hybrid
// mode renders in that mode, and --reference adds the error against it.
TEST(Cli, RenderFlagsReachTheStatsAndFiles) {
  const auto dir = tempDir() / "flags";
  fs::remove_all(dir);
  fs::create_directories(dir);
  auto r = run(
      "render --size 16x16 --spp 2 --max-bounces 3 --rr-start 1 --rr-min 0.1 --rr-max 0.9 --rr-exponent 0.25 "
      "--seed 5 "
      "--sampler pcg --env-rotation 30 --env-intensity 0.5 --aov albedo --out " +
      (dir / "a.exr").string() + " --stats " + (dir / "a.json").string());
  ASSERT_EQ(r.code, 0) << r.output;
  const auto a = readJsonFile(dir / "a.json");
  EXPECT_EQ(a["max_bounces"], 3);
  EXPECT_EQ(a["rr_start"], 1);
  EXPECT_NEAR(a["rr_min"].get<double>(), 0.1, 1e-6);
  EXPECT_NEAR(a["rr_max"].get<double>(), 0.9, 1e-6);
  EXPECT_NEAR(a["rr_exponent"].get<double>(), 0.25, 1e-6);
  EXPECT_EQ(a["seed"], 5);
  EXPECT_EQ(a["sampler"], "pcg");
  EXPECT_EQ(a["mode"], "pathtrace");
  EXPECT_GT(a["paths_per_second"].get<double>(), 0.0);
  EXPECT_TRUE(fs::exists(dir / "a.albedo.exr"));
  EXPECT_FALSE(fs::exists(dir / "a.normal.exr")) << "--aov albedo names only the albedo";
  // Same view in hybrid mode, compared with the path-traced image as its reference.
  auto h = run("render --size 16x16 --spp 2 --mode hybrid --reference " + (dir / "a.exr").string() +
               " --out " + (dir / "h.png").string() + " --stats " + (dir / "h.json").string());
  ASSERT_EQ(h.code, 0) << h.output;
  const auto hj = readJsonFile(dir / "h.json");
  EXPECT_EQ(hj["mode"], "hybrid");
  EXPECT_TRUE(hj.contains("hybrid"));
  EXPECT_GT(hj["error_vs_reference"]["rmse"].get<double>(), 0.0);
  EXPECT_GT(hj["error_vs_reference"]["rel_mse"].get<double>(), 0.0);
  EXPECT_GT(hj["seconds_per_frame"].get<double>(), 0.0);
  // A reference of another size is a one-line error.
  auto bad = run("render --size 8x8 --spp 1 --reference " + (dir / "a.exr").string() + " --out " +
                 (dir / "b.png").string() + " --stats " + (dir / "b.json").string());
  EXPECT_NE(bad.code, 0);
  EXPECT_LE(lineCount(bad.output), 2u) << bad.output;
}

// --define K=V reaches the path tracer's shaders as its own cached variant; a bad name is a one-line error.
TEST(Cli, DefineIsAShaderVariant) {
  const auto dir = tempDir() / "define";
  fs::remove_all(dir);
  const std::string env = "env WB_SHADER_CACHE_DIR=" + (dir / "cache").string() + " ";
  const std::string args = " render --size 8x8 --spp 1 --out " + (dir / "o.png").string() + " --stats ";
  ASSERT_EQ(shell(env + WB_WORKBENCH_BIN + args + (dir / "plain.json").string()).code, 0);
  auto d = shell(env + WB_WORKBENCH_BIN + args + (dir / "defined.json").string() +
                 " --define WB_PAYLOAD_PAD_VEC4=4");
  ASSERT_EQ(d.code, 0) << d.output;
  EXPECT_GT(readJsonFile(dir / "defined.json")["shader_cache"]["compiles"].get<int>(), 0)
      << "a define is a new variant: its stages compile";
  auto bad = run("render --size 8x8 --spp 1 --out " + (dir / "b.png").string() + " --define 1bad=2");
  EXPECT_EQ(bad.code, 2);
  EXPECT_NE(bad.output.find("--define"), std::string::npos) << bad.output;
  EXPECT_EQ(lineCount(bad.output), 1u) << bad.output;
}

TEST(Cli, InspectPixelWritesThePathRecordsAsJson) {
  const auto dir = tempDir();
  const auto json = dir / "inspect.json", png = dir / "inspect.png";
  // Without --out only the pixel is traced; with it the image too, and the records are the same samples.
  CommandResult alone = run("render --size 16x16 --spp 3 --inspect-pixel 8,9 --inspect-out " + json.string());
  ASSERT_EQ(alone.code, 0) << alone.output;
  EXPECT_NE(alone.output.find("inspected pixel 8,9: 3 samples"), std::string::npos) << alone.output;
  std::ifstream f(json);
  const auto j = nlohmann::json::parse(f);
  EXPECT_EQ(j["schema"], "workbench-path-inspector/1");
  EXPECT_EQ(j["pixel"], nlohmann::json::array({8, 9}));
  EXPECT_EQ(j["size"], nlohmann::json::array({16, 16}));
  ASSERT_EQ(j["samples"].size(), 3u);
  EXPECT_EQ(j["pixel_samples"], 3.0);
  EXPECT_TRUE(j["parameters"].contains("max_bounces"));
  for (int c = 0; c < 3; ++c) {
    const double pixel = j["pixel_value"][c], mean = j["estimate"]["mean"][c];
    EXPECT_NEAR(pixel, mean, 1e-5 * std::max(1.0, pixel));
  }
  const auto& s0 = j["samples"][0];
  for (const char* key : {"index", "jitter", "camera_origin", "camera_direction", "radiance", "accumulated",
                          "end", "vertex_count", "vertices_truncated", "shadow_rays", "vertices", "escape",
                          "sum_of_added", "first_non_finite"}) {
    EXPECT_TRUE(s0.contains(key)) << key;
  }
  ASSERT_FALSE(s0["vertices"].empty()) << "pixel 8,9 of the default scene sees the room";
  const auto& v0 = s0["vertices"][0];
  for (const char* key : {"bounce",
                          "position",
                          "distance",
                          "incoming",
                          "geometric_normal",
                          "shading_normal",
                          "front_face",
                          "normal_flipped",
                          "instance",
                          "geometry",
                          "primitive",
                          "material",
                          "emitted",
                          "emission_mis_weight",
                          "light_samples",
                          "lights",
                          "continued",
                          "lobe",
                          "lobe_probability",
                          "direction",
                          "brdf",
                          "pdf",
                          "cosine",
                          "weight",
                          "throughput_in",
                          "rr_probability",
                          "rr_outcome",
                          "throughput",
                          "added"}) {
    EXPECT_TRUE(v0.contains(key)) << key;
  }
  for (const auto& l : v0["lights"]) {
    for (const char* key : {"kind", "index", "status", "direction", "radiance", "light_pdf", "delta",
                            "brdf_cos", "brdf_pdf", "mis_weight", "contribution", "distance", "visible"}) {
      EXPECT_TRUE(l.contains(key)) << key;
    }
  }

  const auto json2 = dir / "inspect_image.json";
  CommandResult withImage = run("render --size 16x16 --spp 3 --inspect-pixel 8,9 --inspect-samples 2 --out " +
                                png.string() + " --inspect-out " + json2.string());
  ASSERT_EQ(withImage.code, 0) << withImage.output;
  EXPECT_TRUE(fs::exists(png));
  std::ifstream f2(json2);
  const auto j2 = nlohmann::json::parse(f2);
  ASSERT_EQ(j2["samples"].size(), 2u);
  EXPECT_EQ(j2["pixel_samples"], 3.0);
  EXPECT_EQ(j2["samples"][1]["radiance"], j["samples"][1]["radiance"]) << "the same sample either way";
}

TEST(Cli, InspectFlagsAreChecked) {
  const auto dir = tempDir();
  const std::string out = " --inspect-out " + (dir / "i.json").string();
  for (const std::string& args : {std::string("--inspect-pixel 3,4"), "--inspect-pixel 16,0" + out,
                                  "--inspect-pixel 3" + out, "--inspect-pixel 3,4 --inspect-samples 5" + out,
                                  "--inspect-pixel 1,1 --mode hybrid --inspect-samples 2" + out,
                                  "--inspect-pixel 1,1 --inspect-out " + (dir / "i.txt").string(),
                                  "--inspect-pixel 1,1 --stats x.json" + out, std::string("")}) {
    CommandResult r = run("render --size 16x16 --spp 4 " + args);
    EXPECT_EQ(r.code, 2) << args << ": " << r.output;
    EXPECT_EQ(lineCount(r.output), 1u) << args << ": " << r.output;
  }
}

TEST(Cli, InspectPixelInAHybridModeWritesItsRays) {
  const auto dir = tempDir();
  const auto json = dir / "hybrid_inspect.json";
  CommandResult r =
      run("render --mode reflections --ao-rays 3 --size 16x16 --spp 2 --inspect-pixel 8,9 "
          "--inspect-out " +
          json.string());
  ASSERT_EQ(r.code, 0) << r.output;
  std::ifstream f(json);
  const auto j = nlohmann::json::parse(f);
  EXPECT_EQ(j["schema"], "workbench-hybrid-inspector/1");
  EXPECT_EQ(j["mode"], "reflections");
  EXPECT_EQ(j["frame"], 1) << "the last of two frames";
  ASSERT_EQ(j["covered"], true);
  EXPECT_EQ(j["ao"]["rays"].size(), 3u);
  for (const char* key : {"position", "normal", "shadow", "ao", "reflection"})
    EXPECT_TRUE(j.contains(key)) << key;
}

// WB_SPLIT_SHADOWS=1 (next-event estimation's shadow rays in a launch of their own) traces the same rays and
// renders the same image as the one path loop, up to the order of the sums: on the default scene
// (alpha-tested leaves: the shadow launch runs any-hit) and on the Cornell box (no any-hit; 64 bounces, more
// light samples than a sample's slots hold in some paths), one sample and four per launch; a denoised render
// (AOVs: the denoiser's guides, which the shadow launch writes) splits too and gives the one loop's image.
TEST(Cli, SplitShadowsRenderTheSameImage) {
  const auto dir = tempDir();
  const std::string cornell = " " + (wb::sharedDir() / "reference" / "cornell.gltf").string() +
                              " --env-color 0,0,0 --max-bounces 64 --no-rr --size 16x16 --spp 4 ";
  for (const std::string& scene : {std::string(" --size 24x24 --spp 4 --max-bounces 4 "), cornell}) {
    for (const char* launch : {"1", "4"}) {
      SCOPED_TRACE(scene + launch);
      const std::string common = scene + "--samples-per-launch " + launch + " ";
      CommandResult r = run("render" + common + "--out " + (dir / "loop.exr").string() + " --stats " +
                            (dir / "loop.json").string());
      ASSERT_EQ(r.code, 0) << r.output;
      r = shell("env WB_SPLIT_SHADOWS=1 " + std::string(WB_WORKBENCH_BIN) + " render" + common + "--out " +
                (dir / "split.exr").string() + " --stats " + (dir / "split.json").string() + " --reference " +
                (dir / "loop.exr").string());
      ASSERT_EQ(r.code, 0) << r.output;
      const auto loop = readJsonFile(dir / "loop.json"), split = readJsonFile(dir / "split.json");
      EXPECT_FALSE(loop["split_shadows"].get<bool>());
      EXPECT_TRUE(split["split_shadows"].get<bool>());
      EXPECT_EQ(split["rays"], loop["rays"]);
      EXPECT_EQ(split["shadow_rays"], loop["shadow_rays"]);
      EXPECT_GT(split["shadow_rays"].get<uint64_t>(), 0u);
      EXPECT_EQ(split["nan_inf_dropped"], 0);
      EXPECT_LT(split["error_vs_reference"]["rel_mse"].get<double>(), 1e-10) << split.dump();
    }
  }
  // Fewer slots than requests (WB_SPLIT_SLOTS): the rest go through the path loop's own shadow iterations.
  for (const char* slots : {"0", "1"}) {
    SCOPED_TRACE(slots);
    const CommandResult r =
        shell("env WB_SPLIT_SHADOWS=1 WB_SPLIT_SLOTS=" + std::string(slots) + " " +
              std::string(WB_WORKBENCH_BIN) + " render" + cornell + "--out " + (dir / "few.exr").string() +
              " --stats " + (dir / "few.json").string() + " --reference " + (dir / "loop.exr").string());
    ASSERT_EQ(r.code, 0) << r.output;
    const auto few = readJsonFile(dir / "few.json");
    EXPECT_TRUE(few["split_shadows"].get<bool>());
    EXPECT_EQ(few["shadow_rays"], readJsonFile(dir / "loop.json")["shadow_rays"]);
    EXPECT_LT(few["error_vs_reference"]["rel_mse"].get<double>(), 1e-10) << few.dump();
  }
  const std::string denoised = " render --size 24x24 --spp 3 --denoise ";
  CommandResult r = run(denoised + "--out " + (dir / "loop_denoised.exr").string());
  ASSERT_EQ(r.code, 0) << r.output;
  r = shell("env WB_SPLIT_SHADOWS=1 " + std::string(WB_WORKBENCH_BIN) + denoised + "--out " +
            (dir / "split_denoised.exr").string() + " --stats " + (dir / "split_denoised.json").string() +
            " --reference " + (dir / "loop_denoised.exr").string());
  ASSERT_EQ(r.code, 0) << r.output;
  const auto split = readJsonFile(dir / "split_denoised.json");
  EXPECT_TRUE(split["split_shadows"].get<bool>());
  EXPECT_LT(split["error_vs_reference"]["rel_mse"].get<double>(), 1e-10) << split.dump();
}
