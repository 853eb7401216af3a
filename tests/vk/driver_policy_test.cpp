// The driver policy is a pure function of what the device is and of the environment's overrides: each
// choice the workbench makes per driver, checked for a CPU implementation (lavapipe) and a GPU.
#include <gtest/gtest.h>

#include <cstdlib>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "vk/driver_policy.h"

using wb::vk::checkDriverEnvironment;
using wb::vk::DevicePolicy;
using wb::vk::DeviceTraits;
using wb::vk::PolicyOverrides;
using wb::vk::resolveDevicePolicy;

namespace {

DeviceTraits cpu() {
  DeviceTraits t;
  t.cpuImplementation = true;
  t.pipelineLibrarySupported = true;  // lavapipe exposes VK_KHR_pipeline_library
  t.deferredHostOpsSupported = true;
  return t;
}

DeviceTraits gpu() {
  DeviceTraits t = cpu();
  t.cpuImplementation = false;
  return t;
}

}  // namespace

TEST(DriverPolicy, ACpuImplementationCompilesAheadAndYieldsToRebuilds) {
  const DevicePolicy p = resolveDevicePolicy(cpu(), {});
  EXPECT_TRUE(p.compilesAtFirstDispatch);
  EXPECT_TRUE(p.jitWarmup);
  EXPECT_FALSE(p.pipelineLibraries) << "lavapipe's linked pipelines render nothing";
  EXPECT_FALSE(p.deferredHostOps) << "lavapipe crashes linking inside a deferred operation";
  EXPECT_TRUE(p.cpuShapedShaderCode);
  EXPECT_DOUBLE_EQ(p.watchRestRatio, 9.0);   // frames keep a tenth of the CPU
  EXPECT_DOUBLE_EQ(p.windowRestRatio, 9.0);  // the window too
  EXPECT_DOUBLE_EQ(p.windowTraceShareWhileCompiling, 0.1);
}

TEST(DriverPolicy, AGpuLinksLibrariesDefersCreationAndNeverRests) {
  const DevicePolicy p = resolveDevicePolicy(gpu(), {});
  EXPECT_FALSE(p.compilesAtFirstDispatch);
  EXPECT_FALSE(p.jitWarmup);
  EXPECT_TRUE(p.pipelineLibraries);
  EXPECT_TRUE(p.deferredHostOps);
  EXPECT_FALSE(p.cpuShapedShaderCode);
  EXPECT_EQ(p.watchRestRatio, 0.0);
  EXPECT_EQ(p.windowRestRatio, 0.0);
  EXPECT_EQ(p.windowTraceShareWhileCompiling, 1.0);
  DeviceTraits noLibraries = gpu();
  noLibraries.pipelineLibrarySupported = false;
  EXPECT_FALSE(resolveDevicePolicy(noLibraries, {}).pipelineLibraries);
}

TEST(DriverPolicy, OverridesWinWhereTheDriverAllowsThem) {
  PolicyOverrides o;
  o.jitWarmup = false;
  o.pipelineLibraries = true;
  o.deferredHostOps = true;
  o.cpuShapedShaderCode = false;
  o.rebuildRestRatio = 2.5;
  const DevicePolicy c = resolveDevicePolicy(cpu(), o);
  EXPECT_FALSE(c.jitWarmup);
  EXPECT_TRUE(c.pipelineLibraries);
  EXPECT_FALSE(c.deferredHostOps) << "never on a CPU implementation, whatever is asked";
  EXPECT_FALSE(c.cpuShapedShaderCode);
  EXPECT_DOUBLE_EQ(c.watchRestRatio, 2.5);
  EXPECT_DOUBLE_EQ(c.windowRestRatio, 2.5);
  o.rebuildRestRatio = -3.0;
  EXPECT_EQ(resolveDevicePolicy(gpu(), o).watchRestRatio, 0.0) << "a negative ratio counts as 0";
  PolicyOverrides on;
  on.jitWarmup = true;
  on.cpuShapedShaderCode = true;
  on.deferredHostOps = false;
  const DevicePolicy g = resolveDevicePolicy(gpu(), on);
  EXPECT_TRUE(g.jitWarmup);
  EXPECT_TRUE(g.cpuShapedShaderCode);
  EXPECT_FALSE(g.deferredHostOps);
}

