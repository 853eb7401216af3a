// The denoiser's bindings and push constants (shaders/denoise/, src/render/denoiser.h), defined once for C++ and
// GLSL. Every denoiser pass has its own descriptor set 0 and declares only the images it reads and writes: the
// path tracer's come in as storage images. The denoiser's own intermediates are buffers reached by device address
// (DenoiseBuffers, in the push constants), indexed y * width + x (imageSize.x), each plane width * height
// elements long: a CPU driver loads from a storage buffer one word of one lane at a time behind a bounds check,
// from an address without it, and the a-trous taps' loads are most of the denoiser's time there.
#ifndef WB_DENOISE_TYPES_H
#define WB_DENOISE_TYPES_H
#include "glsl_cpp.h"

#define WB_DENOISE_BIND_RADIANCE 0  // rgba32f: the path tracer's accumulation (a = samples in the pixel)
#define WB_DENOISE_BIND_ALBEDO 1    // rgba16f: first-hit albedo AOV (WB_BIND_AOV_ALBEDO)
#define WB_DENOISE_BIND_NORMAL 2    // rgba16f: first-hit normal AOV, a = first-hit distance (WB_BIND_AOV_NORMAL)
#define WB_DENOISE_BIND_STATS 3     // rgba32f: r = mean luminance^2 of the samples (WB_BIND_AOV_STATS)
#define WB_DENOISE_BIND_OUTPUT 4    // rgba32f: the denoised radiance (a = samples in the pixel, as the input)

// The a-trous kernel over taps -1, 0, 1 (`step` pixels apart): 1/4, 1/2, 1/4. SVGF's B3 spline (5 taps) costs
// three times the weights per iteration for no gain the converge reports show
// (docs/bench/lavapipe_denoise_speed.md).
#define WB_DENOISE_KERNEL_CENTER 0.5
#define WB_DENOISE_KERNEL_SIDE 0.25

// A tap of the variance pass's 3x3 neighbourhood counts as on the pixel's surface where its geometry weight
// (normals and depths, common.glsl) is above this. A neighbour on the same plane weighs down to about exp(-1) by
// its depth (the change the depth gradient predicts is the weight's unit), and a 0.5 cut it off on slanted
// surfaces: their pixels estimated their variance from a few neighbours, far too small where most samples are
// black, and kept their raw value (the dark specks of a denoised image at 1-4 spp).
#define WB_DENOISE_SAME_SURFACE 0.1

// The side of every denoiser pass's workgroup in pixels; the windowed gain (gain.comp) works per group of
// final.comp.
#define WB_DENOISE_GROUP_SIZE 8

// The window over which the output's radiance is made the raw image's (gain.comp): this many groups either side
// (2: 40x40 pixels).
#define WB_DENOISE_WINDOW_GROUPS 2

// Below this many samples a pixel's variance also takes its neighbourhood's spread (variance.comp).
#define WB_DENOISE_SHORT_HISTORY 4.0

WB_NAMESPACE_BEGIN

// The device addresses of the denoiser's buffers (low word, high word; common.glsl names them).
struct DenoiseBuffers {
  uvec2 geometry;  // vec4 per pixel: first-hit unit normal, depth (< 0: a miss)
  uvec2 filtered;  // vec4 per pixel, two planes (the passes' ping-pong, DenoisePush::source): demodulated
                   // radiance rgb, a = variance of its luminance
  uvec2 gradient;  // float per pixel: how much the depth changes per pixel there
  uvec2 handover;  // vec4 per pixel: the raw mean's demodulated luminance, its variance, the samples in the pixel
  uvec2 bias;      // float per pixel: (filtered - raw)^2 less the raw mean's variance, in the demodulated luminance
                   // (the last a-trous iteration's, for final.comp)
  uvec2 tiles;     // 2 vec4 per 8x8 group of final.comp: its raw and its output radiance summed (rgb)
  uvec2 gain;      // vec4 per 8x8 group: raw over output radiance in its window (rgb)
};

struct DenoisePush {
  uvec2 imageSize;
  uint step;              // a-trous: tap spacing in pixels (1, 2, 4, ...); gain: the phase (0, 1)
  uint source;            // the filter plane read (0 or 1); the other one is written (final: where the result is)
  uint rows;              // rows [0, rows) hold the current accumulation; the rest is not read (the window's strips)
  float sigmaLuminance;   // luminance edge-stopping, in standard deviations of the mean; 0: off
  float sigmaNormal;      // exponent of the normals' cosine
  float sigmaDepth;       // depth edge-stopping, in multiples of the expected depth change
  float handoverTau;      // relative error assumed for the filtered image (hand-over to the raw one); < 0: none
  uint last;              // a-trous: 1 in the last iteration (it also writes the bias buffer)
  uint window;            // 1: the output's radiance made the raw image's over windows (gain.comp, scale.comp)
  float pad2;
  DenoiseBuffers buffers;
};

WB_NAMESPACE_END

#endif
