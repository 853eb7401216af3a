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
    std::vector<VkRayTracingShaderGroupCreateInfoKHR> groupInfos;
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
      groupInfos.push_back(gi);
    }
    if (libraries && ctx.pipelineLibrarySupported()) {
      // One library per group: its stages (re-indexed from 0) and the group. The interface covers every
      // stage.
      VkRayTracingPipelineInterfaceCreateInfoKHR iface{
          VK_STRUCTURE_TYPE_RAY_TRACING_PIPELINE_INTERFACE_CREATE_INFO_KHR};
      for (const auto& st : stages) {
        iface.maxPipelineRayPayloadSize =
            std::max(iface.maxPipelineRayPayloadSize, st->reflection.rayPayloadBytes);
        iface.maxPipelineRayHitAttributeSize =
            std::max(iface.maxPipelineRayHitAttributeSize, st->reflection.hitAttributeBytes);
      }
      iface.maxPipelineRayHitAttributeSize =
          std::min(std::max(iface.maxPipelineRayHitAttributeSize, 8u), ctx.rayTracing().maxHitAttributeSize);
      // The groups' libraries, each made on a thread of its own when the cache lacks it (a cold start or an
      // edit of a file several stages include compiles them side by side).
      struct GroupLibrary {
        std::vector<VkPipelineShaderStageCreateInfo> stages;
        VkRayTracingShaderGroupCreateInfoKHR group{};
      };
      std::vector<GroupLibrary> local(groups.size());
      for (size_t g = 0; g < groups.size(); ++g) {
        local[g].group = groupInfos[g];
        std::ostringstream key;
        key << "group "
            << (g == 0           ? "raygen"
                : g <= missCount ? "miss"
                                 : "hit")
            << " recursion " << maxRecursionDepth << " payload " << iface.maxPipelineRayPayloadSize
            << " attr " << iface.maxPipelineRayHitAttributeSize << " layout " << layoutId;
        for (const auto& c : constants) key << " spec " << c.id << '=' << c.value;
        for (uint32_t* slot : {&local[g].group.generalShader, &local[g].group.closestHitShader,
                               &local[g].group.anyHitShader, &local[g].group.intersectionShader}) {
          if (*slot == VK_SHADER_UNUSED_KHR) continue;
          const uint32_t stage = *slot;
          key << " stage " << stageInfos[stage].stage << ':' << std::hex
              << shader::hash64(stages[stage]->spirv.data(), stages[stage]->spirv.size() * sizeof(uint32_t))
              << std::dec;
          *slot = static_cast<uint32_t>(local[g].stages.size());
          local[g].stages.push_back(stageInfos[stage]);
        }
        libraryKeys_.push_back(key.str());
      }
      std::vector<VkPipeline> libs(groups.size(), VK_NULL_HANDLE);
      std::vector<double> compiledMs(groups.size(), -1.0);  // < 0: the cache had it
      auto makeLibrary = [&](size_t g) {
        libs[g] = libraries->get(libraryKeys_[g], [&] {
          const auto start = std::chrono::steady_clock::now();
          VkRayTracingPipelineCreateInfoKHR lci{VK_STRUCTURE_TYPE_RAY_TRACING_PIPELINE_CREATE_INFO_KHR};
          lci.flags = VK_PIPELINE_CREATE_LIBRARY_BIT_KHR;
          lci.stageCount = static_cast<uint32_t>(local[g].stages.size());
          lci.pStages = local[g].stages.data();
          lci.groupCount = 1;
          lci.pGroups = &local[g].group;
          lci.maxPipelineRayRecursionDepth = maxRecursionDepth;
          lci.pLibraryInterface = &iface;
          lci.layout = layout;
          VkPipeline lib = VK_NULL_HANDLE;
          // Not through a deferred operation: for these one- or two-stage libraries it gained nothing on an
          // H200 (docs/bench/h200_pipeline_creation.md); they compile side by side instead.
          WB_VK(ctx.vkCreateRayTracingPipelinesKHR(ctx.device(), VK_NULL_HANDLE, ctx.pipelineCache(), 1, &lci,
                                                   nullptr, &lib));
          compiledMs[g] =
              std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
          return lib;
        });
      };
      // Cached libraries come back at once; of the missing ones the first compiles on this thread, the others
      // on threads of their own (a closest-hit edit misses one: no thread is started).
      std::vector<size_t> missing;
      for (size_t g = 0; g < groups.size(); ++g) {
        if (libraries->contains(libraryKeys_[g])) {
          makeLibrary(g);
        } else {
          missing.push_back(g);
        }
      }
      std::vector<std::future<void>> making;
      for (size_t i = 1; i < missing.size(); ++i)
        making.push_back(std::async(std::launch::async, makeLibrary, missing[i]));
      std::exception_ptr failure;
      try {
        if (!missing.empty()) makeLibrary(missing[0]);
      } catch (...) {
        failure = std::current_exception();
      }
      for (auto& f : making) {
        try {
          f.get();
        } catch (...) {
          if (!failure) failure = std::current_exception();
        }
      }
      if (failure) std::rethrow_exception(failure);
      for (double ms : compiledMs) {
        if (ms < 0) {
          ++stats_.librariesReused;
        } else {
          ++stats_.librariesCompiled;
          stats_.libraryMs = std::max(stats_.libraryMs, ms);
        }
      }
      // Linked plainly too: through a deferred operation the H200's driver crashed at the first trace.
      const auto linkStart = std::chrono::steady_clock::now();
      VkPipelineLibraryCreateInfoKHR li{VK_STRUCTURE_TYPE_PIPELINE_LIBRARY_CREATE_INFO_KHR};
      li.libraryCount = static_cast<uint32_t>(libs.size());
      li.pLibraries = libs.data();
      VkRayTracingPipelineCreateInfoKHR ci{VK_STRUCTURE_TYPE_RAY_TRACING_PIPELINE_CREATE_INFO_KHR};
      ci.pLibraryInfo = &li;
      ci.pLibraryInterface = &iface;
      ci.maxPipelineRayRecursionDepth = maxRecursionDepth;
      ci.layout = layout;
      WB_VK(ctx.vkCreateRayTracingPipelinesKHR(ctx.device(), VK_NULL_HANDLE, ctx.pipelineCache(), 1, &ci,
                                               nullptr, &pipeline_));
      stats_.linkMs =
          std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - linkStart).count();
    } else {
      VkRayTracingPipelineCreateInfoKHR ci{VK_STRUCTURE_TYPE_RAY_TRACING_PIPELINE_CREATE_INFO_KHR};
      ci.stageCount = static_cast<uint32_t>(stageInfos.size());
      ci.pStages = stageInfos.data();
      ci.groupCount = static_cast<uint32_t>(groupInfos.size());
      ci.pGroups = groupInfos.data();
      ci.maxPipelineRayRecursionDepth = maxRecursionDepth;
      ci.layout = layout;
      WB_VK(runDeferred(ctx, [&](VkDeferredOperationKHR op) {
        return ctx.vkCreateRayTracingPipelinesKHR(ctx.device(), op, ctx.pipelineCache(), 1, &ci, nullptr,
                                                  &pipeline_);
      }));
    }
    const uint32_t hitCount = static_cast<uint32_t>(groups.size()) - 1 - missCount;
    sbt_ = ShaderBindingTable(ctx, pipeline_, missCount, hitCount);
  } catch (...) {
    if (pipeline_) vkDestroyPipeline(ctx.device(), pipeline_, nullptr);
    throw;
  }
  createMs_ = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

RayTracingPipeline::~RayTracingPipeline() {
  if (pipeline_) vkDestroyPipeline(ctx_.device(), pipeline_, nullptr);
}

}  // namespace wb::vk
