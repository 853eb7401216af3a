#include "render/path_inspector.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>

#include "shared/brdf.h"

namespace wb::render {
namespace {

bool finite(const glm::vec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

// The first of a vertex's or a sample's non-finite terms, in the order they are computed: closest-hit's
// terms, what raygen added at the vertex, the throughput after it; the escape, the sample's sum.
std::optional<uint32_t> firstTerm(uint32_t bits) {
  static const uint32_t kOrder[] = {
      WB_INSPECT_NAN_SHADING_NORMAL, WB_INSPECT_NAN_EMISSION,   WB_INSPECT_NAN_LIGHT,
      WB_INSPECT_NAN_BRDF,           WB_INSPECT_NAN_PDF,        WB_INSPECT_NAN_WEIGHT,
      WB_INSPECT_NAN_ADDED,          WB_INSPECT_NAN_THROUGHPUT, WB_INSPECT_NAN_ENVIRONMENT,
      WB_INSPECT_NAN_RADIANCE};
  for (uint32_t bit : kOrder)
    if (bits & bit) return bit;
  return std::nullopt;
}

}  // namespace

std::vector<InspectedSample> inspectedSamples(const InspectBuffers& b, uint32_t sampleLimit) {
  std::vector<InspectedSample> out;
  const uint32_t capacity = b.header.vertexCapacity;
  for (size_t slot = 0; slot < b.samples.size(); ++slot) {
    const gpu::InspectSample& rec = b.samples[slot];
    if (rec.sampleIndex == WB_INSPECT_NO_SAMPLE || rec.sampleIndex >= sampleLimit) continue;
    InspectedSample s;
    s.record = rec;
    const uint32_t recorded = std::min(rec.vertexCount, capacity);
    s.truncated = rec.vertexCount > capacity;
    for (uint32_t k = 0; k < recorded; ++k) {
      InspectedVertex v;
      v.record = b.vertices.at(slot * capacity + k);
      const uint32_t lights = std::min(v.record.lightSamples, WB_INSPECT_MAX_LIGHT_SAMPLES);
      v.lights.assign(v.record.lights, v.record.lights + lights);
      v.added = v.record.added;  // raygen's: what went into the sample, whatever closest-hit recorded
      s.sum += v.added;
      const uint32_t bits = v.record.nonFinite | v.record.pathNonFinite;
      if (!s.firstNonFinite) {
        if (auto term = firstTerm(bits)) s.firstNonFinite = NonFiniteSource{int(k), *term};
      }
      s.vertices.push_back(std::move(v));
    }
    if (rec.escaped) {
      s.escapeAdded = rec.escapeThroughput * rec.escapeRadiance;
      s.sum += s.escapeAdded;
    }
    if (!s.firstNonFinite) {
      if (auto term = firstTerm(rec.nonFinite)) s.firstNonFinite = NonFiniteSource{-1, *term};
    }
    const size_t first = slot * WB_PRINTS_PER_SAMPLE;
    const size_t kept = std::min<size_t>(rec.prints, WB_PRINTS_PER_SAMPLE);
    if (first + kept <= b.prints.size())
      s.prints.assign(b.prints.begin() + long(first), b.prints.begin() + long(first + kept));
    out.push_back(std::move(s));
  }
  std::sort(out.begin(), out.end(), [](const InspectedSample& a, const InspectedSample& b) {
    return a.record.sampleIndex < b.record.sampleIndex;
  });
  return out;
}

void RunningEstimate::add(const glm::dvec3& value) {
  ++count_;
  const glm::dvec3 delta = value - mean_;
  mean_ += delta / double(count_);
  m2_ += delta * (value - mean_);
}

RunningEstimate estimateOf(const std::vector<InspectedSample>& samples) {
  RunningEstimate e;
  for (const auto& s : samples) {
    if (s.record.accumulated && finite(s.record.radiance)) {
      e.add(glm::dvec3(s.record.radiance));
    } else {
      e.addDropped();
    }
  }
  return e;
}

const char* inspectEndName(uint32_t end) {
  switch (end) {
    case WB_INSPECT_END_ESCAPED:
      return "escaped";
    case WB_INSPECT_END_ABSORBED:
      return "absorbed";
    case WB_INSPECT_END_MAX_BOUNCES:
      return "max_bounces";
    case WB_INSPECT_END_RUSSIAN_ROULETTE:
      return "russian_roulette";
    case WB_INSPECT_END_ZERO_THROUGHPUT:
      return "zero_throughput";
    default:
      return "unknown";
  }
}

const char* inspectLobeName(uint32_t lobe) {
  return lobe == WB_LOBE_SPECULAR ? "specular" : lobe == WB_LOBE_REFLECTOR ? "reflector" : "diffuse";
}

const char* inspectRrName(uint32_t outcome) {
  switch (outcome) {
    case WB_INSPECT_RR_SURVIVED:
      return "survived";
    case WB_INSPECT_RR_TERMINATED:
      return "terminated";
    default:
      return "not_applied";
  }
}

const char* inspectLightKindName(uint32_t kind) {
  switch (kind) {
    case WB_INSPECT_LIGHT_DIRECTIONAL:
      return "directional";
    case WB_INSPECT_LIGHT_ENVIRONMENT:
      return "environment";
    case WB_INSPECT_LIGHT_EMITTER:
      return "emitter";
    default:
      return "unknown";
  }
}

const char* inspectLightStatusName(uint32_t status) {
  switch (status) {
    case WB_INSPECT_NEE_TRACED:
      return "traced";
    case WB_INSPECT_NEE_NO_SAMPLE:
      return "no_sample";
    case WB_INSPECT_NEE_BELOW_SURFACE:
      return "below_surface";
    case WB_INSPECT_NEE_ZERO_BRDF:
      return "zero_brdf";
    default:
      return "unknown";
  }
}

const char* inspectNonFiniteName(uint32_t term) {
  switch (term) {
    case WB_INSPECT_NAN_SHADING_NORMAL:
      return "shading_normal";
    case WB_INSPECT_NAN_EMISSION:
      return "emission";
    case WB_INSPECT_NAN_LIGHT:
      return "light_sample";
    case WB_INSPECT_NAN_BRDF:
      return "brdf";
    case WB_INSPECT_NAN_PDF:
      return "pdf";
    case WB_INSPECT_NAN_WEIGHT:
      return "brdf_weight";
    case WB_INSPECT_NAN_THROUGHPUT:
      return "throughput";
    case WB_INSPECT_NAN_ENVIRONMENT:
      return "environment";
    case WB_INSPECT_NAN_ADDED:
      return "added";
    case WB_INSPECT_NAN_RADIANCE:
      return "sample_sum";
    default:
      return "unknown";
  }
}

const char* debugStageName(uint32_t stage) {
  switch (stage) {
    case WB_STAGE_RAYGEN:
      return "raygen";
    case WB_STAGE_CLOSEST_HIT:
      return "closest_hit";
    case WB_STAGE_ANY_HIT:
      return "any_hit";
    case WB_STAGE_MISS:
      return "miss";
    case WB_STAGE_SHADOW_MISS:
      return "shadow_miss";
    default:
      return "unknown";
  }
}

const char* clockName(uint32_t clock) {
  return clock == WB_CLOCK_SUBGROUP ? "subgroup" : clock == WB_CLOCK_DEVICE ? "device" : "none";
}

std::string printValueText(const gpu::PrintRecord& p) {
  const uint32_t n = std::clamp(p.components, 1u, 4u);
  std::string out = n > 1 ? "(" : "";
  for (uint32_t i = 0; i < n; ++i) {
    const uint32_t bits = p.bits[int(i)];
    char buf[48];
    switch (p.type) {
      case WB_PRINT_FLOAT: {
        float f;
        std::memcpy(&f, &bits, sizeof f);
        if (std::isnan(f)) {
          std::snprintf(buf, sizeof buf, "nan");
        } else if (std::isinf(f)) {
          std::snprintf(buf, sizeof buf, f > 0 ? "inf" : "-inf");
        } else {
          std::snprintf(buf, sizeof buf, "%.9g", double(f));
        }
        break;
      }
      case WB_PRINT_INT:
        std::snprintf(buf, sizeof buf, "%d", int32_t(bits));
        break;
      case WB_PRINT_BOOL:
        std::snprintf(buf, sizeof buf, "%s", bits ? "true" : "false");
        break;
      default:
        std::snprintf(buf, sizeof buf, "%u", bits);
    }
    out += (i ? ", " : "") + std::string(buf);
  }
  return n > 1 ? out + ")" : out;
}

std::string debugLabelText(uint32_t label, const std::map<uint32_t, std::string>& labels) {
  const auto it = labels.find(label);
  if (it != labels.end()) return it->second;
  char buf[16];
  std::snprintf(buf, sizeof buf, "#%08x", label);
  return buf;
}

}  // namespace wb::render
