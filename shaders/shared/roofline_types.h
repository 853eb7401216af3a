// The bare-ray roofline (src/render/roofline.h): push constants of its one ray tracing pipeline, defined once for
// C++ and GLSL. It traces the path tracer's scene with trivial shaders: what the device's traversal alone costs.
#ifndef WB_ROOFLINE_TYPES_H
#define WB_ROOFLINE_TYPES_H
#include "glsl_cpp.h"

// What one launch traces (RooflineConstants::kind).
#define WB_ROOFLINE_PRIMARY 0u  // a camera ray per pixel (through its centre); writes the hit G-buffer
#define WB_ROOFLINE_DIFFUSE 1u  // a camera ray per pixel, then one cosine-distributed bounce from its hit
#define WB_ROOFLINE_SHADOW 2u   // from each G-buffer hit facing the light, one shadow ray (terminate on first hit)
#define WB_ROOFLINE_PATH 3u     // a camera ray, then per hit a shadow ray (facing the light) and a cosine bounce

WB_NAMESPACE_BEGIN

struct RooflineConstants {
  vec4 origin;      // camera position (w unused)
  vec4 corner;      // direction through the top-left corner of the image (not normalised; w unused)
  vec4 dx;          // direction change per pixel to the right (w unused)
  vec4 dy;          // direction change per pixel down (w unused)
  vec4 toLight;     // unit direction towards the light the shadow rays aim at (w unused)
  uvec2 imageSize;  // pixels
  uint kind;        // WB_ROOFLINE_*
  uint frame;       // varies the bounce directions from launch to launch
  uint bounces;     // WB_ROOFLINE_PATH: the bounces of a walk at most (the path tracer's maxBounces)
};

WB_NAMESPACE_END

#endif
