// The display pass's push constants and view modes, shared by the C++ host and the display shaders.
#ifndef WB_DISPLAY_TYPES_H
#define WB_DISPLAY_TYPES_H
#include "../shared/glsl_cpp.h"

// Descriptor set 0 bindings of the display pipeline (all read-only storage images in GENERAL layout).
#define WB_DISPLAY_BIND_ACCUM 0    // rgba32f path tracer accumulation
#define WB_DISPLAY_BIND_ALBEDO 1   // rgba16f AOV: albedo, a = dropped NaN/Inf fraction
#define WB_DISPLAY_BIND_NORMAL 2   // rgba16f AOV: shading normal, a = first-hit distance (-1 = miss)
#define WB_DISPLAY_BIND_INFO 3     // rgba16f AOV: geometric normal, a = path vertices
#define WB_DISPLAY_BIND_PREVIEW 4  // rgba32f low-resolution preview shown under rows not yet traced
#define WB_DISPLAY_BIND_STATS 5    // rgba32f AOV: the heat maps' data (WB_BIND_AOV_STATS in shared/bindings.h)
#define WB_DISPLAY_BIND_DENOISED 6  // rgba32f the denoised radiance (the accumulation when not denoising)
#define WB_DISPLAY_BIND_COST 7      // rgba32f AOV: clocks per sample (WB_BIND_AOV_COST, the cost variant's)

// What the display shows (the Inspect panel's debug view). Switching never resets accumulation.
#define WB_VIEW_BEAUTY 0u
#define WB_VIEW_ALBEDO 1u
#define WB_VIEW_SHADING_NORMAL 2u
#define WB_VIEW_GEOMETRIC_NORMAL 3u
#define WB_VIEW_DEPTH 4u
#define WB_VIEW_BOUNCES 5u     // heat map: path length (rays per path, full scale max bounces + 1)
#define WB_VIEW_DROPPED 6u
#define WB_VIEW_RR_END 7u      // heat map: mean bounce where Russian roulette ended paths; dark where it ended none
#define WB_VIEW_VARIANCE 8u    // heat map: relative standard deviation of one sample (fireflies are red)
#define WB_VIEW_NAN_SOURCE 9u  // heat map: lowest bounce where a sample became NaN/Inf; elsewhere the dimmed image
#define WB_VIEW_COST 10u       // heat map: shader clocks per sample (the cost variant), full scale costFull
#define WB_VIEW_INEFFICIENCY 11u  // heat map: relative variance x clocks per sample, full scale inefficiencyFull
#define WB_VIEW_COUNT 12u

// Tonemappers, in the order of eval::Tonemap.
#define WB_TONEMAP_CLAMP 0u
#define WB_TONEMAP_REINHARD 1u
#define WB_TONEMAP_ACES 2u

WB_NAMESPACE_BEGIN

struct DisplayPush {
  vec4 viewRect;       // the image's rectangle in framebuffer pixels: x, y, width, height
  uvec2 imageSize;     // accumulation size
  uvec2 previewSize;   // preview size (0 = no preview)
  float exposureScale;  // 2^exposure stops
  uint tonemap;
  uint view;
  uint encodeSrgb;     // 1 when the swapchain format is UNORM (the shader writes sRGB itself)
  uint tracedRows;     // rows [0, tracedRows) hold the current sample; the rest show the preview
  float sceneScale;    // scene bounding radius (depth view)
  float maxVertices;   // bounce heat map full scale (max bounces + 1)
  float costFull;      // cost view: clocks per sample at the top of the ramp (0: no cost data, the dimmed image)
  float inefficiencyFull;  // inefficiency view: relative variance x clocks at the top of the ramp
  uint costMedian;     // 1: a pixel's cost is its running median (the cost AOV's a), 0: its mean (r)
  float denoiseSplit;  // < 0: the accumulation only; else the denoised image right of this fraction of the view
};

WB_NAMESPACE_END

#endif
