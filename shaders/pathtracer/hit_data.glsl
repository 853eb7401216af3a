// What a ray hit: its geometry record, and the hash behind stochastic transparency. Vertex fetch and material
// inputs are shaders/shared/scene.glsl's.
#ifndef WB_PT_HIT_DATA_GLSL
#define WB_PT_HIT_DATA_GLSL
#include "../shared/random.h"

GeometryInfo hitGeometry() { return geometries[gl_InstanceCustomIndexEXT + gl_GeometryIndexEXT]; }

// A hash of pixel, sample, primitive and geometry for stochastic transparency.
float alphaHash(uvec2 pixel, uint primitive, uint geometry) {
  uint h = hashCombine(pixel.x, pixel.y);
  h = hashCombine(h, WB_SAMPLE_INDEX ^ (pc.seed * 0x68bc21ebu));
  h = hashCombine(h, primitive);
  h = hashCombine(h, geometry);
  return uintToUnitFloat(h);
}

#endif
