// Every third-party shader in shared/assets/shaders-external compiles and reflects, or fails for a reason
// we can explain.
#include "common/paths.h"
#include "shader/library.h"
#include "test_util.h"

#include <algorithm>
#include <map>

using namespace wb::shader;
using namespace wb::shader::test;

namespace {

// File text marker -> why glslang 12 (Debian 12) cannot compile it.
const std::map<std::string, std::string> kExplained = {
    // Added to glslang after version 12: "extension not supported".
    {"GL_EXT_ray_tracing_position_fetch", "GL_EXT_ray_tracing_position_fetch"},
};

std::optional<std::string> expectedFailure(const fs::path& p) {
  const std::string text = readAll(p);
  for (const auto& [marker, reason] : kExplained)
    if (text.find(marker) != std::string::npos) return reason;
  return std::nullopt;
}

}  // namespace

TEST(ExternalShaders, CompileAndReflectOrFailForAKnownReason) {
  const fs::path root = wb::sharedDir() / "assets/shaders-external";
  if (!fs::exists(root)) GTEST_SKIP() << root << " not present";
  ShaderLibrary lib({.printWarnings = false});
  int ok = 0, explained = 0;
  std::vector<fs::path> files;
  for (const auto& e : fs::recursive_directory_iterator(root))
    if (e.is_regular_file() && stageFromPath(e.path())) files.push_back(e.path());
  std::sort(files.begin(), files.end());
  ASSERT_GT(files.size(), 20u);
  for (const auto& f : files) {
    auto why = expectedFailure(f);
    try {
      auto s = lib.compile({f});
      EXPECT_FALSE(why) << f << " compiled, but was expected to fail (" << *why << ")";
      EXPECT_FALSE(s->spirv.empty());
      // Every ray generation / compute shader here writes an image through a descriptor.
      if (s->stage == Stage::RayGen || s->stage == Stage::Compute) {
        EXPECT_FALSE(s->reflection.bindings.empty()) << f;
      }
      ++ok;
    } catch (const CompileError& e) {
      ASSERT_TRUE(why) << f << " failed unexpectedly:\n" << e.what();
      EXPECT_NE(std::string(e.what()).find(*why), std::string::npos) << e.what();
      EXPECT_EQ(e.diagnostics.front().file, fs::canonical(f)) << e.what();
      EXPECT_GT(e.diagnostics.front().line, 0) << e.what();
      ++explained;
    }
  }
  std::printf("external shaders: %d compiled, %d failed for an explained reason\n", ok, explained);
  EXPECT_GT(ok, 30);
}

TEST(ExternalShaders, RayTracingSamplesMergeIntoOneLayout) {
  const fs::path root = wb::sharedDir() / "assets/shaders-external/SaschaWillems-Vulkan/shaders/glsl";
  if (!fs::exists(root)) GTEST_SKIP();
  ShaderLibrary lib({.printWarnings = false});
  for (const char* sample :
       {"raytracingbasic", "raytracingshadows", "raytracingreflections", "raytracinggltf",
        "raytracingtextures", "raytracingcallable", "raytracingintersection", "raytracingsbtdata"}) {
    std::vector<ShaderKey> keys;
    for (const auto& e : fs::directory_iterator(root / sample))
      if (auto st = stageFromPath(e.path()); st && *st != Stage::Vertex && *st != Stage::Fragment)
        keys.push_back({e.path()});
    if (keys.empty()) continue;
    auto id = lib.registerProgram(sample, keys);
    try {
      auto b = lib.buildProgram(id);
      EXPECT_FALSE(b.layout.bindings.empty()) << sample;
      bool hasTlas = false;
      for (const auto& d : b.layout.bindings)
        hasTlas |= d.type == VK_DESCRIPTOR_TYPE_ACCELERATION_STRUCTURE_KHR;
      EXPECT_TRUE(hasTlas) << sample;
    } catch (const CompileError& e) {
      ADD_FAILURE() << sample << ": " << e.what();
    }
  }
}
