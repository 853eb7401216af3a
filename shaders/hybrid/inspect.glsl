// The hybrid modes' inspector: the shadow/AO and reflection raygens record the rays of one pixel
// (frame.inspectX/Y; HybridInspectRecord in shared/hybrid_types.h). Every other pixel pays one comparison.
#ifndef WB_HYBRID_INSPECT_GLSL
#define WB_HYBRID_INSPECT_GLSL

layout(set = 0, binding = WB_BIND_HYBRID_INSPECT, scalar) buffer HybridInspectBlock {
  HybridInspectRecord inspectRecord;
};

bool hybridInspected(ivec2 p) { return uint(p.x) == frame.inspectX && uint(p.y) == frame.inspectY; }

#endif
