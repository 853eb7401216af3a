// The progressive path tracer pass: the ray tracing pipeline (raygen path loop, closest-hit shading, any-hit
// alpha, environment and shadow miss), its accumulation and AOV images, and hot-swappable pipelines.
#pragma once
#include <array>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "eval/cost_map.h"
#include "render/denoiser.h"
#include "render/renderer.h"
#include "scene/features.h"
#include "vk/pipeline_layout.h"
#include "vk/rt_pipeline.h"

namespace wb::render {

// The AOV images the path tracer keeps when settings.aov is on (see shared/bindings.h for their channels);
// Stats holds the heat maps' data (rgba32f); Cost the cost variant's clocks per sample (rgba32f).
enum class Aov { Albedo, Normal, Info, Stats, Cost };

// The path tracer's measuring and checking variants, each a define compiled in only while asked for (the
// default variant's SPIR-V has none of their code). Any combination, with the inspecting variant too.
struct Instrumentation {
  bool cost = false;     // WB_COST: the shader clock per sample (trace calls, shading) into the Cost AOV
  bool asserts = false;  // WB_ASSERTS: wbAssert checked at every pixel, the first failures recorded
  bool operator==(const Instrumentation&) const = default;
};

// The asserts variant's failures as read back: every failure counted, the first `capacity` recorded.
struct AssertReport {
  uint32_t failures = 0;
  std::vector<gpu::AssertRecord> records;  // min(failures, capacity), in the order they were seen
};

struct PixelRegion {
  uint32_t x = 0, y = 0, width = 0, height = 0;
};

// What the path inspector records (render/path_inspector.h reads it back): the paths of one pixel.
struct InspectRequest {
  uint32_t x = 0, y = 0;  // the pixel
  uint32_t samples = 16;  // sample records
  uint32_t vertices = 0;  // vertex records per sample; 0: max bounces + 1, at most kMaxInspectVertices
  bool ring = false;      // false: the first `samples` samples; true: every sample, the latest `samples` kept
  bool operator==(const InspectRequest&) const = default;
};
inline constexpr uint32_t kMaxInspectVertices = 256;
inline constexpr uint32_t kMaxInspectSamples = 1u << 16;

// The inspector's buffers as read back: header, then every sample slot and its vertex records.
struct InspectBuffers {
  gpu::InspectHeader header{};
  std::vector<gpu::InspectSample> samples;   // header.sampleCapacity slots
  std::vector<gpu::InspectVertex> vertices;  // header.vertexCapacity per slot
  std::vector<gpu::PrintRecord> prints;      // WB_PRINTS_PER_SAMPLE per slot (InspectSample.prints made)
};

class PathTracer final : public Renderer {
 public:
  PathTracer(const RendererResources& resources, const RenderSettings& settings,
             const scene::SceneFeatures& features = scene::genericFeatures());
  ~PathTracer() override;

