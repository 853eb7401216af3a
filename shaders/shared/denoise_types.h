// The denoiser's bindings and push constants (shaders/denoise/, src/render/denoiser.h), defined once for C++ and
// GLSL. Every denoiser pass has its own descriptor set 0 and declares only the images it reads and writes.
#ifndef WB_DENOISE_TYPES_H
#define WB_DENOISE_TYPES_H
#include "glsl_cpp.h"

#define WB_DENOISE_BIND_RADIANCE 0  // rgba32f: the path tracer's accumulation (a = samples in the pixel)
#define WB_DENOISE_BIND_ALBEDO 1    // rgba16f: first-hit albedo AOV (WB_BIND_AOV_ALBEDO)
#define WB_DENOISE_BIND_NORMAL 2    // rgba16f: first-hit normal AOV, a = first-hit distance (WB_BIND_AOV_NORMAL)
#define WB_DENOISE_BIND_STATS 3     // rgba32f: r = mean luminance^2 of the samples (WB_BIND_AOV_STATS)
#define WB_DENOISE_BIND_GUIDE 4     // rgba32f: octahedral normal xy, depth, depth change per pixel
#define WB_DENOISE_BIND_PING 5      // rgba32f: demodulated radiance rgb, a = variance of its luminance
#define WB_DENOISE_BIND_PONG 6      // rgba32f: the same, the other side of the ping-pong
#define WB_DENOISE_BIND_VARIANCE 7  // r32f: variance of the raw mean's demodulated luminance (hand-over)
#define WB_DENOISE_BIND_OUTPUT 8    // rgba32f: the denoised radiance (a = samples in the pixel, as the input)

WB_NAMESPACE_BEGIN

struct DenoisePush {
  uvec2 imageSize;
  uint step;              // a-trous: tap spacing in pixels (1, 2, 4, ...)
  uint source;            // 0: read ping, write pong; 1: read pong, write ping (final: where the result is)
  uint rows;              // rows [0, rows) hold the current accumulation; the rest is not read (the window's strips)
  float sigmaLuminance;   // luminance edge-stopping, in standard deviations of the mean; 0: off
  float sigmaNormal;      // exponent of the normals' cosine
  float sigmaDepth;       // depth edge-stopping, in multiples of the expected depth change
  float handoverTau;      // relative error assumed for the filtered image (hand-over to the raw one); < 0: none
  float pad0, pad1, pad2;
};

WB_NAMESPACE_END

#endif
