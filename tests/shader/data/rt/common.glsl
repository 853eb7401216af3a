// Shared declarations of the test ray tracing program.
#ifndef RT_COMMON_GLSL
#define RT_COMMON_GLSL

struct Payload {
  vec3 color;
  uint depth;
};

layout(set = 0, binding = 0) uniform accelerationStructureEXT tlas;
layout(set = 0, binding = 1, rgba32f) uniform image2D accum;
layout(set = 0, binding = 2) uniform Frame {
  mat4 viewInverse;
  mat4 projInverse;
  vec4 envColor;
} frame;
layout(set = 0, binding = 3, std430) readonly buffer Materials { vec4 baseColor[]; } materials;
layout(set = 0, binding = 4, std430) buffer Counters { uint rays; } counters;
layout(set = 0, binding = 5) uniform sampler2D textures[];
layout(push_constant) uniform Push {
  uint sampleIndex;
  uint flags;
} pc;

#endif