  // Shader stages of the path tracer for a feature set: no any-hit stage when every material is opaque.
  // cpuDeviceCode defines WB_CPU_DEVICE=1: code shaped for a driver that JIT-compiles every inlined copy of a
  // function at the first trace (shaders/pathtracer/common.glsl).
  // inspect defines WB_INSPECT=1: the path inspector's variant; `instrumentation` WB_COST / WB_ASSERTS; both
  // measuring variants read the shader clock `clock` (WB_CLOCK_*: WB_CLOCK=N; none: left undefined), and with
  // isolateLanes (DevicePolicy::costIsolatesLanes) the cost variant traces each sample alone in its subgroup
  // (WB_COST_ISOLATE=1, isolatesLanes).
  static std::vector<shader::ShaderKey> stageKeys(const scene::SceneFeatures& features, bool cpuDeviceCode,
                                                  bool inspect = false,
                                                  const Instrumentation& instrumentation = {},
                                                  uint32_t clock = 0, bool isolateLanes = false);
  // The shader clock this device's cost variants read (WB_CLOCK_*): the subgroup clock where there is one,
  // else the device clock, else none (their costs read 0).
  static uint32_t clockOf(const vk::Context& ctx);
  // Whether a variant isolates its lanes where the policy asks for it: the cost variant alone, with a clock
  // (the inspecting and asserting variants read the pixel from the launch ID in every stage).
  static bool isolatesLanes(bool inspect, const Instrumentation& instrumentation, uint32_t clock,
                            bool isolateLanes);
  uint32_t clock() const { return clock_; }
  // Whether this tracer's variant traces each sample alone in its subgroup (WB_COST_ISOLATE, stageKeys).
  bool isolatesLanes() const {
    return isolatesLanes(inspectVariant_, instrumentation_, clock_, ctx_.policy().costIsolatesLanes);
  }
  // DevicePolicy::splitShadows: whether this tracer traces next-event estimation's shadow rays in a launch of
  // their own after the path rays' (shaders/pathtracer/shadow_split.rgen; with tiles, after each region's).
  // The plain variant splits, with AOVs too (the shadow launch accumulates the sample and its AOVs); the
  // inspecting, cost and asserts variants keep the one loop (their records are written along the path).
  bool splitsShadows() const { return split_; }
  // The path rays regrouped by shader execution reordering (DevicePolicy::invocationReorder).
  bool reordersInvocations() const { return reorder_; }
  // Whether the split's variant writes the AOVs (WB_SPLIT_AOVS): made where they are wanted, kept after.
  bool splitsAovs() const { return splitAovs_; }
  // Whether this tracer's shaders are shaped for a CPU device (DevicePolicy::cpuShapedShaderCode).
  bool cpuDeviceCode() const { return cpuDeviceCode_; }
  shader::ShaderLibrary::ProgramId program() const { return pass_->program(); }
  const scene::SceneFeatures& features() const { return features_; }
  // Switches to the variant for `features` (registering it once; compiled variants come from the cache) and
  // rebuilds the pipeline. Returns true when the program changed.
  bool setFeatures(const scene::SceneFeatures& features);

  // Path inspector: with a request the tracer switches to its WB_INSPECT variant (registered once, cached
  // like the scene variants; the images it renders are the same) and records the paths of the requested
  // pixel; nullopt switches back. Returns true when the program changed (its install restarts accumulation;
  // another pixel with the same variant goes on accumulating, its records starting with the next sample).
  bool setInspection(const std::optional<InspectRequest>& request);
  const std::optional<InspectRequest>& inspection() const { return inspection_; }
  // The records so far (reads host-visible memory: call when the traces that wrote them finished).
  InspectBuffers readInspection() const;

  // The cost and asserts variants (switching restarts accumulation; the asserts' records are cleared at
  // every restart). Returns true when the program changed.
  bool setInstrumentation(const Instrumentation& instrumentation);
  const Instrumentation& instrumentation() const { return instrumentation_; }
  // Failure records the asserts variant keeps (the buffer is remade: call between frames).
  void setAssertCapacity(uint32_t records);
  // The asserts variant's failures since the accumulation restarted (host-visible memory: call when the
  // traces finished).
  AssertReport readAsserts() const;
  // wbPrint / wbAssert labels by id, from the installed pipeline's sources (shader/debug_labels.h).
  std::map<uint32_t, std::string> debugLabels() const;

  // Renderer
  RenderMode mode() const override { return RenderMode::PathTrace; }
  vk::Context& context() const override { return ctx_; }
  void setSettings(const RenderSettings& settings) override;
  const RenderSettings& settings() const override { return settings_; }
  void setCamera(const CameraState& camera) override;
  void setEnvironment(const GpuEnvironment& env) override;
  void setLights(const std::vector<gpu::DirectionalLight>& lights) override;
  void resetAccumulation() override { sampleIndex_ = 0; }
  void record(VkCommandBuffer cmd) override;  // every tile of one sample (settings' tile size)
  void advance() override { ++sampleIndex_; }
  uint32_t recordBatch(VkCommandBuffer cmd, uint32_t samples) override;
  // Samples one launch traces for a whole-image sample: settings' samplesPerLaunch (default 1), or for 0 (the
  // device's choice) 1 on a device that compiles at the first dispatch (a CPU is full at any size) and enough
  // for ~2^20 invocations on a GPU (at most 16); always 1 with AOVs, the inspector, the cost or asserts
  // variant, or tiles.
  uint32_t samplesPerLaunch() const;
  void recordCompileOnly(VkCommandBuffer cmd) override;
  uint32_t samplesAccumulated() const override { return sampleIndex_; }
  const vk::Image& outputImage() const override { return accum_; }
  // The denoised image when settings().denoise, else the accumulation (waits for the device; alpha = 1). The
  // denoiser's run is timed as pass "denoise" (call with nothing recorded into the pass timer's round).
  eval::ImageRGBA readImage() const override;
  // The accumulation, never denoised: the estimator's image (alpha = 1).
  eval::ImageRGBA readEstimate() const override;
  // The path tracer's pass, then the denoiser's once it is made (settings().denoise made it).
  std::vector<Pass*> passes() const override;
  vk::GpuTimer* passTimer() const override { return timer_.get(); }
  std::unique_ptr<Renderer> makeLike(const RendererResources& resources,
                                     const RenderSettings& settings) const override;
  gpu::Counters readCounters() const override;
  void resetCounters() override;

