#include "vk/rt_pipeline.h"

#include <algorithm>
#include <chrono>
#include <exception>
#include <future>
#include <sstream>

#include "shader/hash.h"
#include "vk/deferred.h"

namespace wb::vk {

RtLibraryCache::RtLibraryCache(Context& ctx) : ctx_(ctx) {}

RtLibraryCache::~RtLibraryCache() {
  for (auto& [key, e] : libraries_) vkDestroyPipeline(ctx_.device(), e.pipeline, nullptr);
}

VkPipeline RtLibraryCache::get(const std::string& key, const std::function<VkPipeline()>& create) {
  {
    std::lock_guard lock(mutex_);
    if (auto it = libraries_.find(key); it != libraries_.end()) {
      it->second.lastUse = ++clock_;
      return it->second.pipeline;
    }
  }
  VkPipeline lib = create();  // outside the lock: the driver's compile is the slow part
  std::lock_guard lock(mutex_);
  auto [it, inserted] = libraries_.emplace(key, Entry{lib, 0});
  if (!inserted) {
    vkDestroyPipeline(ctx_.device(), lib, nullptr);  // another thread made the same one meanwhile
  } else {
    ++created_;
  }
  it->second.lastUse = ++clock_;
  return it->second.pipeline;
}

void RtLibraryCache::trim(size_t maxLibraries, const std::vector<std::string>& inUse) {
  std::lock_guard lock(mutex_);
  while (libraries_.size() > maxLibraries) {
    auto oldest = libraries_.end();
    for (auto it = libraries_.begin(); it != libraries_.end(); ++it) {
      if (std::find(inUse.begin(), inUse.end(), it->first) != inUse.end()) continue;
      if (oldest == libraries_.end() || it->second.lastUse < oldest->second.lastUse) oldest = it;
    }
    if (oldest == libraries_.end()) return;
    vkDestroyPipeline(ctx_.device(), oldest->second.pipeline, nullptr);
    libraries_.erase(oldest);
  }
}

bool RtLibraryCache::contains(const std::string& key) const {
  std::lock_guard lock(mutex_);
  return libraries_.count(key) != 0;
}

size_t RtLibraryCache::size() const {
  std::lock_guard lock(mutex_);
  return libraries_.size();
}

std::string layoutKey(const shader::PipelineLayoutDesc& desc) {
  std::ostringstream k;
  for (const auto& b : desc.bindings) {
    k << b.set << ':' << b.binding << ':' << b.type << ':' << b.count << ':' << b.runtimeArray << ':'
      << b.stages << ';';
  }
  for (const auto& p : desc.pushConstants)
    k << "pc" << p.offset << ':' << p.size << ':' << p.stageFlags << ';';
  return k.str();
}

namespace {

double msSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

std::vector<VkRayTracingShaderGroupCreateInfoKHR> groupCreateInfos(const std::vector<RtShaderGroup>& groups) {
  std::vector<VkRayTracingShaderGroupCreateInfoKHR> infos;
  for (const auto& g : groups) {
    VkRayTracingShaderGroupCreateInfoKHR gi{VK_STRUCTURE_TYPE_RAY_TRACING_SHADER_GROUP_CREATE_INFO_KHR};
    gi.type = g.general >= 0        ? VK_RAY_TRACING_SHADER_GROUP_TYPE_GENERAL_KHR
              : g.intersection >= 0 ? VK_RAY_TRACING_SHADER_GROUP_TYPE_PROCEDURAL_HIT_GROUP_KHR
                                    : VK_RAY_TRACING_SHADER_GROUP_TYPE_TRIANGLES_HIT_GROUP_KHR;
    auto idx = [](int i) { return i >= 0 ? static_cast<uint32_t>(i) : VK_SHADER_UNUSED_KHR; };
    gi.generalShader = idx(g.general);
    gi.closestHitShader = idx(g.closestHit);
    gi.anyHitShader = idx(g.anyHit);
    gi.intersectionShader = idx(g.intersection);
    infos.push_back(gi);
  }
  return infos;
}

// Runs `work` for every item, the first on this thread and the others on threads of their own, and rethrows
// the first failure once all have finished.
void runSideBySide(const std::vector<size_t>& items, const std::function<void(size_t)>& work) {
  std::vector<std::future<void>> running;
  for (size_t i = 1; i < items.size(); ++i) running.push_back(std::async(std::launch::async, work, items[i]));
  std::exception_ptr failure;
  try {
    if (!items.empty()) work(items[0]);
  } catch (...) {
    failure = std::current_exception();
  }
  for (auto& f : running) {
    try {
      f.get();
    } catch (...) {
      if (!failure) failure = std::current_exception();
    }
  }
  if (failure) std::rethrow_exception(failure);
}

}  // namespace

// What both creation paths work from: the stages (their modules live in the constructor) and the groups.
struct RayTracingPipeline::Inputs {
  const std::vector<std::shared_ptr<const shader::CompiledShader>>& stages;
  const std::vector<VkPipelineShaderStageCreateInfo>& stageInfos;
  const std::vector<VkRayTracingShaderGroupCreateInfoKHR>& groupInfos;
  uint32_t missCount;
  VkPipelineLayout layout;
  uint32_t maxRecursionDepth;
  const std::vector<SpecializationConstant>& constants;
  const std::string& layoutId;
};

// One group's library: the stages it uses (re-indexed from 0) and the group.
struct RayTracingPipeline::GroupLibrary {
  std::vector<VkPipelineShaderStageCreateInfo> stages;
  VkRayTracingShaderGroupCreateInfoKHR group{};
};

RayTracingPipeline::RayTracingPipeline(
    Context& ctx, const std::vector<std::shared_ptr<const shader::CompiledShader>>& stages,
    const RtBindingTable& table, VkPipelineLayout layout, uint32_t maxRecursionDepth,
    const std::vector<SpecializationConstant>& constants, RtLibraryCache* libraries,
    const std::string& layoutId)
    : ctx_(ctx) {
  auto t0 = std::chrono::steady_clock::now();
  if (maxRecursionDepth > ctx.rayTracing().maxRecursionDepth) {
    throw VulkanError("ray recursion depth " + std::to_string(maxRecursionDepth) + " exceeds the device's " +
                      std::to_string(ctx.rayTracing().maxRecursionDepth));
  }
  const std::vector<RtShaderGroup> groups = table.resolve(stages);
  const uint32_t missCount = table.missCount();
  const Specialization spec(constants);
  std::vector<ShaderModule> modules;  // only needed while the pipeline is created
  std::vector<VkPipelineShaderStageCreateInfo> stageInfos;
  try {
    for (const auto& s : stages) {
      modules.emplace_back(ctx.device(), *s);
      stageInfos.push_back(modules.back().stageInfo(spec.info()));
    }
    const std::vector<VkRayTracingShaderGroupCreateInfoKHR> groupInfos = groupCreateInfos(groups);
    const Inputs in{stages, stageInfos,        groupInfos, missCount,
                    layout, maxRecursionDepth, constants,  layoutId};
    if (libraries && ctx.pipelineLibrarySupported()) {
      createLinked(in, *libraries);
    } else {
      createMonolithic(in);
    }
    const uint32_t hitCount = static_cast<uint32_t>(groups.size()) - 1 - missCount;
    sbt_ = ShaderBindingTable(ctx, pipeline_, missCount, hitCount);
  } catch (...) {
    if (pipeline_) vkDestroyPipeline(ctx.device(), pipeline_, nullptr);
    throw;
  }
  createMs_ = msSince(t0);
}

void RayTracingPipeline::createMonolithic(const Inputs& in) {
  VkRayTracingPipelineCreateInfoKHR ci{VK_STRUCTURE_TYPE_RAY_TRACING_PIPELINE_CREATE_INFO_KHR};
  ci.stageCount = static_cast<uint32_t>(in.stageInfos.size());
  ci.pStages = in.stageInfos.data();
  ci.groupCount = static_cast<uint32_t>(in.groupInfos.size());
  ci.pGroups = in.groupInfos.data();
  ci.maxPipelineRayRecursionDepth = in.maxRecursionDepth;
  ci.layout = in.layout;
  WB_VK(runDeferred(ctx_, [&](VkDeferredOperationKHR op) {
    return ctx_.vkCreateRayTracingPipelinesKHR(ctx_.device(), op, ctx_.pipelineCache(), 1, &ci, nullptr,
                                               &pipeline_);
  }));
}

void RayTracingPipeline::createLinked(const Inputs& in, RtLibraryCache& libraries) {
  const VkRayTracingPipelineInterfaceCreateInfoKHR iface = libraryInterface(in);
  const std::vector<GroupLibrary> local = groupLibraries(in, iface);
  const std::vector<VkPipeline> libs = makeLibraries(in, local, iface, libraries);
  linkLibraries(in, libs, iface);
}

VkRayTracingPipelineInterfaceCreateInfoKHR RayTracingPipeline::libraryInterface(const Inputs& in) const {
  // One interface for every library: it covers every stage.
  VkRayTracingPipelineInterfaceCreateInfoKHR iface{
      VK_STRUCTURE_TYPE_RAY_TRACING_PIPELINE_INTERFACE_CREATE_INFO_KHR};
  for (const auto& st : in.stages) {
    iface.maxPipelineRayPayloadSize =
        std::max(iface.maxPipelineRayPayloadSize, st->reflection.rayPayloadBytes);
    iface.maxPipelineRayHitAttributeSize =
        std::max(iface.maxPipelineRayHitAttributeSize, st->reflection.hitAttributeBytes);
  }
  iface.maxPipelineRayHitAttributeSize =
      std::min(std::max(iface.maxPipelineRayHitAttributeSize, 8u), ctx_.rayTracing().maxHitAttributeSize);
  return iface;
}

std::vector<RayTracingPipeline::GroupLibrary> RayTracingPipeline::groupLibraries(
    const Inputs& in, const VkRayTracingPipelineInterfaceCreateInfoKHR& iface) {
  // One library per group; its cache key names everything the library's compile depends on.
  std::vector<GroupLibrary> local(in.groupInfos.size());
  for (size_t g = 0; g < local.size(); ++g) {
    local[g].group = in.groupInfos[g];
    std::ostringstream key;
    key << "group "
        << (g == 0              ? "raygen"
            : g <= in.missCount ? "miss"
                                : "hit")
        << " recursion " << in.maxRecursionDepth << " payload " << iface.maxPipelineRayPayloadSize << " attr "
        << iface.maxPipelineRayHitAttributeSize << " layout " << in.layoutId;
    for (const auto& c : in.constants) key << " spec " << c.id << '=' << c.value;
    for (uint32_t* slot : {&local[g].group.generalShader, &local[g].group.closestHitShader,
                           &local[g].group.anyHitShader, &local[g].group.intersectionShader}) {
      if (*slot == VK_SHADER_UNUSED_KHR) continue;
      const uint32_t stage = *slot;
      const auto& spirv = in.stages[stage]->spirv;
      key << " stage " << in.stageInfos[stage].stage << ':' << std::hex
          << shader::hash64(spirv.data(), spirv.size() * sizeof(uint32_t)) << std::dec;
      *slot = static_cast<uint32_t>(local[g].stages.size());
      local[g].stages.push_back(in.stageInfos[stage]);
    }
    libraryKeys_.push_back(key.str());
  }
  return local;
}

std::vector<VkPipeline> RayTracingPipeline::makeLibraries(
    const Inputs& in, const std::vector<GroupLibrary>& local,
    const VkRayTracingPipelineInterfaceCreateInfoKHR& iface, RtLibraryCache& libraries) {
  std::vector<VkPipeline> libs(local.size(), VK_NULL_HANDLE);
  std::vector<double> compiledMs(local.size(), -1.0);  // < 0: the cache had it
  auto makeLibrary = [&](size_t g) {
    libs[g] = libraries.get(libraryKeys_[g], [&] {
      const auto start = std::chrono::steady_clock::now();
      VkPipeline lib = compileLibrary(in, local[g], iface);
      compiledMs[g] = msSince(start);
      return lib;
    });
  };
  // Cached libraries come back at once; the missing ones compile side by side (a cold start or an edit of a
  // file several stages include), and a single missing one (a closest-hit edit) starts no thread.
  std::vector<size_t> missing;
  for (size_t g = 0; g < local.size(); ++g) {
    if (libraries.contains(libraryKeys_[g])) {
      makeLibrary(g);
    } else {
      missing.push_back(g);
    }
  }
  runSideBySide(missing, makeLibrary);
  for (double ms : compiledMs) {
    if (ms < 0) {
      ++stats_.librariesReused;
    } else {
      ++stats_.librariesCompiled;
      stats_.libraryMs = std::max(stats_.libraryMs, ms);
    }
  }
  return libs;
}

VkPipeline RayTracingPipeline::compileLibrary(const Inputs& in, const GroupLibrary& library,
                                              const VkRayTracingPipelineInterfaceCreateInfoKHR& iface) const {
  VkRayTracingPipelineCreateInfoKHR lci{VK_STRUCTURE_TYPE_RAY_TRACING_PIPELINE_CREATE_INFO_KHR};
  lci.flags = VK_PIPELINE_CREATE_LIBRARY_BIT_KHR;
  lci.stageCount = static_cast<uint32_t>(library.stages.size());
  lci.pStages = library.stages.data();
  lci.groupCount = 1;
  lci.pGroups = &library.group;
  lci.maxPipelineRayRecursionDepth = in.maxRecursionDepth;
  lci.pLibraryInterface = &iface;
  lci.layout = in.layout;
  VkPipeline lib = VK_NULL_HANDLE;
  // Not through a deferred operation: a one- or two-stage library has no parallelism for one to use; the
  // libraries compile side by side instead (docs/bench/h200_pipeline_creation.md).
  WB_VK(ctx_.vkCreateRayTracingPipelinesKHR(ctx_.device(), VK_NULL_HANDLE, ctx_.pipelineCache(), 1, &lci,
                                            nullptr, &lib));
  return lib;
}

void RayTracingPipeline::linkLibraries(const Inputs& in, const std::vector<VkPipeline>& libs,
                                       const VkRayTracingPipelineInterfaceCreateInfoKHR& iface) {
  // Linked plainly too: NVIDIA's driver 580 crashes at the first trace of a pipeline linked through a
  // deferred operation (docs/bench/h200_pipeline_creation.md).
  const auto start = std::chrono::steady_clock::now();
  VkPipelineLibraryCreateInfoKHR li{VK_STRUCTURE_TYPE_PIPELINE_LIBRARY_CREATE_INFO_KHR};
  li.libraryCount = static_cast<uint32_t>(libs.size());
  li.pLibraries = libs.data();
  VkRayTracingPipelineCreateInfoKHR ci{VK_STRUCTURE_TYPE_RAY_TRACING_PIPELINE_CREATE_INFO_KHR};
  ci.pLibraryInfo = &li;
  ci.pLibraryInterface = &iface;
  ci.maxPipelineRayRecursionDepth = in.maxRecursionDepth;
  ci.layout = in.layout;
  WB_VK(ctx_.vkCreateRayTracingPipelinesKHR(ctx_.device(), VK_NULL_HANDLE, ctx_.pipelineCache(), 1, &ci,
                                            nullptr, &pipeline_));
  stats_.linkMs = msSince(start);
}

RayTracingPipeline::~RayTracingPipeline() {
  if (pipeline_) vkDestroyPipeline(ctx_.device(), pipeline_, nullptr);
}

}  // namespace wb::vk
