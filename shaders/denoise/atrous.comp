#version 460
#extension GL_GOOGLE_include_directive : require
// One a-trous iteration (SVGF's spatial filter): a 5x5 B3-spline kernel with taps `step` pixels apart, each
// tap weighted by how alike its surface is (normal, depth) and its demodulated luminance (a Gaussian of the
// difference in standard deviations of the pixel's mean: where the mean is precise, only taps as bright as it
// count, so the filter's reach shrinks as samples accumulate). The variance is carried along as the filtered
// mean's (sum of squared weights), which the next iteration reads. Reads one filter plane, writes the other.
// Each invocation filters a block of 2 x 2 pixels on the step's lattice (WB_DENOISE_ATROUS_BLOCK), each pixel
// as if alone, from a tile of the taps they share, loaded once.
#include "common.glsl"

layout(std430, set = 0, binding = WB_DENOISE_BIND_GEOMETRY) readonly buffer DenoiseGeometryBlock {
  vec4 geometry[];
};
layout(std430, set = 0, binding = WB_DENOISE_BIND_FILTER) buffer DenoiseFilterBlock { vec4 filtered[]; };
layout(std430, set = 0, binding = WB_DENOISE_BIND_GRADIENT) readonly buffer DenoiseGradientBlock {
  float gradient[];
};

// The tile: the block's pixels and the taps around them, loaded once; index ty * kTile + tx holds the pixel
// at tap offset (tx - 2, ty - 2) from the block's first pixel. Every index into the tile is a constant once
// the small loading loops are unrolled and the functions inlined (filterBlock calls filterPixel for each pixel
// of the block, which adds its taps one by one: a loop over the taps is too large for the compiler to
// unroll), so the tile lives in registers, not in memory.
#if WB_DENOISE_ATROUS_BLOCK != 2
#error "filterBlock filters a block of 2 x 2 pixels"
#endif
const int kTile = WB_DENOISE_ATROUS_BLOCK + 4;
vec4 color[kTile * kTile], guide[kTile * kTile];
float lum[kTile * kTile], tapVariance[kTile * kTile];  // per tile pixel: luminance(color.rgb), max(color.a, 0)

struct Accumulator {
  vec3 sum;
  float weights, variance;
};

// What the taps of one pixel share: its guide, luminance, 2 sigma^2 V (reach), and the depth change expected
// over each of the kernel's five tap distances (1, sqrt 2, 2, sqrt 5, sqrt 8). (Divisions, not products with
// reciprocals: a tiny divisor must not make 0 * inf.)
struct Center {
  vec4 geometry;
  float lum, reach;
  float expected[5];
};

// Adds the tap at offset (x, y) in steps (not the pixel itself) of the pixel at tile index t (q: its
// coordinates) to a. The weight is computed without branches (selects), as a CPU driver would run every lane
// through both sides of a branch anyway.
void addTap(inout Accumulator a, int t, ivec2 q, int x, int y, Center p, const bool squaring) {
  const int k = t + y * kTile + x;
  const vec4 geometryQ = guide[k];
  // The geometry's and the luminance's weights in one exponential. A tap off the image does not count, nor a
  // miss for a hit or a hit for a miss.
  const bool missP = p.geometry.w < 0.0, missQ = geometryQ.w < 0.0;
  const int r2 = x * x + y * y;  // the tap's squared distance: 1, 2, 4, 5 or 8
  const int distance = r2 == 1 ? 0 : r2 == 2 ? 1 : r2 == 4 ? 2 : r2 == 5 ? 3 : 4;
  const float normal = normalWeight(p.geometry.xyz, geometryQ.xyz, squaring);
  const float depth = abs(p.geometry.w - geometryQ.w) / p.expected[distance];
  const bool hits = !missP && !missQ;
  float w = kernelWeight(x) * kernelWeight(y) * (hits ? normal : 1.0);
  float exponent = hits ? depth : 0.0;
  const float difference = lum[k] - p.lum;
  const float luminanceExponent =
      p.reach > 0.0 ? difference * difference / p.reach : (difference == 0.0 ? 0.0 : 1.0e30);
  exponent += pc.sigmaLuminance > 0.0 ? luminanceExponent : 0.0;
  w *= exp(-exponent);
  if (insideImage(q) && missP == missQ) {
    a.sum += w * color[k].rgb;
    a.weights += w;
    a.variance += w * w * tapVariance[k];
  }
}