  // Records one sample for `region` into cmd (the window traces a sample in strips over several frames);
  // call advance() once every region of the image got this sample.
  void recordRegion(VkCommandBuffer cmd, const PixelRegion& region) { recordRegion(cmd, region, 1); }
  // Traces `samples` samples of pixel (x, y) alone from scratch, each submitted and waited for (the path
  // inspector without an image): the pixel gets the samples a full render gives it, the rest of the image
  // stays as it was. Returns each sample's wall time in seconds.
  std::vector<double> renderPixel(uint32_t x, uint32_t y, uint32_t samples);

  double lastPipelineMs() const { return pass_->pipeline().rayTracing->createMs(); }
  // On GPUs with VK_KHR_pipeline_library (DevicePolicy::pipelineLibraries) pipelines are linked from
  // per-group libraries: an edit recompiles only the changed group. nullptr when monolithic.
  const vk::RtLibraryCache* libraryCache() const { return libraries_.get(); }
  bool pipelineLinked() const { return pass_->pipeline().rayTracing->linked(); }

  // The denoiser, made the first time settings().denoise is on (nullptr before); it filters the current
  // accumulation into denoiser()->output() when recorded.
  const Denoiser* denoiser() const { return denoiser_.get(); }
  Denoiser* denoiser() { return denoiser_.get(); }
  // Records the denoiser over the accumulation (rows [0, rows) hold the current samples; see Denoiser).
  void recordDenoise(VkCommandBuffer cmd, uint32_t rows = ~0u, vk::GpuTimer* perPass = nullptr) const;
  // Runs the denoiser over the accumulation, submitted and waited for (makes it if none is made); returns
  // its wall time in seconds. readDenoised() then reads its output (alpha = 1).
  double denoise();
  eval::ImageRGBA readDenoised() const;

  // Readbacks (they wait for the device).
  std::vector<float> readAccumulation() const;  // RGBA32F, alpha = samples accumulated in the pixel
  std::vector<float> readAov(Aov aov) const;    // RGBA, from the AOV images
  // The cost variant's summary of the image so far from its cost AOV (readAov(Aov::Cost)), read with the
  // accumulation and the stats AOV: each pixel by this device's estimate (DevicePolicy::costByMedian), in its
  // clock, and whether its lanes were isolated.
  eval::CostSummary summarizeCost(const std::vector<float>& costAov) const;
  const vk::Image& aovImage(Aov aov) const {
    return aov == Aov::Albedo   ? albedo_
           : aov == Aov::Normal ? normal_
           : aov == Aov::Info   ? info_
           : aov == Aov::Stats  ? stats_
                                : cost_;
  }
  const vk::Image& accumulationImage() const { return accum_; }
  // Accumulations set aside (images and finished samples) while another one renders, one per slot: the size
  // left (Tab), and the old pipeline's while an edit's comparison is pending. Park moves the current images
  // into the slot (cleared ones take their place, sample 0; what the slot held is dropped), unpark swaps the
  // slot's back at their size with their samples (false: none parked there), drop forgets them, move hands a
  // slot's accumulation to another slot.
  enum class ParkSlot { Size, Review };
  void parkAccumulation(ParkSlot slot, uint32_t samples);
  bool unparkAccumulation(ParkSlot slot);
  void dropParkedAccumulation(ParkSlot slot) { parked_[size_t(slot)].reset(); }
  bool hasParkedAccumulation(ParkSlot slot) const { return parked_[size_t(slot)].has_value(); }
  void moveParkedAccumulation(ParkSlot from, ParkSlot to);
  // Image sets allocated so far (one per new size: a size used before reuses its set).
  uint32_t imageSetsAllocated() const { return imageSetsAllocated_; }
  const vk::PipelineLayout& layout() const { return pass_->layout(); }

