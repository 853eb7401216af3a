#include "render/pass.h"

#include <algorithm>
#include <filesystem>

namespace wb::render {

Pass::Pass(vk::Context& ctx, shader::ShaderLibrary& library, std::string name, PipelineRecipe recipe)
    : ctx_(ctx), library_(library), name_(std::move(name)), recipe_(std::move(recipe)) {}

Pass::~Pass() {
  if (current_ || sets_) ctx_.waitIdle();  // the descriptor sets and pipeline may be in flight
  sets_.reset();
  current_ = {};
}

bool Pass::useProgram(const std::string& programName, const std::vector<shader::ShaderKey>& stages) {
  auto it =
      std::find_if(variants_.begin(), variants_.end(), [&](const auto& v) { return v.first == stages; });
  ProgramId id = 0;
  if (it != variants_.end()) {
    id = it->second;
  } else {
    id = library_.registerProgram(programName, stages);
    variants_.emplace_back(stages, id);
  }
  const bool changed = !hasProgram_ || id != program_;
  program_ = id;
  hasProgram_ = true;
  return changed;
}

void Pass::setRecipe(PipelineRecipe recipe) {
  std::lock_guard lock(mutex_);
  recipe_ = std::move(recipe);
}

void Pass::rebuild() {
  const ProgramId id = program_;
  install(buildPipeline(id, library_.buildProgram(id)));
}

void Pass::setResource(const std::string& name, Resource resource) {
  {
    std::lock_guard lock(mutex_);
    resources_[name] = resource;
  }
  if (!sets_) return;
  for (const auto& b : current_.pipeline->layout->desc().bindings)
    if (b.name == name && vk::fills(resource.kind, b.type)) write(b, resource);
}

void Pass::setBuffer(const std::string& name, VkBuffer buffer) {
  Resource r;
  r.kind = vk::DescriptorKind::Buffer;
  r.buffer = buffer;
  setResource(name, r);
}

void Pass::setStorageImage(const std::string& name, VkImageView view) {
  Resource r;
  r.kind = vk::DescriptorKind::StorageImage;
  r.view = view;
  setResource(name, r);
}

void Pass::setSampledImages(const std::string& name, std::vector<VkDescriptorImageInfo> images) {
  Resource r;
  r.kind = vk::DescriptorKind::SampledImages;
  r.images = std::move(images);
  setResource(name, r);
}

void Pass::setAccelerationStructure(const std::string& name, VkAccelerationStructureKHR as) {
  Resource r;
  r.kind = vk::DescriptorKind::AccelerationStructure;
  r.as = as;
  setResource(name, r);
}

void Pass::write(const shader::DescriptorBinding& b, const Resource& r) {
  // A resource set to null is named but not there yet (the display before its first image): not written.
  switch (r.kind) {
    case vk::DescriptorKind::Buffer:
      if (r.buffer) sets_->writeBuffer(b.set, b.binding, r.buffer);
      break;
    case vk::DescriptorKind::StorageImage:
      if (r.view) sets_->writeStorageImage(b.set, b.binding, r.view);
      break;
    case vk::DescriptorKind::SampledImages:
      sets_->writeSampledImages(b.set, b.binding, r.images);
      break;
    case vk::DescriptorKind::AccelerationStructure:
      if (r.as) sets_->writeAccelerationStructure(b.set, b.binding, r.as);
      break;
  }
}

void Pass::writeAll() {
  std::lock_guard lock(mutex_);
  for (const auto& b : current_.pipeline->layout->desc().bindings) {
    auto it = resources_.find(b.name);
    if (it != resources_.end() && vk::fills(it->second.kind, b.type)) write(b, it->second);
  }
}

void Pass::requireBound(const ProgramBuild& build) const {
  std::vector<shader::Diagnostic> errors;
  std::string names;  // what the pass binds, for the message
  std::map<std::string, vk::DescriptorKind> kinds;
  {
    std::lock_guard lock(mutex_);
    for (const auto& [name, r] : resources_) {
      kinds[name] = r.kind;
      names += (names.empty() ? "" : ", ") + name;
    }
  }
  auto fail = [&](const shader::DescriptorBinding& b, const std::string& message) {
    // Every stage that uses the binding: the declaration in that stage's files.
    bool located = false;
    for (const auto& stage : build.stages) {
      if (!stage || !(shader::toVkStage(stage->stage) & b.stages)) continue;
      for (const auto& r : stage->reflection.bindings) {
        if (r.set != b.set || r.binding != b.binding) continue;
        const auto where = shader::findDeclaration(*stage, r);
        const shader::Diagnostic d{where.first, where.second, "error", message};
        if (std::find(errors.begin(), errors.end(), d) == errors.end()) errors.push_back(d);
        located = true;
      }
    }
    if (!located) errors.push_back({std::filesystem::path(), 0, "error", message});
  };
  for (const auto& b : build.layout.bindings) {
    const auto it = kinds.find(b.name);
    if (it != kinds.end() && vk::fills(it->second, b.type)) continue;
    std::string message = "set " + std::to_string(b.set) + " binding " + std::to_string(b.binding) + " (" +
                          shader::descriptorTypeName(b.type) + " '" + b.name + "', " +
                          shader::stageFlagsToString(b.stages) + ") ";
    message += it != kinds.end() ? "is bound by the " + name_ + " pass to " +
                                       vk::descriptorKindName(it->second) + ", not to this type"
                                 : "is not bound by the " + name_ + " pass, which binds: " + names;
    fail(b, message);
  }
  for (const auto& range : build.layout.pushConstants) {
    if (range.offset + range.size <= pushBytes_) continue;
    const std::string message = "push constants of " + std::to_string(range.offset + range.size) +
                                " bytes, but the " + name_ + " pass pushes " + std::to_string(pushBytes_);
    bool located = false;
    for (const auto& stage : build.stages) {
      if (stage && !stage->reflection.pushConstants.empty()) {
        errors.push_back({stage->key.path, 0, "error", message});
        located = true;
        break;
      }
    }
    if (!located) errors.push_back({std::filesystem::path(), 0, "error", message});
  }
  if (!errors.empty()) throw shader::CompileError(std::move(errors));
}

PassPipeline Pass::buildPipeline(ProgramId program, const ProgramBuild& build) const {
  // A resource the pass does not bind would be read unbound (VUID-vkCmdTraceRaysKHR-None-02699): a compile
  // error at its declaration instead, and the last good pipeline stays.
  requireBound(build);
  PipelineRecipe recipe;
  {
    std::lock_guard lock(mutex_);
    recipe = recipe_;
  }
  auto p = std::make_shared<vk::BuiltPipeline>();
  p->layout = std::make_unique<vk::PipelineLayout>(ctx_, build.layout);
  if (const auto* rt = std::get_if<RayTracingRecipe>(&recipe)) {
    p->rayTracing = std::make_unique<vk::RayTracingPipeline>(
        ctx_, build.stages, rt->table, p->layout->handle(), rt->maxRecursion, rt->constants, rt->libraries,
        vk::layoutKey(build.layout));
  } else if (const auto* g = std::get_if<GraphicsRecipe>(&recipe)) {
    p->graphics = std::make_unique<vk::GraphicsPipeline>(ctx_, build.stages, g->desc, p->layout->handle(),
                                                         g->constants);
  } else {
    const auto& c = std::get<ComputeRecipe>(recipe);
    if (build.stages.size() != 1) throw std::invalid_argument(name_ + ": a compute pass takes one stage");
    p->compute =
        std::make_unique<vk::ComputePipeline>(ctx_, *build.stages.front(), p->layout->handle(), c.constants);
  }
  return {program, build, std::move(p)};
}

PassPipeline Pass::install(PassPipeline pipeline) {
  if (!hasProgram_ || pipeline.program != program_ || !pipeline) return {};
  ctx_.waitIdle();  // the old pipeline and descriptor sets may still be in flight
  sets_.reset();
  {
    std::lock_guard lock(mutex_);
    std::swap(current_, pipeline);
  }
  sets_ = std::make_unique<vk::DescriptorSets>(ctx_, *current_.pipeline->layout);
  writeAll();
  ++installs_;
  if (onInstall_) onInstall_();
  if (current_.pipeline->rayTracing) {
    std::lock_guard lock(mutex_);
    // Libraries of the last few builds stay (variants and an edit in flight); older ones go.
    if (const auto* rt = std::get_if<RayTracingRecipe>(&recipe_); rt && rt->libraries)
      rt->libraries->trim(24, current_.pipeline->rayTracing->libraryKeys());
  }
  return pipeline;
}

PassPipeline Pass::installed() const {
  std::lock_guard lock(mutex_);
  return current_;
}

void Pass::bind(VkCommandBuffer cmd) const {
  const vk::BuiltPipeline& p = *current_.pipeline;
  vkCmdBindPipeline(cmd, p.bindPoint(), p.handle());
  const auto& sets = sets_->sets();
  if (!sets.empty()) {
    vkCmdBindDescriptorSets(cmd, p.bindPoint(), p.layout->handle(), 0, static_cast<uint32_t>(sets.size()),
                            sets.data(), 0, nullptr);
  }
}

void Pass::pushRaw(VkCommandBuffer cmd, const void* data, size_t bytes) const {
  const auto& layout = *current_.pipeline->layout;
  for (const auto& range : layout.desc().pushConstants) {
    if (range.offset + range.size > bytes) continue;  // refused at build (requireBound)
    vkCmdPushConstants(cmd, layout.handle(), range.stageFlags, range.offset, range.size,
                       static_cast<const char*>(data) + range.offset);
  }
}

void Pass::traceRays(VkCommandBuffer cmd, uint32_t width, uint32_t height, uint32_t depth) const {
  current_.pipeline->rayTracing->sbt().trace(ctx_, cmd, width, height, depth);
}

void Pass::dispatch(VkCommandBuffer cmd, uint32_t x, uint32_t y, uint32_t z) const {
  vkCmdDispatch(cmd, x, y, z);
}

}  // namespace wb::render
