// A pass: one pipeline and everything it is made from and bound to. It owns its program (stage keys and
// defines, registered with the ShaderLibrary; a pass may switch between variants), the recipe that turns a
// program build into a pipeline (ray tracing, graphics or compute), the reflected layout, descriptor sets
// whose resources are bound by the names the shaders declare, and push constants. Renderers are made of
// passes; the live-edit loop (src/live) reloads passes: it builds a pipeline off the render thread
// (buildPipeline) and installs it at a frame boundary (install).
#pragma once
#include <atomic>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <variant>
#include <vector>
#include <vulkan/vulkan.h>

#include "shader/library.h"
#include "vk/built_pipeline.h"
#include "vk/context.h"
#include "vk/pipeline_layout.h"
#include "vk/resources.h"
#include "vk/rt_binding_table.h"

namespace wb::render {

// How a program becomes a pipeline.
struct RayTracingRecipe {
  vk::RtBindingTable table;
  uint32_t maxRecursion = 1;
  std::vector<vk::SpecializationConstant> constants;
  // Link from per-group pipeline libraries kept here (DevicePolicy::pipelineLibraries); null: monolithic.
  vk::RtLibraryCache* libraries = nullptr;
};
struct GraphicsRecipe {
  vk::GraphicsPipelineDesc desc;
  std::vector<vk::SpecializationConstant> constants;
};
struct ComputeRecipe {
  std::vector<vk::SpecializationConstant> constants;
};
using PipelineRecipe = std::variant<RayTracingRecipe, GraphicsRecipe, ComputeRecipe>;

// A pipeline built for a pass from one build of its program.
struct PassPipeline {
  shader::ShaderLibrary::ProgramId program = 0;
  shader::ShaderLibrary::ProgramBuild build;
  std::shared_ptr<vk::BuiltPipeline> pipeline;
  explicit operator bool() const { return pipeline != nullptr; }
};

// What the live-edit loop sees of a pass: its program, a pipeline built from a build of it (any thread) and
// installed (render thread). render::Pass is the one implementation outside tests.
class ReloadTarget {
 public:
  using ProgramId = shader::ShaderLibrary::ProgramId;
  using ProgramBuild = shader::ShaderLibrary::ProgramBuild;
  virtual ~ReloadTarget() = default;
  virtual const std::string& name() const = 0;
  // The program in use (any thread: a pass may switch to another variant on the render thread).
  virtual ProgramId program() const = 0;
  // Any thread. Throws what compilation and pipeline creation throw.
  virtual PassPipeline buildPipeline(ProgramId program, const ProgramBuild& build) const = 0;
  // Render thread, at a frame boundary: installs `pipeline` and returns the one it replaced. A pipeline of
  // another program (a variant the pass has switched away from) is dropped: returns an empty one.
  virtual PassPipeline install(PassPipeline pipeline) = 0;
  // The installed pipeline and its build (any thread).
  virtual PassPipeline installed() const = 0;
};

class Pass final : public ReloadTarget {
 public:
  Pass(vk::Context& ctx, shader::ShaderLibrary& library, std::string name, PipelineRecipe recipe);
  ~Pass() override;
  Pass(const Pass&) = delete;
  Pass& operator=(const Pass&) = delete;

  vk::Context& context() const { return ctx_; }

  // The program: `stages` registered with the library under `programName` on first use (each variant's keys
  // once). Returns true when the program changed; rebuild() then makes its pipeline.
  bool useProgram(const std::string& programName, const std::vector<shader::ShaderKey>& stages);
  // A new recipe (a specialisation constant changed); rebuild() then makes a pipeline with it.
  void setRecipe(PipelineRecipe recipe);
  // The bytes of push constants the pass pushes (record's push()): a program declaring more is refused.
  void setPushConstantBytes(uint32_t bytes) { pushBytes_ = bytes; }
  // Compiles the program (cached), builds its pipeline and installs it, on the calling thread.
  void rebuild();
  // Called after every install (the owner restarts its accumulation: the image is the new pipeline's).
  void setOnInstall(std::function<void()> onInstall) { onInstall_ = std::move(onInstall); }

