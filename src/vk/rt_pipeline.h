// A ray tracing pipeline from compiled stages and shader groups, with its shader binding table.
#pragma once
#include <atomic>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <vector>
#include <vulkan/vulkan.h>

#include "shader/types.h"
#include "vk/rt_binding_table.h"
#include "vk/sbt.h"
#include "vk/shader_module.h"

namespace wb::vk {

// Pipeline libraries (VK_KHR_pipeline_library), one per shader group, kept across rebuilds: a pipeline linked
// from them recompiles only the groups whose SPIR-V, specialisation, layout or interface changed, so an edit
// of the closest-hit shader compiles one library and links. Thread-safe (hot reload builds on a worker
// thread).
class RtLibraryCache {
 public:
  explicit RtLibraryCache(Context& ctx);
  ~RtLibraryCache();
  RtLibraryCache(const RtLibraryCache&) = delete;
  RtLibraryCache& operator=(const RtLibraryCache&) = delete;

  // The library for `key`, made by `create` when there is none yet.
  VkPipeline get(const std::string& key, const std::function<VkPipeline()>& create);
  // Destroys the least recently used libraries beyond `maxLibraries`, never one in `inUse` (a library must
  // outlive the pipelines linked from it; the most recent builds' stay, so a prepared but not yet committed
  // pipeline keeps its libraries).
  void trim(size_t maxLibraries, const std::vector<std::string>& inUse);
  bool contains(const std::string& key) const;
  uint64_t librariesCreated() const { return created_; }
  size_t size() const;

 private:
  Context& ctx_;
  mutable std::mutex mutex_;
  struct Entry {
    VkPipeline pipeline = VK_NULL_HANDLE;
    uint64_t lastUse = 0;
  };
  std::map<std::string, Entry> libraries_;
  uint64_t clock_ = 0;
  std::atomic<uint64_t> created_{0};
};

// A key that identifies a reflected pipeline layout's contents (libraries need a compatible layout).
std::string layoutKey(const shader::PipelineLayoutDesc& desc);

// What building a linked pipeline took (all zero for a monolithic one).
struct RtLibraryStats {
  uint32_t librariesCompiled = 0;  // groups whose library the cache lacked
  uint32_t librariesReused = 0;    // groups whose library came from the cache
  double libraryMs = 0;            // the slowest library compile (they compile side by side)
  double linkMs = 0;               // linking the libraries into the pipeline
};

class RayTracingPipeline {
 public:
  // The groups come from `table`, resolved against `stages`. With a library cache (and a device with
  // VK_KHR_pipeline_library) the pipeline is linked from per-group libraries; `layoutId` must then identify
  // the layout's contents (layoutKey()).
  RayTracingPipeline(Context& ctx, const std::vector<std::shared_ptr<const shader::CompiledShader>>& stages,
                     const RtBindingTable& table, VkPipelineLayout layout, uint32_t maxRecursionDepth,
                     const std::vector<SpecializationConstant>& constants = {},
                     RtLibraryCache* libraries = nullptr, const std::string& layoutId = {});
  // The libraries this pipeline was linked from (their cache keys); empty when monolithic.
  const std::vector<std::string>& libraryKeys() const { return libraryKeys_; }
  bool linked() const { return !libraryKeys_.empty(); }
  ~RayTracingPipeline();
  RayTracingPipeline(const RayTracingPipeline&) = delete;
  RayTracingPipeline& operator=(const RayTracingPipeline&) = delete;

  VkPipeline handle() const { return pipeline_; }
  const ShaderBindingTable& sbt() const { return sbt_; }
  double createMs() const { return createMs_; }
  const RtLibraryStats& libraryStats() const { return stats_; }

 private:
  Context& ctx_;
  VkPipeline pipeline_ = VK_NULL_HANDLE;
  ShaderBindingTable sbt_;
  double createMs_ = 0;
  RtLibraryStats stats_;
  std::vector<std::string> libraryKeys_;

  struct Inputs;        // what both creation paths work from
  struct GroupLibrary;  // one shader group's stages, re-indexed for a library of its own
  // One pipeline from every stage and group, created through a deferred operation.
  void createMonolithic(const Inputs& in);
  // A pipeline linked from per-group libraries, taken from `libraries` or compiled into it.
  void createLinked(const Inputs& in, RtLibraryCache& libraries);
  VkRayTracingPipelineInterfaceCreateInfoKHR libraryInterface(const Inputs& in) const;
  // Each group's library, with its cache key appended to libraryKeys_.
  std::vector<GroupLibrary> groupLibraries(const Inputs& in,
                                           const VkRayTracingPipelineInterfaceCreateInfoKHR& iface);
  // The groups' libraries from the cache, compiling those it lacks; records stats_.
  std::vector<VkPipeline> makeLibraries(const Inputs& in, const std::vector<GroupLibrary>& local,
                                        const VkRayTracingPipelineInterfaceCreateInfoKHR& iface,
                                        RtLibraryCache& libraries);
  VkPipeline compileLibrary(const Inputs& in, const GroupLibrary& library,
                            const VkRayTracingPipelineInterfaceCreateInfoKHR& iface) const;
  void linkLibraries(const Inputs& in, const std::vector<VkPipeline>& libs,
                     const VkRayTracingPipelineInterfaceCreateInfoKHR& iface);
};

}  // namespace wb::vk
