// The path tracer's side of wbPrint and wbAssert (shaders/shared/debug_print.h), in its debug variants only:
// the inspecting variant (WB_INSPECT) records prints at the inspected pixel, into the sample's record slot
// (inspect.glsl), in the order the sample makes them; the asserts variant (WB_ASSERTS) checks asserts at every
// pixel and records the first failures. Each stage says which one it is (WB_STAGE before including
// common.glsl) and where in the path it is (wbDebugAtBounce: raygen before each trace, the hit and miss
// shaders from the payload); without a debug variant all of it is nothing.
#ifndef WB_PT_DEBUG_GLSL
#define WB_PT_DEBUG_GLSL

#ifndef WB_ASSERTS
#define WB_ASSERTS 0
#endif
#define WB_DEBUG_PRINT WB_INSPECT
#define WB_DEBUG_ASSERTS WB_ASSERTS
#include "../shared/debug_types.h"

#if WB_DEBUG_PRINT || WB_DEBUG_ASSERTS
// The vertex the invocation traces or shades (private to the invocation, like every global).
uint wbDebugBounce = WB_DEBUG_NO_BOUNCE;
#define wbDebugAtBounce(b) wbDebugBounce = (b)
#ifndef WB_STAGE
#define WB_STAGE WB_STAGE_RAYGEN
#endif
#else
#define wbDebugAtBounce(b)
#endif

#if WB_DEBUG_PRINT
layout(set = 0, binding = WB_BIND_INSPECT_PRINTS, scalar) buffer InspectPrintBlock { PrintRecord inspectPrints[]; };

void wbDebugPrint(uint label, uint type, uint components, uvec4 bits) {
  const uint slot = inspectSlot();
  if (slot == WB_INSPECT_NONE) return;
  // One invocation traces the inspected pixel's sample (every stage runs inside its raygen): no atomics.
  const uint n = inspectSamples[slot].prints;
  inspectSamples[slot].prints = n + 1u;
  if (n >= WB_PRINTS_PER_SAMPLE) return;
  PrintRecord r;
  r.label = label;
  r.bounce = wbDebugBounce;
  r.stage = WB_STAGE;
  r.type = type;
  r.components = components;
  r.pad0 = 0u;
  r.pad1 = 0u;
  r.pad2 = 0u;
  r.bits = bits;
  inspectPrints[slot * WB_PRINTS_PER_SAMPLE + n] = r;
}
#endif

#if WB_DEBUG_ASSERTS
layout(set = 0, binding = WB_BIND_ASSERT_HEADER, scalar) buffer AssertHeaderBlock { AssertHeader assertHeader; };
layout(set = 0, binding = WB_BIND_ASSERT_RECORDS, scalar) buffer AssertRecordBlock { AssertRecord assertRecords[]; };

void wbDebugAssertFailed(uint label) {
  const uint n = atomicAdd(assertHeader.failures, 1u);
  if (n >= assertHeader.capacity) return;
  AssertRecord r;
  r.pixel = gl_LaunchIDEXT.xy + pc.tileOffset;
  r.sampleIndex = WB_SAMPLE_INDEX;
  r.bounce = wbDebugBounce;
  r.label = label;
  r.stage = WB_STAGE;
  r.pad0 = 0u;
  r.pad1 = 0u;
  assertRecords[n] = r;
}
#endif

#include "../shared/debug_print.h"

#endif
