#include "app/inspect_json.h"

#include <algorithm>
#include <cmath>

#include "app/debug_json.h"

namespace wb::app {
namespace {

using nlohmann::json;

json number(double v) {
  if (std::isnan(v)) return "nan";
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  return v;
}

json vec(const glm::vec3& v) {
  return json::array({number(v.x), number(v.y), number(v.z)});
}
json vec(const glm::dvec3& v) {
  return json::array({number(v.x), number(v.y), number(v.z)});
}

json lightJson(const gpu::InspectLightSample& l) {
  return {{"kind", render::inspectLightKindName(l.kind)},
          {"index", l.index},
          {"status", render::inspectLightStatusName(l.status)},
          {"direction", vec(l.direction)},
          {"radiance", vec(l.radiance)},
          {"light_pdf", number(l.lightPdf)},
          {"delta", l.kind == WB_INSPECT_LIGHT_DIRECTIONAL && l.lightPdf == 0.0f},
          {"brdf_cos", vec(l.brdfCos)},
          {"brdf_pdf", number(l.brdfPdf)},
          {"mis_weight", number(l.misWeight)},
          {"contribution", vec(l.contribution)},
          {"distance", number(l.distance)},
          {"visible", l.status == WB_INSPECT_NEE_TRACED && l.visible != 0}};
}

json vertexJson(const render::InspectedVertex& v, size_t bounce, uint32_t clock) {
  const auto& r = v.record;
  json lights = json::array();
  for (const auto& l : v.lights) lights.push_back(lightJson(l));
  json j = {{"bounce", bounce},
            {"position", vec(r.position)},
            {"distance", number(r.distance)},
            {"incoming", vec(r.incoming)},
            {"geometric_normal", vec(r.geometricNormal)},
            {"shading_normal", vec(r.shadingNormal)},
            {"front_face", (r.flags & WB_INSPECT_FRONT_FACE) != 0},
            {"normal_flipped", (r.flags & WB_INSPECT_NORMAL_FLIPPED) != 0},
            {"instance", r.instance},
            {"geometry", r.geometry},
            {"primitive", r.primitive},
            {"material", r.material},
            {"emitted", vec(r.emitted)},
            {"emission_mis_weight", number(r.emissionMis)},
            {"light_samples", r.lightSamples},
            {"lights", lights},
            {"continued", (r.flags & WB_INSPECT_CONTINUED) != 0},
            {"lobe", render::inspectLobeName(r.lobe)},
            {"lobe_probability", number(r.lobeProbability)},
            {"direction", vec(r.direction)},
            {"brdf", vec(r.brdf)},
            {"pdf", number(r.pdf)},
            {"cosine", number(r.cosine)},
            {"weight", vec(r.weight)},
            {"throughput_in", vec(r.throughputIn)},
            {"rr_probability", number(r.rrProbability)},
            {"rr_outcome", render::inspectRrName(r.rrOutcome)},
            {"throughput", vec(r.throughput)},
            {"added", vec(v.added)}};
  j["cost"] = clock == WB_CLOCK_NONE ? json(nullptr)
                                     : json{{"trace_clocks", r.traceClocks},
                                            {"shade_clocks", r.shadeClocks},
                                            {"shadow_clocks", r.shadowClocks}};
  return j;
}

}  // namespace

json inspectSampleJson(const render::InspectedSample& s, const std::map<uint32_t, std::string>& labels,
                       uint32_t clock) {
  const auto& r = s.record;
  json vertices = json::array();
  for (size_t k = 0; k < s.vertices.size(); ++k) vertices.push_back(vertexJson(s.vertices[k], k, clock));
  json prints = json::array();
  for (const auto& p : s.prints) prints.push_back(printJson(p, labels));
  json escape = nullptr;
  if (r.escaped) {
    escape = {{"direction", vec(r.escapeDirection)},   {"environment", vec(r.escapeEnvironment)},
              {"mis_weight", number(r.escapeMis)},     {"sun", vec(r.escapeSun)},
              {"throughput", vec(r.escapeThroughput)}, {"added", vec(s.escapeAdded)}};
  }
  json nonFinite = nullptr;
  if (s.firstNonFinite) {
    nonFinite = {{"vertex", s.firstNonFinite->vertex < 0 ? json(nullptr) : json(s.firstNonFinite->vertex)},
                 {"term", render::inspectNonFiniteName(s.firstNonFinite->term)}};
  }
  return {{"index", r.sampleIndex},
          {"jitter", json::array({number(r.jitter.x), number(r.jitter.y)})},
          {"camera_origin", vec(r.cameraOrigin)},
          {"camera_direction", vec(r.cameraDirection)},
          {"radiance", vec(r.radiance)},
          {"accumulated", r.accumulated != 0},
          {"end", render::inspectEndName(r.end)},
          {"vertex_count", r.vertexCount},
          {"vertices_truncated", s.truncated},
          {"shadow_rays", r.shadowRays},
          {"vertices", vertices},
          {"escape", escape},
          {"sum_of_added", vec(s.sum)},
          {"first_non_finite", nonFinite},
          {"clocks", clock == WB_CLOCK_NONE ? json(nullptr) : json(r.clocks)},
          {"escape_clocks", clock == WB_CLOCK_NONE || !r.escaped ? json(nullptr) : json(r.escapeClocks)},
          {"prints_made", r.prints},
          {"prints", prints}};
}

json inspectJson(const InspectContext& c, const std::vector<render::InspectedSample>& samples) {
  const render::RunningEstimate e = render::estimateOf(samples);
  json list = json::array();
  for (const auto& s : samples) list.push_back(inspectSampleJson(s, c.labels, c.clock));
  return {{"schema", "workbench-path-inspector/1"},
          {"scene", c.scene},
          {"pixel", json::array({c.x, c.y})},
          {"size", json::array({c.width, c.height})},
          {"samples_requested", c.samplesRequested},
          {"spp", c.spp},
          {"pixel_value", vec(glm::vec3(c.pixelValue))},
          {"pixel_samples", number(c.pixelValue.w)},
          {"clock", render::clockName(c.clock)},
          {"estimate",
           {{"samples", e.count()},
            {"dropped", e.dropped()},
            {"mean", vec(e.mean())},
            {"variance", vec(e.variance())},
            {"standard_error",
             vec(e.count() > 0 ? glm::sqrt(e.variance() / double(e.count())) : glm::dvec3(0.0))}}},
          {"samples", list}};
}

json hybridInspectJson(const InspectContext& c, const gpu::HybridInspectRecord& r, const std::string& mode) {
  auto ray = [](const gpu::HybridInspectRay& x) {
    return json{{"direction", vec(x.direction)},
                {"origin", vec(x.origin)},
                {"traced", x.traced != 0},
                {"visible", x.traced != 0 && x.visible != 0}};
  };
  json ao = json::array();
  for (uint32_t i = 0; i < std::min(r.aoRays, WB_HYBRID_INSPECT_MAX_AO); ++i) ao.push_back(ray(r.aoRay[i]));
  json bounces = json::array();
  for (uint32_t i = 0; i < std::min(r.reflectionBounces, WB_HYBRID_INSPECT_MAX_REFLECTIONS); ++i) {
    const auto& b = r.bounces[i];
    json j = {{"direction", vec(b.direction)},
              {"hit", b.hit != 0},
              {"throughput", vec(b.throughput)},
              {"added", vec(b.added)}};
    if (b.hit) {
      j["position"] = vec(b.position);
      j["normal"] = vec(b.normal);
      j["roughness"] = number(b.roughness);
      j["metallic"] = number(b.metallic);
      j["sun_visible"] = b.sunVisible > 0.0f;
    }
    bounces.push_back(j);
  }
  const bool written = r.frameIndex != WB_HYBRID_NO_INSPECT;
  json j = {{"schema", "workbench-hybrid-inspector/1"},
            {"scene", c.scene},
            {"mode", mode},
            {"pixel", json::array({c.x, c.y})},
            {"size", json::array({c.width, c.height})},
            {"frames", c.spp},
            {"pixel_value", vec(glm::vec3(c.pixelValue))},
            {"recorded", written},
            {"frame", written ? json(r.frameIndex) : json(nullptr)},
            {"covered", written && r.covered != 0}};
  if (!written || !r.covered) return j;
  j["position"] = vec(r.position);
  j["normal"] = vec(r.normal);
  j["shadow"] = {
      {"ray", ray(r.shadowRay)}, {"visibility", number(r.shadow)}, {"average", number(r.shadowAverage)}};
  j["ao"] = {{"rays", ao}, {"open", number(r.ao)}, {"average", number(r.aoAverage)}};
  j["reflection"] = r.reflected ? json{{"radiance", vec(r.reflection)}, {"bounces", bounces}} : json(nullptr);
  return j;
}

}  // namespace wb::app
