// The path inspector's records, in the WB_INSPECT build only: the host compiles that variant while a pixel is
// inspected, and normal rendering never includes this file. Every stage writes what it alone knows about the
// inspected pixel's current sample (closest-hit: the vertex, its light samples and BRDF sample; the miss shader:
// the environment and its MIS weight, the suns' discs; raygen: throughput, Russian roulette, shadow visibility
// and the sample's total), each field by exactly one stage. The records are a side effect: no value of the path
// is changed.
#ifndef WB_PT_INSPECT_GLSL
#define WB_PT_INSPECT_GLSL
#include "../shared/inspect_types.h"

layout(set = 0, binding = WB_BIND_INSPECT_HEADER, scalar) readonly buffer InspectHeaderBlock {
  InspectHeader inspectHeader;
};
layout(set = 0, binding = WB_BIND_INSPECT_SAMPLES, scalar) buffer InspectSampleBlock {
  InspectSample inspectSamples[];
};
layout(set = 0, binding = WB_BIND_INSPECT_VERTICES, scalar) buffer InspectVertexBlock {
  InspectVertex inspectVertices[];
};

#define WB_INSPECT_NONE 0xffffffffu

// The record slot of the current sample, or WB_INSPECT_NONE when this invocation traces another pixel or a sample
// that is not recorded.
uint inspectSlot() {
  const uvec2 pixel = gl_LaunchIDEXT.xy + pc.tileOffset;
  if (pixel != inspectHeader.pixel || inspectHeader.sampleCapacity == 0u) return WB_INSPECT_NONE;
  if (inspectHeader.mode == WB_INSPECT_RING) return pc.sampleIndex % inspectHeader.sampleCapacity;
  if (pc.sampleIndex < inspectHeader.firstSample) return WB_INSPECT_NONE;
  const uint slot = pc.sampleIndex - inspectHeader.firstSample;
  return slot < inspectHeader.sampleCapacity ? slot : WB_INSPECT_NONE;
}

// The record of vertex `bounce` of the current sample, or WB_INSPECT_NONE (not recorded, or beyond capacity).
uint inspectVertex(uint bounce) {
  const uint slot = inspectSlot();
  if (slot == WB_INSPECT_NONE || bounce >= inspectHeader.vertexCapacity) return WB_INSPECT_NONE;
  return slot * inspectHeader.vertexCapacity + bounce;
}

uint inspectNonFinite(vec3 v, uint bit) { return any(isnan(v)) || any(isinf(v)) ? bit : 0u; }
uint inspectNonFinite(float v, uint bit) { return isnan(v) || isinf(v) ? bit : 0u; }

#endif
