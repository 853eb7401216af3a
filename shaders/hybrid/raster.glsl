// Raster-only declarations of the G-buffer pass: per-draw push constants and the varyings. Editing this file
// rebuilds only the raster pipeline.
#ifndef WB_HYBRID_RASTER_GLSL
#define WB_HYBRID_RASTER_GLSL

layout(push_constant, scalar) uniform DrawBlock { HybridDrawConstants draw; };

#define VARYING_WORLD_POS 0
#define VARYING_NORMAL 1
#define VARYING_UV 2
#define VARYING_MATERIAL 3

#endif
