// The parameters of the path tracer's two fast, biased counterparts (the hybrid modes).
#pragma once
#include <cstdint>

namespace wb::render {

struct HybridSettings {
  float aoRadius = 0.0f;         // world units; 0 = 15% of the camera-to-target distance
  uint32_t aoRays = 2;           // per pixel and frame; 0 disables ambient occlusion
  bool temporal = true;          // average shadow and AO over frames while the camera is still
  uint32_t reflectionDepth = 2;  // reflection bounces (specialisation constant of the reflection raygen)
  float reflectionMaxRoughness = 0.3f;  // surfaces smoother than this get traced reflections ...
  float reflectionMinMetallic = 0.5f;   // ... when at least this metallic (0: smooth dielectrics too)
};

}  // namespace wb::render
