// render::Pass on the device: resources reach the shader by the names it declares (whatever binding number it
// puts them at), a resource changed after the install is rewritten, a program using a name the pass does not
// bind (or more push constants than it pushes) is refused at its declaration, and a pipeline built for a
// variant the pass has left is dropped at install.
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>

#include "render/pass.h"
#include "vk/context.h"

namespace fs = std::filesystem;
using namespace wb;

namespace {

struct PassFixture : ::testing::Test {
  fs::path dir;
  std::unique_ptr<vk::Context> ctx;
  std::unique_ptr<shader::ShaderLibrary> lib;

  void SetUp() override {
    std::random_device rd;
    dir = fs::temp_directory_path() / ("wb_pass_test_" + std::to_string(rd()));
    fs::create_directories(dir);
    vk::ContextOptions o;
    o.validation = true;
    ctx = std::make_unique<vk::Context>(o);
    lib = std::make_unique<shader::ShaderLibrary>(
        shader::ShaderLibrary::Options{.includeRoots = {dir}, .cacheDir = {}, .printWarnings = false});
  }
  void TearDown() override {
    lib.reset();
    if (ctx) {
      EXPECT_EQ(ctx->validationErrors(), 0u);
      for (const auto& m : ctx->validationMessages()) ADD_FAILURE() << "validation: " << m;
    }
    ctx.reset();
    fs::remove_all(dir);
  }
  // A compute shader that writes `value` (+ a push constant when `push` is set) into the block `block`,
  // declared at binding `binding`.
  fs::path shader(const std::string& name, const std::string& block, int binding, uint32_t value,
                  bool push = false) {
    const fs::path p = dir / name;
    std::ofstream f(p);
    f << "#version 460\nlayout(local_size_x = 1) in;\n"
      << "layout(set = 0, binding = " << binding << ", std430) buffer " << block << " { uint v[]; };\n";
    if (push) f << "layout(push_constant) uniform Push { uint add; uint more[7]; } pc;\n";
    f << "void main() { v[0] = " << value << "u" << (push ? " + pc.add" : "") << "; }\n";
    return p;
  }
  uint32_t run(render::Pass& pass, const vk::Buffer& buffer, uint32_t push = 0) {
    std::memset(buffer.mapped(), 0, sizeof(uint32_t));
    ctx->submitAndWait([&](VkCommandBuffer cmd) {
      pass.bind(cmd);
      pass.push(cmd, push);
      pass.dispatch(cmd, 1, 1);
    });
    uint32_t v = 0;
    std::memcpy(&v, buffer.mapped(), sizeof v);
    return v;
  }
};

}  // namespace

TEST_F(PassFixture, ResourcesAreBoundByTheNameTheShaderDeclares) {
  vk::Buffer a(*ctx, 64, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, true);
  vk::Buffer b(*ctx, 64, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, true);
  render::Pass pass(*ctx, *lib, "test", render::ComputeRecipe{});
  pass.setPushConstantBytes(sizeof(uint32_t));
  pass.setBuffer("Out", a);
  pass.setBuffer("Other", b);
  // Binding 7: no number on the host side names it.
  pass.useProgram("test", {{shader("out.comp", "Out", 7, 41)}});
  pass.rebuild();
  EXPECT_EQ(run(pass, a), 41u);
  // The other block at binding 0 in another variant: the pass follows the name.
  ASSERT_TRUE(pass.useProgram("test other", {{shader("other.comp", "Other", 0, 42)}}));
  pass.rebuild();
  EXPECT_EQ(run(pass, b), 42u);
  // A resource set after the install is written into the installed pipeline's descriptors.
  vk::Buffer c(*ctx, 64, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, true);
  pass.setBuffer("Other", c);
  EXPECT_EQ(run(pass, c), 42u);
  EXPECT_EQ(pass.installs(), 2u);
}

TEST_F(PassFixture, AProgramUsingANameThePassDoesNotBindIsRefusedAtItsDeclaration) {
  vk::Buffer a(*ctx, 64, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, true);
  render::Pass pass(*ctx, *lib, "test", render::ComputeRecipe{});
  pass.setBuffer("Out", a);
  const fs::path file = shader("typo.comp", "Ouput", 0, 1);
  pass.useProgram("test", {{file}});
  try {
    pass.rebuild();
    FAIL() << "a program reading a resource the pass does not bind was built";
  } catch (const shader::CompileError& e) {
    ASSERT_EQ(e.diagnostics.size(), 1u) << e.what();
    EXPECT_EQ(fs::canonical(e.diagnostics[0].file), fs::canonical(file));
    EXPECT_EQ(e.diagnostics[0].line, 3) << "the line that declares the block";
    EXPECT_NE(e.diagnostics[0].message.find("'Ouput'"), std::string::npos) << e.what();
    EXPECT_NE(e.diagnostics[0].message.find("not bound by the test pass, which binds: Out"),
              std::string::npos)
        << e.what();
  }
  EXPECT_EQ(pass.installs(), 0u);
}

TEST_F(PassFixture, MorePushConstantsThanThePassPushesAreRefused) {
  vk::Buffer a(*ctx, 64, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, true);
  render::Pass pass(*ctx, *lib, "test", render::ComputeRecipe{});
  pass.setBuffer("Out", a);
  pass.setPushConstantBytes(sizeof(uint32_t));  // the shader's block is 32 bytes
  pass.useProgram("test", {{shader("push.comp", "Out", 0, 1, true)}});
  try {
    pass.rebuild();
    FAIL() << "a pipeline reading push constants past what the pass pushes was built";
  } catch (const shader::CompileError& e) {
    EXPECT_NE(std::string(e.what()).find("push constants of 32 bytes, but the test pass pushes 4"),
              std::string::npos)
        << e.what();
  }
  pass.setPushConstantBytes(32);
  pass.rebuild();
  struct {
    uint32_t add = 5;
    uint32_t more[7] = {};
  } push;
  std::memset(a.mapped(), 0, 4);
  ctx->submitAndWait([&](VkCommandBuffer cmd) {
    pass.bind(cmd);
    pass.push(cmd, push);
    pass.dispatch(cmd, 1, 1);
  });
  uint32_t v = 0;
  std::memcpy(&v, a.mapped(), 4);
  EXPECT_EQ(v, 6u);
}

TEST_F(PassFixture, APipelineOfAVariantThePassLeftIsDropped) {
  vk::Buffer a(*ctx, 64, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, true);
  render::Pass pass(*ctx, *lib, "test", render::ComputeRecipe{});
  pass.setBuffer("Out", a);
  pass.useProgram("one", {{shader("one.comp", "Out", 0, 1)}});
  pass.rebuild();
  const auto one = pass.program();
  auto built = pass.buildPipeline(one, lib->buildProgram(one));  // a reload built off the render thread
  pass.useProgram("two", {{shader("two.comp", "Out", 0, 2)}});
  pass.rebuild();
  EXPECT_FALSE(pass.install(built)) << "a pipeline of the variant left behind replaced the current one";
  EXPECT_EQ(run(pass, a), 2u);
  // Back to the first variant: its pipeline is accepted and hands back the one it replaced.
  pass.useProgram("one", {{dir / "one.comp"}});
  EXPECT_EQ(pass.program(), one) << "a variant is registered once";
  const auto replaced = pass.install(built);
  EXPECT_TRUE(replaced);
  EXPECT_EQ(run(pass, a), 1u);
}
