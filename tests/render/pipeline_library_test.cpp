// Ray tracing pipelines linked from per-group pipeline libraries: a rebuild with unchanged stages reuses
// every library, an edit of one stage compiles exactly one new library (the edit-to-pipeline win on GPUs),
// and the cache never destroys a library a pipeline in use was linked from.
#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iterator>

#include "shader/library.h"
#include "vk/context.h"
#include "vk/pipeline_layout.h"
#include "vk/rt_pipeline.h"

using namespace wb;

TEST(PipelineLibrary, AnEditOfOneStageCompilesOneLibrary) {
  vk::ContextOptions o;
  o.validation = true;
  vk::Context ctx(o);
  if (!ctx.pipelineLibrarySupported()) GTEST_SKIP() << ctx.deviceName() << " has no VK_KHR_pipeline_library";
  // A copy of the test program, so the test can edit its closest-hit shader.
  const auto dir =
      std::filesystem::temp_directory_path() / ("wb_pipeline_library_" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  std::filesystem::copy(std::filesystem::path(WB_SOURCE_DIR) / "tests/shader/data/rt", dir);
  shader::ShaderLibrary lib({.includeRoots = {dir}, .cacheDir = {}, .printWarnings = false});
  auto compileAll = [&] {
    return std::vector<std::shared_ptr<const shader::CompiledShader>>{
        lib.compile({dir / "rt.rgen"}), lib.compile({dir / "rt.rmiss"}), lib.compile({dir / "rt.rchit"}),
        lib.compile({dir / "rt.rahit"})};
  };
  vk::RtBindingTable groups;
  groups.raygen("rt.rgen").miss("rt.rmiss").hitGroup({.closestHit = "rt.rchit", .anyHit = "rt.rahit"});
  const auto stages = compileAll();
  EXPECT_GT(stages[0]->reflection.rayPayloadBytes, 0u);
  EXPECT_GT(stages[2]->reflection.hitAttributeBytes, 0u);
  const auto layoutDesc = shader::mergeLayouts(stages);
  vk::PipelineLayout layout(ctx, layoutDesc);
  vk::RtLibraryCache cache(ctx);
  const std::string layoutId = vk::layoutKey(layoutDesc);

  auto first = std::make_unique<vk::RayTracingPipeline>(
      ctx, stages, groups, layout.handle(), 1, std::vector<vk::SpecializationConstant>{}, &cache, layoutId);
  EXPECT_TRUE(first->linked());
  EXPECT_EQ(cache.librariesCreated(), 3u) << "one library per group";
  EXPECT_EQ(first->libraryStats().librariesCompiled, 3u);
  EXPECT_EQ(first->libraryStats().librariesReused, 0u);
  EXPECT_GT(first->libraryStats().libraryMs, 0.0);
  EXPECT_GT(first->libraryStats().linkMs, 0.0);
  vk::RayTracingPipeline again(ctx, stages, groups, layout.handle(), 1, {}, &cache, layoutId);
  EXPECT_EQ(cache.librariesCreated(), 3u) << "unchanged stages reuse their libraries";
  EXPECT_EQ(again.libraryStats().librariesCompiled, 0u);
  EXPECT_EQ(again.libraryStats().librariesReused, 3u);
  EXPECT_EQ(again.libraryStats().libraryMs, 0.0);

  // Edit the closest-hit shader: only the hit group's library is new.
  {
    std::ifstream in(dir / "rt.rchit");
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    text.replace(text.rfind('}'), 1, "  payload.color *= 0.5;\n}");
    std::ofstream(dir / "rt.rchit", std::ios::trunc) << text;
  }
  lib.invalidateFiles({std::filesystem::canonical(dir / "rt.rchit")});  // what the watcher does on a save
  const auto edited = compileAll();
  ASSERT_NE(edited[2]->spirv, stages[2]->spirv);
  ASSERT_EQ(edited[0].get(), stages[0].get());
  vk::RayTracingPipeline afterEdit(ctx, edited, groups, layout.handle(), 1, {}, &cache, layoutId);
  EXPECT_EQ(cache.librariesCreated(), 4u);
  EXPECT_EQ(afterEdit.libraryStats().librariesCompiled, 1u);
  EXPECT_EQ(afterEdit.libraryStats().librariesReused, 2u);
  EXPECT_NE(afterEdit.libraryKeys()[2], first->libraryKeys()[2]);
  EXPECT_EQ(afterEdit.libraryKeys()[0], first->libraryKeys()[0]);
  EXPECT_EQ(afterEdit.sbt().layout().hit.size, first->sbt().layout().hit.size);

  // Trimming keeps what a pipeline in use was linked from.
  cache.trim(0, afterEdit.libraryKeys());
  EXPECT_EQ(cache.size(), 3u);
  first.reset();
  EXPECT_EQ(ctx.validationErrors(), 0u);
  std::filesystem::remove_all(dir);
}
