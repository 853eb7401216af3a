// One definition of every host/shader struct (shaders/shared/*_types.h) only holds if the shaders lay the
// structs out as C++ does: the block and element sizes that SPIRV-Cross reflects from the real shaders equal
// sizeof(gpu::...) on the host. A member added on one side only, or a layout qualifier changed, fails here.
#include <gtest/gtest.h>

#include <spirv_cross/spirv_cross.hpp>

#include <fstream>
#include <map>
#include <regex>
#include <string>

#include "common/paths.h"
#include "display/display_types.h"
#include "shader/library.h"
#include "shared/debug_types.h"
#include "shared/denoise_types.h"
#include "shared/hybrid_types.h"
#include "shared/inspect_types.h"
#include "shared/pathtracer_types.h"
#include "shared/roofline_types.h"
#include "shared/scene_types.h"

namespace {

// Sizes in a module by block name: a block whose only member is a runtime array reports its element stride,
// any other block its declared size. Buffer-reference blocks (VertexBuffer) count too.
std::map<std::string, size_t> blockSizes(const std::vector<uint32_t>& spirv) {
  spirv_cross::Compiler c(spirv);
  std::map<std::string, size_t> sizes;
  const uint32_t bound = spirv.at(3);  // SPIR-V header: every id is below it
  for (uint32_t id = 1; id < bound; ++id) {
    const spirv_cross::SPIRType* t = nullptr;
    try {
      t = &c.get_type(id);
    } catch (const spirv_cross::CompilerError&) {
      continue;  // not a type
    }
    if (t->basetype != spirv_cross::SPIRType::Struct || t->pointer || id != t->self) continue;
    const std::string name = c.get_name(id);
    if (name.empty() || t->member_types.size() != 1) continue;
    const auto& member = c.get_type(t->member_types[0]);
    if (!member.array.empty() && member.array.back() == 0) {
      sizes[name] = c.get_decoration(t->member_types[0], spv::DecorationArrayStride);
    } else if (member.basetype == spirv_cross::SPIRType::Struct) {
      sizes[name] = c.get_declared_struct_size(member);
    }
  }
  return sizes;
}

std::map<std::string, size_t> moduleBlocks(const std::string& rel,
                                           std::vector<wb::shader::Define> defines = {}) {
  wb::shader::ShaderLibrary lib({.includeRoots = {wb::shaderDir()}, .cacheDir = {}, .printWarnings = false});
  const auto compiled = lib.compile({wb::shaderDir() / rel, std::nullopt, defines});
  return blockSizes(compiled->spirv);
}

}  // namespace

TEST(GpuTypesLayout, PathTracerBlocksMatchTheHostStructs) {
  using namespace wb::gpu;
  const auto chit = moduleBlocks("pathtracer/closesthit.rchit");
  const std::map<std::string, size_t> expected = {
      {"FrameBlock", sizeof(FrameUniforms)},    {"GeometryBlock", sizeof(GeometryInfo)},
      {"MaterialBlock", sizeof(Material)},      {"LightBlock", sizeof(DirectionalLight)},
      {"EnvAliasBlock", sizeof(EnvAliasEntry)}, {"EmitterBlock", sizeof(EmissiveTriangle)},
      {"PushBlock", sizeof(PushConstants)},     {"VertexBuffer", sizeof(Vertex)},
  };
  for (const auto& [block, size] : expected) {
    ASSERT_TRUE(chit.count(block)) << "closesthit.rchit has no block " << block;
    EXPECT_EQ(chit.at(block), size) << block;
  }
  const auto raygen = moduleBlocks("pathtracer/raygen.rgen");
  ASSERT_TRUE(raygen.count("CounterBlock"));
  EXPECT_EQ(raygen.at("CounterBlock"), sizeof(Counters));
}

TEST(GpuTypesLayout, HybridAndDisplayBlocksMatchTheHostStructs) {
  using namespace wb::gpu;
  const auto vert = moduleBlocks("hybrid/gbuffer.vert");
  ASSERT_TRUE(vert.count("HybridFrameBlock") && vert.count("DrawBlock") && vert.count("VertexBuffer"));
  EXPECT_EQ(vert.at("HybridFrameBlock"), sizeof(HybridUniforms));
  EXPECT_EQ(vert.at("DrawBlock"), sizeof(HybridDrawConstants));
  EXPECT_EQ(vert.at("VertexBuffer"), sizeof(Vertex));
  EXPECT_EQ(vert.at("GeometryBlock"), sizeof(GeometryInfo));
  const auto frag = moduleBlocks("hybrid/gbuffer.frag");
  ASSERT_TRUE(frag.count("MaterialBlock"));
  EXPECT_EQ(frag.at("MaterialBlock"), sizeof(Material));
  for (const char* stage : {"hybrid/shadow_ao.rgen", "hybrid/reflect.rgen"}) {
    const auto rt = moduleBlocks(stage);
    ASSERT_TRUE(rt.count("HybridInspectBlock")) << stage;
    EXPECT_EQ(rt.at("HybridInspectBlock"), sizeof(HybridInspectRecord)) << stage;
    EXPECT_EQ(rt.at("HybridFrameBlock"), sizeof(HybridUniforms)) << stage;
  }
  const auto display = moduleBlocks("display/display.frag");
  ASSERT_TRUE(display.count("Push"));
  EXPECT_EQ(display.at("Push"), sizeof(DisplayPush));
}

