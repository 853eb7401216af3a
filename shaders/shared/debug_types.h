// What wbPrint and wbAssert record (shaders/shared/debug_print.h; the path tracer's buffers are declared in
// shaders/pathtracer/debug.glsl), defined once for C++ and GLSL. Layouts are std430/scalar-compatible.
#ifndef WB_DEBUG_TYPES_H
#define WB_DEBUG_TYPES_H
#include "glsl_cpp.h"

// wbPrint records kept per recorded sample of the inspected pixel (more are counted, not recorded).
#define WB_PRINTS_PER_SAMPLE 32u

// PrintRecord.type: how `bits` holds the value.
#define WB_PRINT_FLOAT 0u
#define WB_PRINT_INT 1u
#define WB_PRINT_UINT 2u
#define WB_PRINT_BOOL 3u

// The ray tracing stage that printed or asserted (PrintRecord.stage, AssertRecord.stage).
#define WB_STAGE_RAYGEN 0u
#define WB_STAGE_CLOSEST_HIT 1u
#define WB_STAGE_ANY_HIT 2u
#define WB_STAGE_MISS 3u
#define WB_STAGE_SHADOW_MISS 4u

// The bounce of a print or assert made before any ray of the sample was traced (raygen's camera ray setup).
#define WB_DEBUG_NO_BOUNCE 0xffffffffu

WB_NAMESPACE_BEGIN

// One wbPrint("label", value) at the inspected pixel, in the order the sample made them.
struct PrintRecord {
  uint label;       // the label's id (shader::debugLabelId: FNV-1a of its text)
  uint bounce;      // the path vertex being traced or shaded (WB_DEBUG_NO_BOUNCE: before the camera ray)
  uint stage;       // WB_STAGE_*
  uint type;        // WB_PRINT_*
  uint components;  // 1 .. 4
  uint pad0;
  uint pad1;
  uint pad2;
  uvec4 bits;       // the value's components, floatBitsToUint for floats
};

// The asserts variant's count of failures (every pixel, every sample since the host cleared it).
struct AssertHeader {
  uint failures;  // all failures seen (atomic); the first `capacity` are recorded
  uint capacity;  // AssertRecord slots
  uint pad0;
  uint pad1;
};

// One failed wbAssert(condition, "label").
struct AssertRecord {
  uvec2 pixel;
  uint sampleIndex;  // the accumulation's sample index
  uint bounce;  // WB_DEBUG_NO_BOUNCE: before the camera ray
  uint label;
  uint stage;   // WB_STAGE_*
  uint pad0;
  uint pad1;
};

WB_NAMESPACE_END

#endif
