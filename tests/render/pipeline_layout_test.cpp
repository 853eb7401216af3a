// The path tracer's descriptor-set layout comes from reflecting its stages: check it against the bindings the
// shared header promises, with the right types and the union of the stages that use each.
#include <gtest/gtest.h>

#include <map>

#include "common/paths.h"
#include "render/path_tracer.h"
#include "shader/library.h"

using namespace wb;

TEST(PathTracerLayout, ReflectedBindingsMatchTheSharedHeader) {
  shader::ShaderLibrary::Options o;
  o.includeRoots = {shaderDir()};
  shader::ShaderLibrary lib(o);  // memory-only: this test must compile for real
  const auto id =
      lib.registerProgram("pathtracer", render::PathTracer::stageKeys(scene::genericFeatures(), false));
  const auto build = lib.buildProgram(id);
  ASSERT_EQ(build.stages.size(), 5u);

  const VkShaderStageFlags rgen = VK_SHADER_STAGE_RAYGEN_BIT_KHR, chit = VK_SHADER_STAGE_CLOSEST_HIT_BIT_KHR,
                           ahit = VK_SHADER_STAGE_ANY_HIT_BIT_KHR, miss = VK_SHADER_STAGE_MISS_BIT_KHR;
  struct Expected {
    VkDescriptorType type;
    VkShaderStageFlags stages;
    bool runtimeArray;
  };
  const std::map<uint32_t, Expected> expected = {
      {WB_BIND_TLAS, {VK_DESCRIPTOR_TYPE_ACCELERATION_STRUCTURE_KHR, rgen, false}},
      {WB_BIND_ACCUM, {VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, rgen, false}},
      {WB_BIND_FRAME, {VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, rgen | chit | miss, false}},
      {WB_BIND_GEOMETRIES, {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, chit | ahit, false}},
      {WB_BIND_MATERIALS, {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, chit | ahit, false}},
      {WB_BIND_LIGHTS, {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, chit | miss, false}},  // miss: the suns' discs
      {WB_BIND_TEXTURES, {VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, chit | ahit, true}},
      {WB_BIND_ENV_MAP, {VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, chit | miss, false}},
      {WB_BIND_ENV_ALIAS, {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, chit | miss, false}},
      {WB_BIND_AOV_ALBEDO, {VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, rgen, false}},
      {WB_BIND_AOV_NORMAL, {VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, rgen, false}},
      {WB_BIND_AOV_INFO, {VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, rgen, false}},
      {WB_BIND_AOV_STATS, {VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, rgen, false}},
      {WB_BIND_COUNTERS, {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, rgen, false}},
      {WB_BIND_BLUE_NOISE, {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, rgen | chit, false}},
      {WB_BIND_SOBOL, {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, rgen | chit, false}},
      {WB_BIND_EMITTERS, {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, chit, false}},
      {WB_BIND_EMITTER_ALIAS, {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, chit, false}},
      {WB_BIND_SAMPLE_SLOTS, {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, rgen, false}},
      {WB_BIND_REFLECTORS, {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, chit, false}},  // reflector guiding
  };
  std::map<uint32_t, const shader::DescriptorBinding*> got;
  for (const auto& b : build.layout.bindings) {
    EXPECT_EQ(b.set, 0u) << b.name;
    got[b.binding] = &b;
  }
  EXPECT_EQ(got.size(), expected.size());
  for (const auto& [binding, e] : expected) {
    SCOPED_TRACE("binding " + std::to_string(binding));
    ASSERT_TRUE(got.count(binding));
    EXPECT_EQ(got[binding]->type, e.type) << got[binding]->name;
    EXPECT_EQ(got[binding]->stages, e.stages)
        << got[binding]->name << ": " << shader::stageFlagsToString(got[binding]->stages);
    EXPECT_EQ(got[binding]->runtimeArray, e.runtimeArray) << got[binding]->name;
  }
  ASSERT_EQ(build.layout.pushConstants.size(), 1u);
  EXPECT_EQ(build.layout.pushConstants[0].offset, 0u);
  EXPECT_EQ(build.layout.pushConstants[0].size, sizeof(gpu::PushConstants));
  EXPECT_EQ(build.layout.pushConstants[0].stageFlags, rgen | chit | ahit | miss);
}

