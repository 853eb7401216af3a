// Every struct and binding number that crosses the host/shader boundary, defined once for C++ and GLSL, by
// concept: bindings.h (descriptor bindings), scene_types.h (the scene: vertices, materials, lights, emitters),
// pathtracer_types.h, inspect_types.h (the path inspector), debug_types.h (wbPrint, wbAssert), hybrid_types.h,
// roofline_types.h (the bare-ray roofline). Shaders include the ones they use.
#ifndef WB_GPU_TYPES_H
#define WB_GPU_TYPES_H
#include "bindings.h"
#include "scene_types.h"
#include "pathtracer_types.h"
#include "inspect_types.h"
#include "debug_types.h"
#include "hybrid_types.h"
#include "roofline_types.h"
#endif
