// The scene's emissive triangles in world space: the area lights of next-event estimation.
#pragma once
#include <vector>

#include "scene/scene.h"

namespace wb::scene {

float emitterLuminance(
    const gpu::Material& m);  // Rec.709 luminance of the emissive factor (textures not included)
// Every triangle of every instance whose material emits (luminance > 0) and whose world area is > 0.
std::vector<gpu::EmissiveTriangle> emissiveTriangles(const Scene& scene);
// Selection weights: luminance(emissive factor) * world area, the weights the emitter alias table samples.
std::vector<double> emitterWeights(const Scene& scene, const std::vector<gpu::EmissiveTriangle>& emitters);

}  // namespace wb::scene
