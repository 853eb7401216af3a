// Environment maps for importance sampling: equirectangular RGB (row 0 = +Y, see
// shaders/shared/sampling_math.h) plus the alias table that shaders/shared/env_sampling.h samples.
#pragma once
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "shared/scene_types.h"

namespace wb {

struct EnvironmentMap {
  int width = 0;
  int height = 0;
  std::vector<float> rgb;                 // width * height * 3 linear floats, row-major, row 0 = top (+Y)
  std::vector<gpu::EnvAliasEntry> alias;  // width * height entries
  float totalWeight = 0.0f;           // sum of the unnormalised pixel weights (FrameUniforms::envTotalWeight)
  std::vector<std::string> warnings;  // what the loader chose for the user (an 8-bit image taken as radiance)
};

// Pixel weights for importance sampling: luminance * sin(theta_center) (negative / non-finite luminance ->
// 0). If every weight is 0 (a black map) the weights fall back to sin(theta_center) so sampling stays
// defined.
std::vector<double> environmentWeights(int width, int height, const std::vector<float>& rgb);

// Vose's alias method: O(n) build, O(1) sampling. pdf = weight / sum. Throws on empty / all-zero / negative
// input.
std::vector<gpu::EnvAliasEntry> buildAliasTable(const std::vector<double>& weights);

// Builds alias + totalWeight for a map whose width/height/rgb are set.
void buildEnvironmentSampling(EnvironmentMap& env);

// Loads an equirectangular environment: a Radiance .hdr (common/image_decode.h: bounded, truncated files
// refused), or a PNG/JPEG decoded from sRGB to linear with a warning in EnvironmentMap::warnings. Throws
// std::runtime_error with the path and the reason for a directory, a missing or unreadable file, another
// format, a map smaller than 2x1 or one with no finite pixels.
EnvironmentMap loadHdrEnvironment(const std::filesystem::path& path);

// A 1x1 map of constant radiance (the sampler then draws uniformly in (u,v), pdf = 1 / (2 pi^2 sin theta)).
EnvironmentMap constantEnvironment(glm::vec3 radiance);

}  // namespace wb
