// The real device on this machine (lavapipe here, a GPU where there is one), under the validation layer.
#include <gtest/gtest.h>

#include <link.h>

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <set>
#include <string>
#include <filesystem>
#include <fstream>
#include <unistd.h>

#include "common/paths.h"
#include "vk/context.h"
#include "vk/driver_policy.h"

using namespace wb::vk;

TEST(Context, CreatesRayTracingDeviceWithValidation) {
  ContextOptions o;
  o.validation = true;
  Context ctx(o);
  EXPECT_FALSE(ctx.deviceName().empty());
  EXPECT_GT(ctx.rayTracing().handleSize, 0u);
  EXPECT_GE(ctx.rayTracing().maxRecursionDepth, 2u);
  ctx.submitAndWait([](VkCommandBuffer) {});
  EXPECT_EQ(ctx.validationErrors(), 0u);
}

TEST(Context, UnknownDeviceNameIsAClearError) {
  ContextOptions o;
  o.deviceName = "no-such-gpu-xyz";
  try {
    Context ctx(o);
    FAIL() << "expected an error";
  } catch (const VulkanError& e) {
    EXPECT_NE(std::string(e.what()).find("no-such-gpu-xyz"), std::string::npos) << e.what();
  }
}

TEST(PipelineCache, PersistsAndRejectsForeignOrCorruptData) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / ("wb_pcache_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  ContextOptions o;
  o.pipelineCacheDir = dir.string();
  {
    Context ctx(o);  // creates and, at exit, saves the cache
    ASSERT_NE(ctx.pipelineCache(), VK_NULL_HANDLE);
  }
  ASSERT_FALSE(fs::is_empty(dir));
  const fs::path file = fs::directory_iterator(dir)->path();
  {
    Context ctx(o);
    EXPECT_GT(ctx.pipelineCacheObject()->loadedBytes(), 0u) << "the saved cache is loaded back";
    EXPECT_TRUE(ctx.pipelineCacheObject()->warning().empty());
  }
  // Garbage of the right size but with a wrong header is discarded with a warning, not handed to the driver.
  {
    std::ofstream f(file, std::ios::binary | std::ios::trunc);
    f << std::string(64, 'x');
  }
  {
    Context ctx(o);
    EXPECT_EQ(ctx.pipelineCacheObject()->loadedBytes(), 0u);
    EXPECT_NE(ctx.pipelineCacheObject()->warning().find("another device"), std::string::npos);
  }
  fs::remove_all(dir);
}

TEST(PipelineCache, HeaderCheck) {
  VkPhysicalDeviceProperties props{};
  props.vendorID = 0x10de;
  props.deviceID = 0x2330;
  for (uint32_t i = 0; i < VK_UUID_SIZE; ++i) props.pipelineCacheUUID[i] = uint8_t(i);
  VkPipelineCacheHeaderVersionOne h{};
  h.headerSize = sizeof(h);
  h.headerVersion = VK_PIPELINE_CACHE_HEADER_VERSION_ONE;
  h.vendorID = props.vendorID;
  h.deviceID = props.deviceID;
  std::memcpy(h.pipelineCacheUUID, props.pipelineCacheUUID, VK_UUID_SIZE);
  EXPECT_TRUE(PipelineCache::headerMatches(&h, sizeof(h), props));
  EXPECT_FALSE(PipelineCache::headerMatches(&h, sizeof(h) - 1, props)) << "truncated";
  auto other = h;
  other.deviceID = 0x1234;
  EXPECT_FALSE(PipelineCache::headerMatches(&other, sizeof(other), props)) << "another GPU";
  other = h;
  other.pipelineCacheUUID[3] ^= 1;
  EXPECT_FALSE(PipelineCache::headerMatches(&other, sizeof(other), props)) << "another driver build";
}

namespace {
std::set<std::string> loadedLibraries() {
  std::set<std::string> names;
  dl_iterate_phdr(
      [](dl_phdr_info* info, size_t, void* out) {
        if (info->dlpi_name && info->dlpi_name[0] == '/')
          static_cast<std::set<std::string>*>(out)->insert(info->dlpi_name);
        return 0;
      },
      &names);
  return names;
}
}  // namespace

// What an instance loaded (the driver, the layers, the other drivers the loader tried) stays loaded after the
// instance is gone: NVIDIA's driver takes static TLS each time it is loaded and could not be loaded again
// after ~20 instances in one process (vk/context.cpp). Without that, the loader unloads the validation layer
// and the drivers it did not pick here (lavapipe itself stays either way).
TEST(Context, WhatAnInstanceLoadedStaysLoadedAfterIt) {
  const auto before = loadedLibraries();
  std::set<std::string> loadedByContext;
  {
    ContextOptions o;
    o.validation = true;
    Context ctx(o);
    for (const auto& n : loadedLibraries())
      if (!before.count(n)) loadedByContext.insert(n);
  }
  // ctest runs each test in a process of its own, where this first instance loads the driver.
  if (loadedByContext.empty()) GTEST_SKIP() << "an earlier test of this process loaded (and kept) the driver";
  const auto after = loadedLibraries();
  for (const auto& n : loadedByContext) EXPECT_TRUE(after.count(n)) << n << " was unloaded";
}

// The workbench's llvmpipe default (vk/driver_policy.h) reaches the driver: set before the driver reads it,
// at the process's first instance, with a Mesa cache folder of its own width.
TEST(Context, LlvmpipeCompilesFourLanesWideUnlessTheUserChoseAWidth) {
  const auto applied = applyDriverDefaults(wb::shaderCacheDir());
  const bool ours = std::find(applied.begin(), applied.end(), "LP_NATIVE_VECTOR_WIDTH=128") != applied.end();
  Context ctx;
  if (!ctx.policy().compilesAtFirstDispatch) GTEST_SKIP() << "not lavapipe: " << ctx.deviceName();
  if (!ours) {
    GTEST_SKIP() << "LP_NATIVE_VECTOR_WIDTH or MESA_SHADER_CACHE_DIR set by the user";
  }
  EXPECT_STREQ(std::getenv("LP_NATIVE_VECTOR_WIDTH"), "128");
  EXPECT_NE(ctx.deviceName().find("128 bits"), std::string::npos) << ctx.deviceName();
  EXPECT_EQ(std::string(std::getenv("MESA_SHADER_CACHE_DIR")),
            (wb::shaderCacheDir() / "mesa" / "lp128").string());
}
