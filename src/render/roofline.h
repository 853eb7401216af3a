// The bare-ray roofline: the path tracer's scene and acceleration structure (GpuScene's TLAS) traced by a
// small pipeline of its own with trivial shaders (shaders/roofline): camera rays, camera rays with one
// diffuse bounce, and shadow rays. Their rates, at the path tracer's size in the same process, are what
// traversal alone reaches on the device: the bound the path tracer's ray rate is measured against (`bench`,
// pathtracer section).
#pragma once
#include <cstdint>
#include <memory>
#include <vector>

#include "render/renderer.h"

namespace wb::render {

enum class BareRays {
  Primary,  // a camera ray per pixel, through its centre
  Diffuse,  // a camera ray per pixel and one cosine-distributed bounce from each hit
  Shadow,   // a shadow ray towards the scene's first directional light from each camera-ray hit facing it
            // (terminate on first hit, no closest-hit shader; straight up when the scene has no such light)
  Path,  // bare paths: a camera ray, then at each hit a shadow ray as above and a cosine-distributed bounce,
         // until a ray escapes or after `bounces` bounces: the path tracer's mix of rays, trivially shaded
};
const char* bareRaysName(BareRays kind);  // "primary" | "diffuse" | "shadow" | "path"

class Roofline {
 public:
  // Traces the camera rays once (the G-buffer the shadow rays leave from) and counts what each kind traces
  // (the bare paths, of at most `bounces` bounces, on one launch: their length varies from launch to launch
  // by the noise of a mean over every pixel).
  Roofline(const RendererResources& resources, uint32_t width, uint32_t height, const CameraState& camera,
           uint32_t bounces);
  ~Roofline();
  Roofline(const Roofline&) = delete;
  Roofline& operator=(const Roofline&) = delete;

  // Rays one launch of `kind` traces.
  uint64_t raysPerLaunch(BareRays kind) const;
  // Camera rays that hit the scene, and those of them facing the light (the shadow rays' origins).
  uint64_t hits() const { return hits_; }
  uint64_t litHits() const { return litHits_; }
  // Records `launches` launches of `kind`, a barrier after each.
  void record(VkCommandBuffer cmd, BareRays kind, uint32_t launches);
  Pass& pass() { return *pass_; }
  // Read back (they wait for the device), RGBA per pixel: the G-buffer (xyz the camera ray's hit, w 1 for a
  // hit, 0 for a miss) and what the last launch found (x; shadow: 1 light visible, 0 occluded or not traced;
  // diffuse: the bounce's hit distance, -1 escaped, or -1 when the camera ray missed; path: the rays traced,
  // and y the shadow rays that reached the light).
  std::vector<float> readHits() const { return readFloatImage(hitImage_); }
  std::vector<float> readResult() const { return readFloatImage(result_); }

 private:
  vk::Context& ctx_;
  uint32_t width_, height_;
  std::unique_ptr<Pass> pass_;
  vk::Image hitImage_, normals_, result_;
  gpu::RooflineConstants constants_{};
  uint64_t hits_ = 0, litHits_ = 0, pathRays_ = 0;
  uint32_t frame_ = 0;
};

}  // namespace wb::render
