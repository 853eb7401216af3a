// The scene's emissive triangles in world space: the area lights of next-event estimation.
#pragma once
#include <vector>

#include "scene/scene.h"

namespace wb::scene {

float emitterLuminance(
    const gpu::Material& m);  // Rec.709 luminance of the emissive factor (textures not included)
// Every triangle of every instance whose material emits (finite luminance > 0) and whose world area is > 0,
// with the scene's materials or with live-edited ones (same indices).
std::vector<gpu::EmissiveTriangle> emissiveTriangles(const Scene& scene);
std::vector<gpu::EmissiveTriangle> emissiveTriangles(const Scene& scene,
                                                     const std::vector<gpu::Material>& materials);
// Selection weights: luminance(emissive factor) * world area, the weights the emitter alias table samples.
std::vector<double> emitterWeights(const Scene& scene, const std::vector<gpu::EmissiveTriangle>& emitters);
std::vector<double> emitterWeights(const std::vector<gpu::Material>& materials,
                                   const std::vector<gpu::EmissiveTriangle>& emitters);

}  // namespace wb::scene