TEST(DriverPolicy, TheEnvironmentIsReadThroughOneReader) {
  ::setenv("WB_JIT_WARMUP", "0", 1);
  ::setenv("WB_PIPELINE_LIBRARY", "1", 1);
  ::setenv("WB_DEFERRED_HOST_OPS", "0", 1);
  ::setenv("WB_CPU_DEVICE_CODE", "0", 1);
  ::setenv("WB_REBUILD_YIELD", "", 1);  // empty: the default
  const PolicyOverrides o = PolicyOverrides::fromEnvironment();
  EXPECT_EQ(o.jitWarmup, false);
  EXPECT_EQ(o.pipelineLibraries, true);
  EXPECT_EQ(o.deferredHostOps, false);
  EXPECT_EQ(o.cpuShapedShaderCode, false);
  EXPECT_FALSE(o.rebuildRestRatio.has_value());
  ::setenv("WB_REBUILD_YIELD", "4", 1);
  EXPECT_EQ(PolicyOverrides::fromEnvironment().rebuildRestRatio, 4.0);
  for (const char* v : {"WB_JIT_WARMUP", "WB_PIPELINE_LIBRARY", "WB_DEFERRED_HOST_OPS", "WB_CPU_DEVICE_CODE",
                        "WB_REBUILD_YIELD"})
    ::unsetenv(v);
  // A value a variable cannot take is refused naming the variable (it used to mean the default, or "on").
  for (const auto& [name, value] :
       std::vector<std::pair<const char*, const char*>>{{"WB_JIT_WARMUP", "banana"},
                                                        {"WB_PIPELINE_LIBRARY", "abc"},
                                                        {"WB_CPU_DEVICE_CODE", "yes"},
                                                        {"WB_REBUILD_YIELD", "-5"},
                                                        {"WB_REBUILD_YIELD", "0x10"},
                                                        {"WB_DEFERRED_HOST_OPS", "no"}}) {
    ::setenv(name, value, 1);
    try {
      PolicyOverrides::fromEnvironment();
      ADD_FAILURE() << name << "=" << value << " was taken";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(name), std::string::npos) << e.what();
    }
    ::unsetenv(name);
  }
  const PolicyOverrides none = PolicyOverrides::fromEnvironment();
  EXPECT_FALSE(none.jitWarmup || none.pipelineLibraries || none.deferredHostOps || none.cpuShapedShaderCode ||
               none.rebuildRestRatio);
}

// llvmpipe takes any LP_NATIVE_VECTOR_WIDTH and segfaults compiling at widths other than 128, 256 and 512
// (measured on Mesa 25.0.7: 0, 64 and 384 crash, 1024 smashes the stack): those are refused naming the
// variable (issue 33).
TEST(DriverPolicy, LlvmpipeVectorWidthIsOneItCompiles) {
  const char* before = std::getenv("LP_NATIVE_VECTOR_WIDTH");
  const std::string saved = before ? before : "";
  for (const char* width : {"128", "256", "512"}) {
    ::setenv("LP_NATIVE_VECTOR_WIDTH", width, 1);
    EXPECT_NO_THROW(checkDriverEnvironment()) << width;
  }
  for (const char* width : {"0", "64", "-1", "384", "1024", "0x80", "256 ", "abc"}) {
    ::setenv("LP_NATIVE_VECTOR_WIDTH", width, 1);
    try {
      checkDriverEnvironment();
      ADD_FAILURE() << width << " was taken";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("LP_NATIVE_VECTOR_WIDTH="), std::string::npos) << e.what();
    }
  }
  ::setenv("LP_NATIVE_VECTOR_WIDTH", "", 1);  // empty: unset
  EXPECT_NO_THROW(checkDriverEnvironment());
  if (before) {
    ::setenv("LP_NATIVE_VECTOR_WIDTH", saved.c_str(), 1);
  } else {
    ::unsetenv("LP_NATIVE_VECTOR_WIDTH");
  }
}

// The shader clock (the cost variants): enabled wherever the device has it unless WB_SHADER_CLOCK=0; a CPU
// device's costs are read as medians (its clock counts the time the OS ran other threads).
TEST(DriverPolicy, TheShaderClockIsOnWhereSupportedUnlessSwitchedOff) {
  DeviceTraits withClock = gpu();
  withClock.shaderClockSupported = true;
  EXPECT_TRUE(resolveDevicePolicy(withClock, {}).shaderClock);
  EXPECT_FALSE(resolveDevicePolicy(gpu(), {}).shaderClock);
  PolicyOverrides off;
  off.shaderClock = false;
  EXPECT_FALSE(resolveDevicePolicy(withClock, off).shaderClock);
  EXPECT_FALSE(resolveDevicePolicy(withClock, {}).costByMedian);
  EXPECT_TRUE(resolveDevicePolicy(cpu(), {}).costByMedian);
  ::setenv("WB_SHADER_CLOCK", "0", 1);
  EXPECT_EQ(PolicyOverrides::fromEnvironment().shaderClock, false);
  ::setenv("WB_SHADER_CLOCK", "maybe", 1);
  EXPECT_THROW(PolicyOverrides::fromEnvironment(), std::invalid_argument);
  ::unsetenv("WB_SHADER_CLOCK");
  EXPECT_FALSE(PolicyOverrides::fromEnvironment().shaderClock.has_value());
}

