// print and assert from any ray tracing stage (raygen, closest-hit, any-hit, miss):
//
//   wbPrint("label", value);        // float, int, uint, bool and their vec2..vec4
//   wbAssert(condition, "label");
//
// Both compile to nothing unless the pipeline's debug variant defines WB_DEBUG_PRINT / WB_DEBUG_ASSERTS to 1
// (the path tracer: its inspecting variant records prints at the inspected pixel, its asserts variant checks
// asserts at every pixel; shaders/pathtracer/debug.glsl), so a pipeline's default SPIR-V is the same with and
// without the calls: their arguments are never compiled there.
//
// Labels are string literals. GLSL has no strings: the shader library replaces each string literal of a
// shader's code (outside comments and preprocessor lines) by its 32-bit id before glslang sees it, and the
// host maps ids back to texts from the same sources (src/shader/debug_labels.h). A label is therefore written
// in the call itself, not through a macro or a variable.
//
// A pipeline that turns a variant on defines, before including this file, the function that records:
//   void wbDebugPrint(uint label, uint type, uint components, uvec4 bits);   (WB_DEBUG_PRINT)
//   void wbDebugAssertFailed(uint label);                                     (WB_DEBUG_ASSERTS)
#ifndef WB_DEBUG_PRINT_H
#define WB_DEBUG_PRINT_H
#include "debug_types.h"

#ifndef WB_DEBUG_PRINT
#define WB_DEBUG_PRINT 0
#endif
#ifndef WB_DEBUG_ASSERTS
#define WB_DEBUG_ASSERTS 0
#endif

#if WB_DEBUG_PRINT
#define wbPrint(label, value) wbPrint_(label, value)
void wbPrint_(uint label, float v) { wbDebugPrint(label, WB_PRINT_FLOAT, 1u, uvec4(floatBitsToUint(v), 0u, 0u, 0u)); }
void wbPrint_(uint label, vec2 v) { wbDebugPrint(label, WB_PRINT_FLOAT, 2u, uvec4(floatBitsToUint(v), 0u, 0u)); }
void wbPrint_(uint label, vec3 v) { wbDebugPrint(label, WB_PRINT_FLOAT, 3u, uvec4(floatBitsToUint(v), 0u)); }
void wbPrint_(uint label, vec4 v) { wbDebugPrint(label, WB_PRINT_FLOAT, 4u, floatBitsToUint(v)); }
void wbPrint_(uint label, int v) { wbDebugPrint(label, WB_PRINT_INT, 1u, uvec4(uint(v), 0u, 0u, 0u)); }
void wbPrint_(uint label, ivec2 v) { wbDebugPrint(label, WB_PRINT_INT, 2u, uvec4(uvec2(v), 0u, 0u)); }
void wbPrint_(uint label, ivec3 v) { wbDebugPrint(label, WB_PRINT_INT, 3u, uvec4(uvec3(v), 0u)); }
void wbPrint_(uint label, ivec4 v) { wbDebugPrint(label, WB_PRINT_INT, 4u, uvec4(v)); }
void wbPrint_(uint label, uint v) { wbDebugPrint(label, WB_PRINT_UINT, 1u, uvec4(v, 0u, 0u, 0u)); }
void wbPrint_(uint label, uvec2 v) { wbDebugPrint(label, WB_PRINT_UINT, 2u, uvec4(v, 0u, 0u)); }
void wbPrint_(uint label, uvec3 v) { wbDebugPrint(label, WB_PRINT_UINT, 3u, uvec4(v, 0u)); }
void wbPrint_(uint label, uvec4 v) { wbDebugPrint(label, WB_PRINT_UINT, 4u, v); }
void wbPrint_(uint label, bool v) { wbDebugPrint(label, WB_PRINT_BOOL, 1u, uvec4(v ? 1u : 0u, 0u, 0u, 0u)); }
void wbPrint_(uint label, bvec2 v) { wbDebugPrint(label, WB_PRINT_BOOL, 2u, uvec4(uvec2(v), 0u, 0u)); }
void wbPrint_(uint label, bvec3 v) { wbDebugPrint(label, WB_PRINT_BOOL, 3u, uvec4(uvec3(v), 0u)); }
void wbPrint_(uint label, bvec4 v) { wbDebugPrint(label, WB_PRINT_BOOL, 4u, uvec4(v)); }
#else
#define wbPrint(label, value)
#endif

#if WB_DEBUG_ASSERTS
#define wbAssert(condition, label) \
  do {                                   \
    if (!(condition)) wbDebugAssertFailed(label); \
  } while (false)
#else
#define wbAssert(condition, label)
#endif

#endif