  // Resources, by the name the shaders declare them under: a block's name for buffers ("FrameBlock"), the
  // variable's for images, samplers and acceleration structures ("accumImage", "tlas"). Written into the
  // current descriptor sets at once (call it when no submitted work uses them) and into every later
  // pipeline's. A program may use only resources the pass sets (buildPipeline refuses others).
  void setBuffer(const std::string& name, VkBuffer buffer);
  void setBuffer(const std::string& name, const vk::Buffer& buffer) { setBuffer(name, buffer.handle()); }
  void setStorageImage(const std::string& name, VkImageView view);
  void setSampledImages(const std::string& name, std::vector<VkDescriptorImageInfo> images);
  void setAccelerationStructure(const std::string& name, VkAccelerationStructureKHR as);

  // ReloadTarget. buildPipeline throws shader::CompileError at the declaration of each resource the pass does
  // not set (or sets to another kind of descriptor), and for more push constants than the pass pushes.
  // install() waits for the device and writes new descriptor sets.
  const std::string& name() const override { return name_; }
  ProgramId program() const override { return program_; }
  PassPipeline buildPipeline(ProgramId program, const ProgramBuild& build) const override;
  PassPipeline install(PassPipeline pipeline) override;
  PassPipeline installed() const override;

  // Render thread.
  const vk::BuiltPipeline& pipeline() const { return *current_.pipeline; }
  const vk::PipelineLayout& layout() const { return *current_.pipeline->layout; }
  // Pipelines installed since construction (the first build counts).
  uint32_t installs() const { return installs_; }

  // Recording: bind() binds the pipeline and its descriptor sets; push() the reflected push-constant ranges
  // out of `constants`; then a ray tracing pass traces, a compute pass dispatches, a graphics pass draws.
  void bind(VkCommandBuffer cmd) const;
  template <class T>
  void push(VkCommandBuffer cmd, const T& constants) const {
    pushRaw(cmd, &constants, sizeof(T));
  }
  void traceRays(VkCommandBuffer cmd, uint32_t width, uint32_t height, uint32_t depth = 1) const;
  void dispatch(VkCommandBuffer cmd, uint32_t x, uint32_t y, uint32_t z = 1) const;

 private:
  struct Resource {
    vk::DescriptorKind kind = vk::DescriptorKind::Buffer;
    VkBuffer buffer = VK_NULL_HANDLE;
    VkImageView view = VK_NULL_HANDLE;
    std::vector<VkDescriptorImageInfo> images;
    VkAccelerationStructureKHR as = VK_NULL_HANDLE;
  };
  void setResource(const std::string& name, Resource resource);
  void write(const shader::DescriptorBinding& binding, const Resource& resource);
  void writeAll();
  // Throws CompileError for each binding of `build` no resource of the pass fills.
  void requireBound(const ProgramBuild& build) const;
  void pushRaw(VkCommandBuffer cmd, const void* data, size_t bytes) const;

  vk::Context& ctx_;
  shader::ShaderLibrary& library_;
  std::string name_;
  mutable std::mutex mutex_;  // recipe_, resources_ and current_ (read on the live loop's thread)
  PipelineRecipe recipe_;
  std::map<std::string, Resource> resources_;
  uint32_t pushBytes_ = 0;
  std::atomic<ProgramId> program_{0};
  bool hasProgram_ = false;
  std::vector<std::pair<std::vector<shader::ShaderKey>, ProgramId>> variants_;
  PassPipeline current_;  // written on the render thread under mutex_
  std::unique_ptr<vk::DescriptorSets> sets_;
  uint32_t installs_ = 0;
  std::function<void()> onInstall_;
};

}  // namespace wb::render