// Filters the pixel at (bx, by) of the block whose first pixel is `origin` from the tile into the plane
// starting at `destination`. `squaring`: see normalWeight.
void filterPixel(ivec2 origin, int bx, int by, uint destination, const bool squaring) {
  const int step = int(pc.step);
  const ivec2 p = origin + ivec2(bx, by) * step;
  if (!insideImage(p)) return;
  const uint i = pixelIndex(p);
  const int t = (by + 2) * kTile + bx + 2;
  const vec4 center = color[t];
  Center c;
  c.geometry = guide[t];
  c.lum = lum[t];
  // 2 sigma^2 V: a tap sigmaLuminance standard deviations away weighs exp(-1/2).
  c.reach = 2.0 * pc.sigmaLuminance * pc.sigmaLuminance * max(center.a, 0.0);
  const float distances[5] = float[5](1.0, sqrt(2.0), 2.0, sqrt(5.0), sqrt(8.0));
  const float gradientP = gradient[i];
  for (int d = 0; d < 5; ++d)
    c.expected[d] = pc.sigmaDepth * gradientP * (float(step) * distances[d]) + 1.0e-3 * c.geometry.w;
  Accumulator a;
  a.sum = center.rgb * (0.375 * 0.375);
  a.weights = 0.375 * 0.375;
  a.variance = center.a * (0.375 * 0.375) * (0.375 * 0.375);
  // The taps in rows, as a loop over y and x would take them.
#define WB_TAP(x, y) addTap(a, t, p + ivec2(x, y) * step, x, y, c, squaring)
#define WB_ROW(y) WB_TAP(-2, y); WB_TAP(-1, y); WB_TAP(0, y); WB_TAP(1, y); WB_TAP(2, y)
  WB_ROW(-2);
  WB_ROW(-1);
  WB_TAP(-2, 0);
  WB_TAP(-1, 0);
  WB_TAP(1, 0);
  WB_TAP(2, 0);
  WB_ROW(1);
  WB_ROW(2);
#undef WB_ROW
#undef WB_TAP
  filtered[destination + i] = vec4(a.sum / a.weights, a.variance / (a.weights * a.weights));
}

// Loads the tile of the block whose first pixel is `origin` from the plane starting at `source` (a tap off
// the image loads an edge pixel, which no weight uses) and filters the block's pixels.
void filterBlock(ivec2 origin, uint source, uint destination, const bool squaring) {
  const int step = int(pc.step);
  const ivec2 last = ivec2(int(pc.imageSize.x) - 1, int(min(pc.rows, pc.imageSize.y)) - 1);
  for (int ty = 0; ty < kTile; ++ty) {
    for (int tx = 0; tx < kTile; ++tx) {
      const int k = ty * kTile + tx;
      const uint j = pixelIndex(clamp(origin + (ivec2(tx, ty) - 2) * step, ivec2(0), last));
      color[k] = filtered[source + j];
      guide[k] = geometry[j];
      lum[k] = luminance(color[k].rgb);
      tapVariance[k] = max(color[k].a, 0.0);
    }
  }
  filterPixel(origin, 0, 0, destination, squaring);
  filterPixel(origin, 1, 0, destination, squaring);
  filterPixel(origin, 0, 1, destination, squaring);
  filterPixel(origin, 1, 1, destination, squaring);
}

void main() {
  const int step = int(pc.step);
  const ivec2 g = ivec2(gl_GlobalInvocationID.xy);
  const ivec2 origin = (g / step) * (WB_DENOISE_ATROUS_BLOCK * step) + g % step;  // the block's first pixel
  if (!insideImage(origin)) return;  // the block's first pixel is off the image: so are the others
  const uint source = pc.source * planeSize(), destination = (pc.source ^ 1u) * planeSize();
  if (pc.sigmaNormal == 128.0) {
    filterBlock(origin, source, destination, true);
  } else {
    filterBlock(origin, source, destination, false);
  }
}
