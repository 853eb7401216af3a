// Helpers of the path tracer GPU tests: mean estimates with an error bar, HDR files written on the fly, image
// comparisons.
#pragma once
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "gpu_fixture.h"

namespace wb::testing {

struct Estimate {
  double mean = 0;   // image mean of (r + g + b) / 3
  double sigma = 0;  // standard error of `mean`
  uint32_t dropped = 0;
  size_t nonFinite = 0;
};

// Mean of the image with its standard error, from `batches` independent renders of `spp` samples each (the
// PCG sampler unless told otherwise, seeds seedBase, seedBase + 1, ...: independent random numbers; owen is
// an independent randomisation per seed too, sobol is not). Per pixel p the batch values x_pk are iid, so the
// image mean M = sum_pk x_pk / (P K) has Var(M) = sum_p Var(x_p) / (K P^2); Var(x_p) is estimated by the
// unbiased per-pixel sample variance across batches. Where pixels share random choices (the reflector
// guiding's coherent tiles) they are not independent: sigma is then the larger of that and the spread of the
// batches' image means.
Estimate estimateMean(render::RenderSession& session, render::RenderSettings settings, int batches,
                      uint32_t spp, uint32_t seedBase,
                      render::SamplerKind sampler = render::SamplerKind::Pcg);

// Writes a small equirectangular Radiance .hdr (rgb floats, row 0 = top) and returns its path (temp dir).
std::filesystem::path writeHdr(const std::string& name, int width, int height, const std::vector<float>& rgb);

double imageMean(const eval::ImageRGBA& img);  // of (r + g + b) / 3

}  // namespace wb::testing
