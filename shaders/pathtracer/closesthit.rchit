#version 460
#extension GL_GOOGLE_include_directive : require
#define WB_STAGE WB_STAGE_CLOSEST_HIT
// All surface shading: material evaluation, next-event estimation (directional lights, with MIS when they have an
// angular size; environment and area lights with MIS), BRDF sampling of the continuation ray, handed back to
// raygen through the payload together with the shadow rays that decide the light samples (raygen traces them: see
// ShadowRequest in payload.glsl).
#include "common.glsl"
#include "payload.glsl"
#include "hit_data.glsl"
#include "random.glsl"
#include "environment.glsl"
#include "emitters.glsl"
#include "guiding.glsl"

layout(location = PATH_PAYLOAD_LOCATION) rayPayloadInEXT PathPayload payload;

hitAttributeEXT vec2 attribs;

void main() {
#if WB_TIMED
  const uint shadeStart = wbClock();  // the cost variants: this shading's clocks go back in the payload
#endif
  wbDebugAtBounce(payload.bounce);
  initPathSampler(WB_PIXEL, WB_SAMPLE_INDEX);
  const GeometryInfo g = hitGeometry();
  const Material m = materials[g.materialIndex];
  const TriangleHit h = fetchTriangle(g, gl_PrimitiveID, attribs);

  const vec3 wo = -gl_WorldRayDirectionEXT;
  const vec3 position = gl_ObjectToWorldEXT * vec4(h.position, 1.0);
  // Normals transform with the inverse transpose: n_world = n_object * WorldToObject (3x3 part).
  vec3 ng = normalize((h.geoNormal * gl_WorldToObjectEXT).xyz);
  if (any(isnan(ng))) ng = wo;  // zero-area triangle: no orientation; face the viewer
  const bool frontFace = dot(ng, wo) >= 0.0;
  if (!frontFace) ng = -ng;  // shade the side the ray came from

  vec3 ns = (h.normal * gl_WorldToObjectEXT).xyz;
  ns = dot(ns, ns) > 1e-20 ? normalize(ns) : ng;
  // The shading normal goes to the side the ray came from, like ng: on back faces, and also where a mesh's
  // normals were authored against its winding (common on double-sided foliage).
  const bool nsFlipped = dot(ns, ng) < 0.0;
  if (nsFlipped) ns = -ns;

  // Material inputs, textures applied.
  const MaterialInputs inputs = materialInputs(m, h.uv);
  const vec4 baseColor = inputs.baseColor;
  const float metallic = inputs.metallic;
  const float roughness = inputs.roughness;
#if WB_HAS_EMISSIVE
  const vec3 emissive = inputs.emissive;
#endif

  // Normal mapping with the TBN frame (tangent sign from w); skipped when the tangent is missing or degenerate.
#if WB_HAS_NORMAL_MAPS
  if (m.normalTexture >= 0) {
    vec3 t = (gl_ObjectToWorldEXT * vec4(h.tangent.xyz, 0.0)).xyz;
    t = t - ns * dot(ns, t);
    if (dot(t, t) > 1e-20 && h.tangent.w != 0.0) {
      t = normalize(t);
      const vec3 b = cross(ns, t) * (h.tangent.w < 0.0 ? -1.0 : 1.0) * (nsFlipped ? -1.0 : 1.0);
      vec3 tn = sampleTexture(m.normalTexture, h.uv).xyz * 2.0 - 1.0;
      tn.xy *= m.normalScale;
      const vec3 mapped = tn.x * t + tn.y * b + tn.z * ns;
      if (dot(mapped, mapped) > 1e-20) ns = normalize(mapped);
    }
  }
#endif
  // Keep the shading normal on the visible side of the geometric normal (no black pixels at grazing views).
  const float minCos = 1e-3;
  const float nsDotWo = dot(ns, wo);
  if (nsDotWo < minCos) ns = normalize(ns + (minCos - nsDotWo) * wo);
  if (any(isnan(ns))) ns = ng;

  SurfaceMaterial sm;
  sm.baseColor = baseColor.rgb;
  sm.metallic = clamp(metallic, 0.0, 1.0);
  sm.roughness = clamp(roughness, 0.0, 1.0);
#if WB_HAS_SPECULAR
  sm.specularFactor = m.specularFactor;
  sm.specularColor = m.specularColorFactor;
#else  // no material of the scene sets KHR_materials_specular: its defaults, folded by the compiler
  sm.specularFactor = 1.0;
  sm.specularColor = vec3(1.0);
#endif

  payload.hitT = gl_HitTEXT;
  payload.albedo = baseColor.rgb;
  payload.normal = ns;
  payload.geoNormal = ng;

  // Emission, from the front face only unless the material is double-sided.
  vec3 radiance = vec3(0.0);
#if WB_INSPECT
  float emissionMis = 1.0;
#endif
#if WB_HAS_EMISSIVE
  if (frontFace || (m.flags & WB_MATERIAL_DOUBLE_SIDED) != 0u) {
    // A BRDF-sampled ray (pdf > 0) that hits an emitter is the second strategy for it when NEE sampled it too.
    float w = 1.0;
    if (payload.bounce > 0u && payload.pdf > 0.0 && (pc.flags & WB_FLAG_NO_NEE) == 0u &&
        frame.emitterCount > 0u) {
      if ((pc.flags & WB_FLAG_NO_BRDF_MIS) != 0u) {
        w = 0.0;  // light sampling only: emitters are reached through NEE alone
      } else {
        // The pdf next-event estimation had for this direction, from the previous vertex (the ray's origin).
        const float lightPdf =
            (1.0 - frame.envSelectProbability) *
            emitterPdf(gl_WorldRayOriginEXT, gl_ObjectToWorldEXT * vec4(h.p0, 1.0), gl_ObjectToWorldEXT * vec4(h.p1, 1.0),
                       gl_ObjectToWorldEXT * vec4(h.p2, 1.0), m.emissive, gl_HitTEXT, abs(dot(ng, wo)));
        w = powerHeuristic(1.0, payload.pdf, 1.0, lightPdf);
      }
    }
    radiance += emissive * w;
#if WB_INSPECT
    emissionMis = w;
#endif
  }
#endif

  const uint bounce = payload.bounce;
#if WB_INSPECT
  // The vertex's record: the surface here, its light samples in the loop below, its BRDF sample at the end.
  const uint iv = inspectVertex(bounce);
  uint inspectLights = 0u;
  if (iv != WB_INSPECT_NONE) {
    inspectVertices[iv].position = position;
    inspectVertices[iv].distance = gl_HitTEXT;
    inspectVertices[iv].geometricNormal = ng;
    inspectVertices[iv].shadingNormal = ns;
    inspectVertices[iv].incoming = gl_WorldRayDirectionEXT;
    inspectVertices[iv].flags = (frontFace ? WB_INSPECT_FRONT_FACE : 0u) | (nsFlipped ? WB_INSPECT_NORMAL_FLIPPED : 0u);
    inspectVertices[iv].instance = gl_InstanceID;
    inspectVertices[iv].primitive = gl_PrimitiveID;
    inspectVertices[iv].geometry = int(gl_InstanceCustomIndexEXT + gl_GeometryIndexEXT);
    inspectVertices[iv].material = int(g.materialIndex);
    inspectVertices[iv].emitted = radiance;
    inspectVertices[iv].emissionMis = emissionMis;
    inspectVertices[iv].lobe = WB_LOBE_DIFFUSE;
    inspectVertices[iv].lobeProbability = 0.0;
    inspectVertices[iv].direction = vec3(0.0);
    inspectVertices[iv].brdf = vec3(0.0);
    inspectVertices[iv].weight = vec3(0.0);
    inspectVertices[iv].pdf = 0.0;
    inspectVertices[iv].cosine = 0.0;
  }
  uint inspectNan = inspectNonFinite(ns, WB_INSPECT_NAN_SHADING_NORMAL) | inspectNonFinite(radiance, WB_INSPECT_NAN_EMISSION);
#endif
  // The vertex's sample dimensions (WB_DIM_LOBE .. WB_DIM_LIGHT + 2). A CPU device JIT-compiles every inlined copy
  // of the sampler: there they come from one loop up front (a shorter JIT); GPUs draw each where it is used (the
  // loop's array costs them trace rate). docs/bench/README.md has the measurements.
#if WB_CPU_DEVICE
  float u[WB_DIM_LIGHT + 3u];
  for (uint k = 0u; k < WB_DIM_LIGHT + 3u; ++k) u[k] = pathSampleBounce(bounce, k);
#define VERTEX_SAMPLE(k) u[k]
#else
#define VERTEX_SAMPLE(k) pathSampleBounce(bounce, k)
#endif
  const vec3 originOut = offsetRay(position, ng);
  payload.origin = originOut;
  uint shadowRequests = 0u;
  if ((pc.flags & WB_FLAG_NO_NEE) == 0u) {
    // Light samples: one per directional light (a delta light: plain light sampling, no MIS; a sun of angular
    // size: a direction uniform in its cone, from the light sample's point dimensions, MIS-weighted against BRDF
    // sampling, whose rays into the cone the miss shader weighs), then one sample of the environment or the area
    // lights together: pick which with the environment's selection probability; that one is MIS-weighted (power
    // heuristic) against BRDF sampling with the pdf of this combined strategy. Each light's estimate is unbiased
    // on its own, so lights may share sample dimensions. Every sample goes through the same loop body (one BRDF
    // evaluation: lavapipe's JIT time grows with every inlined copy) and becomes a shadow request for raygen.
    const float uChoice = VERTEX_SAMPLE(WB_DIM_LIGHT_CHOICE);
    const vec3 ul =
        vec3(VERTEX_SAMPLE(WB_DIM_LIGHT), VERTEX_SAMPLE(WB_DIM_LIGHT + 1u), VERTEX_SAMPLE(WB_DIM_LIGHT + 2u));
    const bool noMis = (pc.flags & WB_FLAG_NO_BRDF_MIS) != 0u;
    for (uint i = 0u; i <= WB_LIGHT_COUNT; ++i) {
      vec3 wi = vec3(0.0);        // direction to the light, for the BRDF
      vec3 shadowDir = vec3(0.0); // direction of the shadow ray (differs for area lights: offset end point)
      float tMax = 1.0e30;
      vec3 le = vec3(0.0);        // radiance arriving along wi
      float lightPdf = -1.0;      // solid-angle pdf of the strategy; 0 = delta light (no MIS); < 0: no sample
#if WB_INSPECT
      uint lightKind = i < WB_LIGHT_COUNT ? WB_INSPECT_LIGHT_DIRECTIONAL
                       : uChoice < frame.envSelectProbability ? WB_INSPECT_LIGHT_ENVIRONMENT
                                                              : WB_INSPECT_LIGHT_EMITTER;
      int lightIndex = i < WB_LIGHT_COUNT ? int(i) : -1;
#endif
      if (i < WB_LIGHT_COUNT) {
        const DirectionalLight light = lights[i];
        wi = -light.direction;
        le = light.radiance;
        lightPdf = 0.0;
        if (!sunIsDelta(light.cosAngularRadius)) {  // the sun's disc (shared/sun.h)
          wi = sampleCone(wi, light.cosAngularRadius, vec2(ul.y, ul.z));
          le = sunDiscRadiance(light.radiance, light.cosAngularRadius);
          lightPdf = sunConePdf(light.cosAngularRadius);
        }
        shadowDir = wi;
      } else if (uChoice < frame.envSelectProbability) {
#if WB_ENV_MODE != WB_ENV_NONE
        // Environment: importance sampled by its alias table.
        float envPdfValue;
        le = envSample(ul, wi, envPdfValue);
        shadowDir = wi;
        lightPdf = frame.envSelectProbability * envPdfValue;
        if (!(lightPdf > 0.0)) lightPdf = -1.0;
#endif
      } else {
#if WB_HAS_EMISSIVE
        // Area lights: a point on an emissive triangle; the choice's remainder is the alias coin.
        const float uCoin = (uChoice - frame.envSelectProbability) / (1.0 - frame.envSelectProbability);
        // From the shadow ray's origin, like the continuation ray whose MIS weight closest-hit computes there.
        const EmitterSample es = sampleEmitter(originOut, ul.x, min(uCoin, 0.99999994), vec2(ul.y, ul.z));
        lightPdf = (1.0 - frame.envSelectProbability) * es.pdf;
#if WB_INSPECT
        lightIndex = int(es.index);
#endif
        if (lightPdf > 0.0) {
          wi = es.wi;
          le = es.radiance;
          // The shadow ray stops short of the light by leaving from an origin offset off the light's surface.
          const vec3 lightPoint = offsetRay(es.position, dot(es.normal, es.wi) < 0.0 ? es.normal : -es.normal);
          tMax = length(lightPoint - originOut);
          shadowDir = normalize(lightPoint - originOut);
        } else {
          lightPdf = -1.0;
        }
#endif
      }
#if WB_INSPECT
      // Every light sample is recorded, those that end here with the reason.
      const uint il = iv != WB_INSPECT_NONE && inspectLights < WB_INSPECT_MAX_LIGHT_SAMPLES ? inspectLights : WB_INSPECT_NONE;
      ++inspectLights;
      if (il != WB_INSPECT_NONE) {
        inspectVertices[iv].lights[il].direction = wi;
        inspectVertices[iv].lights[il].kind = lightKind;
        inspectVertices[iv].lights[il].index = lightIndex;
        inspectVertices[iv].lights[il].radiance = le;
        inspectVertices[iv].lights[il].lightPdf = lightPdf;
        inspectVertices[iv].lights[il].distance = tMax;
        inspectVertices[iv].lights[il].brdfCos = vec3(0.0);
        inspectVertices[iv].lights[il].brdfPdf = 0.0;
        inspectVertices[iv].lights[il].misWeight = 0.0;
        inspectVertices[iv].lights[il].contribution = vec3(0.0);
        inspectVertices[iv].lights[il].status = lightPdf < 0.0 ? WB_INSPECT_NEE_NO_SAMPLE
                                                : dot(wi, ng) <= 0.0 ? WB_INSPECT_NEE_BELOW_SURFACE
                                                                     : WB_INSPECT_NEE_ZERO_BRDF;
      }
#endif
      if (lightPdf < 0.0 || dot(wi, ng) <= 0.0) continue;
      const vec3 f = brdfEval(sm, ns, wo, wi);
#if WB_INSPECT
      if (il != WB_INSPECT_NONE) {
        inspectVertices[iv].lights[il].brdfCos = f;
        inspectVertices[iv].lights[il].brdfPdf = pathPdf(sm, ns, wo, position, ng, wi);
      }
#endif
      if (max(f.x, max(f.y, f.z)) <= 0.0) continue;
      vec3 contribution = f * le;
      float misWeight = 1.0;  // delta lights, and light sampling alone (noMis): plain light sampling
      if (lightPdf != 0.0) {
        if (!noMis) misWeight = powerHeuristic(1.0, lightPdf, 1.0, pathPdf(sm, ns, wo, position, ng, wi));
        contribution *= misWeight / lightPdf;
      }
#if WB_INSPECT
      inspectNan |= inspectNonFinite(contribution, WB_INSPECT_NAN_LIGHT) | inspectNonFinite(le, WB_INSPECT_NAN_LIGHT) |
                    inspectNonFinite(misWeight, WB_INSPECT_NAN_LIGHT);
      if (il != WB_INSPECT_NONE) {
        inspectVertices[iv].lights[il].misWeight = misWeight;
        inspectVertices[iv].lights[il].contribution = contribution;
        inspectVertices[iv].lights[il].status = WB_INSPECT_NEE_TRACED;
      }
      // Raygen finds the record of the shadow ray's outcome through the request's spare field.
      payload.shadowRequests[shadowRequests].pad = il == WB_INSPECT_NONE ? -1.0 : float(il);
#endif
      payload.shadowRequests[shadowRequests].direction = shadowDir;
      payload.shadowRequests[shadowRequests].tMax = tMax;
      payload.shadowRequests[shadowRequests].radiance = contribution;
      ++shadowRequests;
    }
  }
  payload.radiance = radiance;
  payload.shadowRequestCount = shadowRequests;

  // Continuation ray by BRDF sampling (mixed with reflector directions: guiding.glsl).
  const float uPart = pathPartSample(sampleDimension(bounce, WB_DIM_LOBE), VERTEX_SAMPLE(WB_DIM_LOBE));
  const vec3 uBrdf = vec3(uPart, VERTEX_SAMPLE(WB_DIM_BRDF), VERTEX_SAMPLE(WB_DIM_BRDF + 1u));
  const BrdfSample s = pathSample(sm, ns, wo, position, ng, uBrdf);
#if WB_INSPECT
  if (iv != WB_INSPECT_NONE) {
    const float cosine = dot(ns, s.wi);
    const vec3 fCos = brdfEval(sm, ns, wo, s.wi);
    inspectNan |= s.pdf > 0.0 ? inspectNonFinite(fCos, WB_INSPECT_NAN_BRDF) : 0u;
    inspectNan |= inspectNonFinite(s.pdf, WB_INSPECT_NAN_PDF) | inspectNonFinite(s.weight, WB_INSPECT_NAN_WEIGHT);
    inspectVertices[iv].lightSamples = inspectLights;
    inspectVertices[iv].lobe = s.lobe;
    inspectVertices[iv].lobeProbability = pathLobeProbability(sm, ns, wo, position, ng, s.lobe);
    inspectVertices[iv].direction = s.wi;
    inspectVertices[iv].pdf = s.pdf;
    inspectVertices[iv].weight = s.weight;
    inspectVertices[iv].cosine = cosine;
    inspectVertices[iv].brdf = cosine > 0.0 ? fCos / cosine : vec3(0.0);
    inspectVertices[iv].nonFinite = inspectNan;
    if (s.pdf > 0.0 && dot(s.wi, ng) > 0.0) inspectVertices[iv].flags |= WB_INSPECT_CONTINUED;
  }
#endif
  if (s.pdf <= 0.0 || dot(s.wi, ng) <= 0.0) {
    payload.status = PAYLOAD_ABSORBED;  // below the geometric surface: would leak light through it
#if WB_TIMED
    payload.shadeClocks = wbClock() - shadeStart;
#endif
    return;
  }
  payload.status = PAYLOAD_CONTINUE;
  payload.weight = s.weight;
  payload.pdf = s.pdf;
  payload.direction = s.wi;
#if WB_TIMED
  payload.shadeClocks = wbClock() - shadeStart;
#endif
}
