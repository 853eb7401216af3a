// The path inspector's records made sense of on the host: the samples of the inspected pixel in order, each
// with its vertices, what every vertex and the escaping ray added to the sample, the first NaN/Inf and the
// term that produced it, and the pixel's estimate from the recorded samples. The shaders write the records
// (shaders/pathtracer/inspect.glsl, structs in shaders/shared/inspect_types.h); PathTracer::readInspection
// reads them.
#pragma once
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "render/path_tracer.h"

namespace wb::render {

struct InspectedVertex {
  gpu::InspectVertex record;
  std::vector<gpu::InspectLightSample> lights;  // the recorded light samples
  // What raygen added to the sample at the vertex: throughputIn * (the radiance closest-hit returned + every
  // visible shadow request's). When the shader records what it returns, throughputIn * (emitted + the
  // contributions of visible light samples).
  glm::vec3 added{0.0f};
};

struct NonFiniteSource {
  int vertex = -1;    // the vertex whose term went NaN/Inf; -1: the sample's end (environment or its sum)
  uint32_t term = 0;  // one WB_INSPECT_NAN_* bit
};

struct InspectedSample {
  gpu::InspectSample record;
  std::vector<InspectedVertex> vertices;  // the recorded ones, in path order
  bool truncated = false;                 // the path had more vertices than the records hold
  glm::vec3 escapeAdded{0.0f};            // escapeThroughput * escapeRadiance when the path escaped
  glm::vec3 sum{0.0f};  // every vertex's `added` plus escapeAdded: the sample's value up to float rounding
  std::optional<NonFiniteSource> firstNonFinite;
  // wbPrint's records of the sample, in the order it made them (record.prints made; at most
  // WB_PRINTS_PER_SAMPLE kept).
  std::vector<gpu::PrintRecord> prints;
};

// The written samples of `buffers` whose index is below `sampleLimit` (the samples whose traces finished), by
// sample index.
std::vector<InspectedSample> inspectedSamples(const InspectBuffers& buffers,
                                              uint32_t sampleLimit = UINT32_MAX);

// Mean and variance of sample values, added one at a time (Welford): the Inspect tab's running estimate.
class RunningEstimate {
 public:
  void add(const glm::dvec3& value);
  void addDropped() { ++dropped_; }
  uint32_t count() const { return count_; }
  uint32_t dropped() const { return dropped_; }
  glm::dvec3 mean() const { return mean_; }
  // Unbiased sample variance of one sample's value (0 with fewer than 2); the mean's is variance() / count().
  glm::dvec3 variance() const { return count_ > 1 ? m2_ / double(count_ - 1) : glm::dvec3(0.0); }

 private:
  uint32_t count_ = 0, dropped_ = 0;
  glm::dvec3 mean_{0.0}, m2_{0.0};
};

// The estimate of the accumulated (finite) samples: what the path tracer averages into the pixel.
RunningEstimate estimateOf(const std::vector<InspectedSample>& samples);

// Names of the record's codes, as the JSON and the Inspect tab write them.
const char* inspectEndName(uint32_t end);         // "escaped", "absorbed", "max_bounces", ...
const char* inspectLobeName(uint32_t lobe);       // "diffuse" | "specular" | "reflector"
const char* inspectRrName(uint32_t outcome);      // "not_applied" | "survived" | "terminated"
const char* inspectLightKindName(uint32_t kind);  // "directional" | "environment" | "emitter"
const char* inspectLightStatusName(
    uint32_t status);                             // "traced" | "no_sample" | "below_surface" | "zero_brdf"
const char* inspectNonFiniteName(uint32_t term);  // "shading_normal", "emission", ...
const char* debugStageName(uint32_t stage);       // "raygen", "closest_hit", "any_hit", "miss", "shadow_miss"
const char* clockName(uint32_t clock);            // "none", "subgroup", "device"
// A print's value as text ("0.5", "(1, 2, 3)", "true"): floats with 9 significant digits (they read back
// exactly), NaN and Inf by name.
std::string printValueText(const gpu::PrintRecord& p);
// A print's or an assert's label: its text (`labels`: shader::debugLabelsOf), or "#" and its id in hex.
std::string debugLabelText(uint32_t label, const std::map<uint32_t, std::string>& labels);

}  // namespace wb::render
