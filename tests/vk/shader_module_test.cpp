// ShaderModule and Specialization on the real device: a compute stage compiled with its own entry point name
// and a specialisation constant runs, and writes the constant's value.
#include <gtest/gtest.h>

#include "shader/compiler.h"
#include "vk/check.h"
#include "vk/context.h"
#include "vk/resources.h"
#include "vk/shader_module.h"

using namespace wb;

namespace {

constexpr const char* kSource = R"(#version 460
#extension GL_EXT_buffer_reference : require
layout(constant_id = 3) const uint kValue = 1u;
layout(buffer_reference, std430) buffer Out { uint v[]; };
layout(push_constant) uniform Push { Out dst; } pc;
layout(local_size_x = 1) in;
void main() { pc.dst.v[0] = kValue; }
)";

shader::CompiledShader compileCompute(const std::string& entry) {
  shader::CompileInput in;
  in.path = "/virtual/fill.comp";
  in.source = kSource;
  in.stage = shader::Stage::Compute;
  in.entry = entry;
  shader::CompiledShader s;
  s.key.path = in.path;
  s.key.entry = entry;
  s.stage = in.stage;
  s.spirv = shader::compileGlsl(in).spirv;
  return s;
}

// Runs the stage once; returns what it wrote.
uint32_t runOnce(vk::Context& ctx, const shader::CompiledShader& stage,
                 const std::vector<vk::SpecializationConstant>& constants) {
  vk::Buffer out(ctx, 16, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT,
                 true);
  std::memset(out.mapped(), 0, 16);
  VkPushConstantRange range{VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(VkDeviceAddress)};
  VkPipelineLayoutCreateInfo li{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
  li.pushConstantRangeCount = 1;
  li.pPushConstantRanges = &range;
  VkPipelineLayout layout = VK_NULL_HANDLE;
  WB_VK(vkCreatePipelineLayout(ctx.device(), &li, nullptr, &layout));
  const vk::Specialization spec(constants);
  VkPipeline pipeline = VK_NULL_HANDLE;
  {
    const vk::ShaderModule module(ctx.device(), stage);
    VkComputePipelineCreateInfo ci{VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO};
    ci.stage = module.stageInfo(spec.info());
    ci.layout = layout;
    WB_VK(vkCreateComputePipelines(ctx.device(), VK_NULL_HANDLE, 1, &ci, nullptr, &pipeline));
  }  // the module may go once the pipeline exists
  const VkDeviceAddress address = out.address();
  ctx.submitAndWait([&](VkCommandBuffer cmd) {
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline);
    vkCmdPushConstants(cmd, layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof address, &address);
    vkCmdDispatch(cmd, 1, 1, 1);
  });
  vkDestroyPipeline(ctx.device(), pipeline, nullptr);
  vkDestroyPipelineLayout(ctx.device(), layout, nullptr);
  uint32_t v = 0;
  std::memcpy(&v, out.mapped(), sizeof v);
  return v;
}

}  // namespace

TEST(ShaderModule, StageInfoNamesTheStagesOwnEntryPoint) {
  vk::ContextOptions o;
  o.validation = true;
  vk::Context ctx(o);
  const auto stage = compileCompute("fill");
  const vk::ShaderModule module(ctx.device(), stage);
  const VkPipelineShaderStageCreateInfo si = module.stageInfo();
  EXPECT_STREQ(si.pName, "fill");
  EXPECT_EQ(si.stage, VK_SHADER_STAGE_COMPUTE_BIT);
  EXPECT_NE(si.module, VK_NULL_HANDLE);
  EXPECT_EQ(si.pSpecializationInfo, nullptr);
  // A pipeline made from it runs: the driver found "fill" (with "main" the validation layer and the driver
  // would refuse it: the module has no such entry point).
  EXPECT_EQ(runOnce(ctx, stage, {}), 1u);  // the constant's default
  EXPECT_EQ(ctx.validationErrors(), 0u);
}

TEST(ShaderModule, SpecializationConstantsReachTheStage) {
  vk::ContextOptions o;
  o.validation = true;
  vk::Context ctx(o);
  const auto stage = compileCompute("main");
  EXPECT_EQ(runOnce(ctx, stage, {{3, 42u}}), 42u);
  EXPECT_EQ(runOnce(ctx, stage, {{7, 5u}, {3, 9u}}), 9u);  // by id, not by position; unknown ids are ignored
  EXPECT_EQ(vk::Specialization({}).info(), nullptr);
  const vk::Specialization two({{7, 5u}, {3, 9u}});
  ASSERT_NE(two.info(), nullptr);
  EXPECT_EQ(two.info()->mapEntryCount, 2u);
  EXPECT_EQ(two.info()->dataSize, 8u);
  EXPECT_EQ(ctx.validationErrors(), 0u);
}