// OpTraceRayKHR instructions in a SPIR-V module.
static int traceRayInstructions(const std::vector<uint32_t>& spirv) {
  constexpr uint32_t kOpTraceRayKHR = 4445;
  int n = 0;
  for (size_t i = 5; i < spirv.size();) {
    const uint32_t words = spirv[i] >> 16;
    if ((spirv[i] & 0xffffu) == kOpTraceRayKHR) ++n;
    if (words == 0) break;
    i += words;
  }
  return n;
}

// Every ray of the path tracer, shadow rays included, leaves from one traceRayEXT in raygen: lavapipe
// compiles a traversal into the pipeline per call site, and each costs JIT time on every shader edit
// (payload.glsl).
TEST(PathTracerLayout, RaygenIsTheOnlyStageThatTracesRaysFromOneCallSite) {
  shader::ShaderLibrary::Options o;
  o.includeRoots = {shaderDir()};
  shader::ShaderLibrary lib(o);
  scene::SceneFeatures specialised;
  specialised.generic = false;
  specialised.directionalLights = 3;
  for (const auto& features : {scene::genericFeatures(), specialised}) {
    SCOPED_TRACE(scene::describeFeatures(features));
    const auto build =
        lib.buildProgram(lib.registerProgram("pt", render::PathTracer::stageKeys(features, false)));
    ASSERT_EQ(build.stages.size(), 5u);
    for (const auto& st : build.stages) {
      EXPECT_EQ(traceRayInstructions(st->spirv), st->stage == shader::Stage::RayGen ? 1 : 0)
          << st->key.path.filename();
    }
  }
}

// The cost variant traces each sample alone in its subgroup where the device policy asks for it
// (DevicePolicy::costIsolatesLanes): its ray generation stage then uses subgroup operations; the default
// variant never does, nor the inspecting or asserting variants, nor a cost variant without a shader clock
// (nothing to isolate).
TEST(PathTracerLayout, TheCostVariantIsolatesLanesOnlyWhereAsked) {
  shader::ShaderLibrary::Options o;
  o.includeRoots = {shaderDir()};
  shader::ShaderLibrary lib(o);
  // SPIR-V's OpCapability GroupNonUniform (word 0x00020011: opcode 17, two words; capability 61).
  auto isolates = [&](bool inspect, const render::Instrumentation& instrumentation, uint32_t clock,
                      bool isolate) {
    const auto keys = render::PathTracer::stageKeys(scene::genericFeatures(), false, inspect, instrumentation,
                                                    clock, isolate);
    const auto raygen = lib.compile(keys.front());
    EXPECT_EQ(keys.front().path.filename(), "raygen.rgen");
    const auto& w = raygen->spirv;
    for (size_t i = 5; i + 1 < w.size(); ++i)
      if (w[i] == 0x00020011u && w[i + 1] == 61u) return true;
    return false;
  };
  const render::Instrumentation cost{.cost = true}, none{};
  EXPECT_TRUE(isolates(false, cost, WB_CLOCK_SUBGROUP, true));
  EXPECT_TRUE(isolates(false, cost, WB_CLOCK_DEVICE, true));
  EXPECT_FALSE(isolates(true, none, WB_CLOCK_SUBGROUP, true)) << "the inspecting variant";
  EXPECT_FALSE(isolates(true, cost, WB_CLOCK_SUBGROUP, true)) << "the inspecting variant with the cost AOV";
  EXPECT_FALSE(
      isolates(false, render::Instrumentation{.cost = true, .asserts = true}, WB_CLOCK_SUBGROUP, true));
  EXPECT_FALSE(isolates(false, cost, WB_CLOCK_SUBGROUP, false));
  EXPECT_FALSE(isolates(false, cost, WB_CLOCK_NONE, true)) << "no clock: nothing to isolate";
  EXPECT_FALSE(isolates(false, none, WB_CLOCK_SUBGROUP, true)) << "the default variant";
  EXPECT_FALSE(isolates(false, render::Instrumentation{.asserts = true}, WB_CLOCK_SUBGROUP, true));
}