TEST(GpuTypesLayout, PathInspectorBlocksMatchTheHostStructs) {
  using namespace wb::gpu;
  for (const char* stage :
       {"pathtracer/raygen.rgen", "pathtracer/closesthit.rchit", "pathtracer/miss.rmiss"}) {
    const auto blocks = moduleBlocks(stage, {{"WB_INSPECT", "1"}});
    for (const auto& [block, size] :
         std::map<std::string, size_t>{{"InspectHeaderBlock", sizeof(InspectHeader)},
                                       {"InspectSampleBlock", sizeof(InspectSample)},
                                       {"InspectVertexBlock", sizeof(InspectVertex)}}) {
      if (!blocks.count(block)) continue;  // a stage that does not use it
      EXPECT_EQ(blocks.at(block), size) << stage << " " << block;
    }
  }
  const auto chit = moduleBlocks("pathtracer/closesthit.rchit", {{"WB_INSPECT", "1"}});
  EXPECT_TRUE(chit.count("InspectVertexBlock"));
  const auto raygen = moduleBlocks("pathtracer/raygen.rgen", {{"WB_INSPECT", "1"}});
  EXPECT_TRUE(raygen.count("InspectSampleBlock") && raygen.count("InspectHeaderBlock"));
  // The normal build declares none of them.
  EXPECT_FALSE(moduleBlocks("pathtracer/raygen.rgen").count("InspectSampleBlock"));
}

TEST(GpuTypesLayout, DebugPrintAndAssertBlocksMatchTheHostStructs) {
  using namespace wb::gpu;
  // wbPrint records in the inspecting variant, wbAssert failures in the asserts variant (raygen holds both
  // kinds of call: its own wbAssert, and inspect.glsl's reset of the print count).
  const auto inspect = moduleBlocks("pathtracer/closesthit.rchit", {{"WB_INSPECT", "1"}});
  ASSERT_TRUE(inspect.count("InspectPrintBlock"));
  EXPECT_EQ(inspect.at("InspectPrintBlock"), sizeof(PrintRecord));
  const auto asserts = moduleBlocks("pathtracer/raygen.rgen", {{"WB_ASSERTS", "1"}});
  ASSERT_TRUE(asserts.count("AssertHeaderBlock") && asserts.count("AssertRecordBlock"));
  EXPECT_EQ(asserts.at("AssertHeaderBlock"), sizeof(AssertHeader));
  EXPECT_EQ(asserts.at("AssertRecordBlock"), sizeof(AssertRecord));
  EXPECT_FALSE(moduleBlocks("pathtracer/raygen.rgen").count("AssertRecordBlock"));
}

TEST(GpuTypesLayout, DenoiserPushConstantsMatchTheHostStruct) {
  for (const char* stage :
       {"denoise/prepare.comp", "denoise/variance.comp", "denoise/atrous.comp", "denoise/final.comp"}) {
    const auto blocks = moduleBlocks(stage);
    ASSERT_TRUE(blocks.count("PushBlock")) << stage;
    EXPECT_EQ(blocks.at("PushBlock"), sizeof(wb::gpu::DenoisePush)) << stage;
  }
}

TEST(GpuTypesLayout, RooflineBlocksMatchTheHostStructs) {
  using namespace wb::gpu;
  for (const char* stage : {"roofline/roofline.rgen", "roofline/roofline.rchit"}) {
    const auto blocks = moduleBlocks(stage);
    ASSERT_TRUE(blocks.count("PushBlock")) << stage;
    EXPECT_EQ(blocks.at("PushBlock"), sizeof(RooflineConstants)) << stage;
    EXPECT_EQ(blocks.at("GeometryBlock"), sizeof(GeometryInfo)) << stage;
  }
}

TEST(GpuTypesLayout, ResolvePassBlocksMatchTheHostStructs) {
  using namespace wb::gpu;
  const auto blocks = moduleBlocks("pathtracer/resolve.comp");
  ASSERT_TRUE(blocks.count("ResolveBlock"));
  EXPECT_EQ(blocks.at("ResolveBlock"), sizeof(ResolveConstants));
  EXPECT_EQ(blocks.at("SampleSlotBlock"), sizeof(float) * 4);  // vec4 per slot
}

// Every descriptor binding of shared/bindings.h has a number of its own: two resources given one number (two
// features added apart) alias where one shader declares both, and a pipeline layout keeps only one of them
// (the other's records are written into the first's buffer), unnoticed while their types agree.
TEST(GpuTypesLayout, EveryBindingNumberIsUsedOnce) {
  std::ifstream in(wb::shaderDir() / "shared" / "bindings.h");
  ASSERT_TRUE(in) << "shared/bindings.h";
  const std::regex define(R"(^#define (WB_BIND_\w+) (\d+)\b)");
  std::map<int, std::string> byNumber;
  std::string line;
  size_t defines = 0;
  while (std::getline(in, line)) {
    std::smatch m;
    if (!std::regex_search(line, m, define)) continue;
    ++defines;
    const auto [it, fresh] = byNumber.emplace(std::stoi(m[2]), m[1]);
    EXPECT_TRUE(fresh) << m[1] << " and " << it->second << " are both binding " << m[2];
  }
  EXPECT_GT(defines, 20u) << "the bindings are #defines of shared/bindings.h";
}