 private:
  // `samples` > 1: a launch of that depth over the whole image, then the resolve pass.
  void recordRegion(VkCommandBuffer cmd, const PixelRegion& region, uint32_t samples);
  void createImages();
  // Sets every resource the path tracer binds on its pass.
  void bindResources();
  void updateFrameUniforms();
  // Makes the program for (features, inspect, instrumentation_) current, registering it on first use;
  // rebuilds the pipeline.
  void useVariant(const scene::SceneFeatures& features, bool inspect);
  void createAssertBuffers(uint32_t records);
  void createInspectBuffers();
  // Makes the denoiser when settings_.denoise asks for it and none is made.
  void makeDenoiser();
  // Writes the lights as the shaders shade them (the sun angle of the settings applied) when they changed.
  void uploadLights();

  vk::Context& ctx_;
  shader::ShaderLibrary& library_;
  const GpuScene& gpuScene_;
  const GpuEnvironment* env_;
  RenderSettings settings_;
  CameraState camera_;
  scene::SceneFeatures features_;
  bool featuresSet_ = false;
  bool cpuDeviceCode_ = false;
  std::optional<InspectRequest> inspection_;
  bool inspectVariant_ = false;  // the current program is the WB_INSPECT build
  Instrumentation instrumentation_;
  uint32_t clock_ = 0;  // WB_CLOCK_* of the cost variants
  // Sample index of the last region recorded: a restart after sample 0 clears the inspector's sample slots.
  uint32_t lastRecordedSample_ = 0;
  uint64_t emitterVersion_ = 0;  // the scene's emitter buffers the pass points at
  // Before pass_: destroyed after the pipelines linked from it.
  std::unique_ptr<vk::RtLibraryCache> libraries_;
  std::unique_ptr<Pass> pass_;
  // The split's shadow launch (made where DevicePolicy::splitShadows, used while splitsShadows) and its
  // buffers (WB_BIND_SPLIT_*; 16 bytes while not split).
  bool split_ = false;
  bool reorder_ = false;  // the raygen variant with WB_INVOCATION_REORDER
  bool splitAovs_ = false;   // the split's variant writes AOVs (splitsAovs)
  uint32_t splitSlots_ = 0;  // shadow requests per sample the buffers hold (PushConstants::splitSlots)
  std::unique_ptr<Pass> shadowPass_;
  vk::Buffer splitRequests_, splitPaths_;
  bool splitWanted(bool inspect) const;
  // What the path and the shadow launch both read and write, bound by name (bindResources).
  void bindSharedResources(Pass& pass) const;
  void createSplitBuffers();
  std::unique_ptr<vk::GpuTimer> timer_;
  // Accumulates the samples of a launch of several (not in passes(): a fixed part of the accumulation).
  std::unique_ptr<Pass> resolve_;
  vk::Buffer sampleSlots_;  // WB_BIND_SAMPLE_SLOTS, sized for the largest launch so far
  std::unique_ptr<Denoiser> denoiser_;
  vk::Image accum_, albedo_, normal_, info_, stats_, cost_;
  // The image sets of the last sizes left (a preview's, the full one's): going back to a size reuses its
  // memory, already touched, instead of allocating and touching it anew (a CPU device pays for the first
  // touch in the first frame).
  struct ImageSet {
    vk::Image accum, albedo, normal, info, stats, cost;
  };
  // Moves the current images out (they are left empty), and a set in.
  ImageSet takeImages();
  void putImages(ImageSet&& set);
  std::vector<ImageSet> spareImages_;
  struct ParkedSet {
    ImageSet images;
    uint32_t samples = 0;
  };
  std::array<std::optional<ParkedSet>, 2> parked_;  // by ParkSlot
  uint32_t imageSetsAllocated_ = 0;
  vk::Buffer frameUniforms_, counters_, blueNoise_, sobol_;
  std::vector<gpu::DirectionalLight> lights_;  // the scene's lights, or the session's edits of them
  vk::Buffer lightBuffer_;                     // lights_ with settings_.sunAngleDeg (scene::withSunAngle)
  vk::Buffer inspectHeader_, inspectSamples_, inspectVertices_, inspectPrints_;
  vk::Buffer assertHeader_, assertRecords_;
  uint32_t sampleIndex_ = 0;
};

}  // namespace wb::render