// WB_DEVICE_CLOCK=1 makes the cost variants read the device clock instead of the subgroup clock.
TEST(DriverPolicy, TheDeviceClockIsChosenOnlyWhenAsked) {
  DeviceTraits withClock = gpu();
  withClock.shaderClockSupported = true;
  EXPECT_FALSE(resolveDevicePolicy(withClock, {}).deviceClock);
  ::setenv("WB_DEVICE_CLOCK", "1", 1);
  const PolicyOverrides asked = PolicyOverrides::fromEnvironment();
  EXPECT_EQ(asked.deviceClock, true);
  EXPECT_TRUE(resolveDevicePolicy(withClock, asked).deviceClock);
  ::setenv("WB_DEVICE_CLOCK", "yes", 1);
  EXPECT_THROW(PolicyOverrides::fromEnvironment(), std::invalid_argument);
  ::unsetenv("WB_DEVICE_CLOCK");
}

// Lane isolation in the cost variant needs subgroup operations in ray generation: on by default where the
// device has them, WB_COST_ISOLATE=0 turns it off, never on a device without them.
// The split path loop is the default on GPUs, off on lavapipe; both ways can be asked for, and the slots per
// sample lowered.
TEST(DriverPolicy, ShadowRaysAreSplitOnGpus) {
  EXPECT_TRUE(resolveDevicePolicy(gpu(), {}).splitShadows);
  EXPECT_FALSE(resolveDevicePolicy(cpu(), {}).splitShadows);
  PolicyOverrides on, off;
  on.splitShadows = true;
  off.splitShadows = false;
  EXPECT_TRUE(resolveDevicePolicy(cpu(), on).splitShadows);
  EXPECT_FALSE(resolveDevicePolicy(gpu(), off).splitShadows);
  EXPECT_EQ(resolveDevicePolicy(gpu(), {}).splitSlotsLimit, 18u);
  PolicyOverrides few;
  few.splitSlots = 3;
  EXPECT_EQ(resolveDevicePolicy(gpu(), few).splitSlotsLimit, 3u);
}

TEST(DriverPolicy, InvocationsAreReorderedWhereTheDeviceReordersThem) {
  DeviceTraits reorders = gpu(), noOp = gpu();
  reorders.invocationReorderSupported = reorders.invocationReorderReorders = true;
  noOp.invocationReorderSupported = true;
  EXPECT_TRUE(resolveDevicePolicy(reorders, {}).invocationReorder);
  EXPECT_FALSE(resolveDevicePolicy(noOp, {}).invocationReorder);
  EXPECT_FALSE(resolveDevicePolicy(gpu(), {}).invocationReorder);
  EXPECT_FALSE(resolveDevicePolicy(cpu(), {}).invocationReorder);
  PolicyOverrides on, off;
  on.invocationReorder = true;
  off.invocationReorder = false;
  EXPECT_TRUE(resolveDevicePolicy(noOp, on).invocationReorder);  // to measure what the calls cost
  EXPECT_FALSE(resolveDevicePolicy(gpu(), on).invocationReorder);  // never without the feature
  EXPECT_FALSE(resolveDevicePolicy(cpu(), on).invocationReorder);
  EXPECT_FALSE(resolveDevicePolicy(reorders, off).invocationReorder);
}

TEST(DriverPolicy, LaneIsolationIsTheDefaultWhereRayGenerationHasSubgroupOperations) {
  DeviceTraits voting = gpu();
  voting.raygenSubgroupVote = true;
  EXPECT_TRUE(resolveDevicePolicy(voting, {}).costIsolatesLanes) << "on by default";
  EXPECT_FALSE(resolveDevicePolicy(gpu(), {}).costIsolatesLanes)
      << "no subgroup operations in ray generation";
  ::setenv("WB_COST_ISOLATE", "1", 1);
  const PolicyOverrides asked = PolicyOverrides::fromEnvironment();
  EXPECT_TRUE(resolveDevicePolicy(voting, asked).costIsolatesLanes);
  EXPECT_FALSE(resolveDevicePolicy(gpu(), asked).costIsolatesLanes) << "no votes in ray generation";
  EXPECT_FALSE(resolveDevicePolicy(cpu(), asked).costIsolatesLanes) << "lavapipe: none either";
  ::setenv("WB_COST_ISOLATE", "0", 1);
  EXPECT_FALSE(resolveDevicePolicy(voting, PolicyOverrides::fromEnvironment()).costIsolatesLanes);
  ::setenv("WB_COST_ISOLATE", "2", 1);
  EXPECT_THROW(PolicyOverrides::fromEnvironment(), std::invalid_argument);
  ::unsetenv("WB_COST_ISOLATE");
}
