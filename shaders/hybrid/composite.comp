#version 460
#extension GL_GOOGLE_include_directive : require
// Composite: direct sun (BRDF of the path tracer) times the ray traced shadow mask, ambient from the environment
// times ambient occlusion, ray traced reflections on smooth surfaces, emission; the environment behind, and the
// sun's disc there when it has an angular size (as the path tracer's camera rays see it).
// Output: linear radiance (the PNG writer tonemaps, EXR keeps it linear).
#include "common.glsl"
#include "gbuffer.glsl"
#include "lighting.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(set = 0, binding = WB_BIND_SHADOW_MASK, r8) uniform readonly image2D shadowMask;
layout(set = 0, binding = WB_BIND_AO_MASK, r8) uniform readonly image2D aoMask;
layout(set = 0, binding = WB_BIND_REFLECTION, rgba16f) uniform readonly image2D reflectionImage;
layout(set = 0, binding = WB_BIND_HYBRID_OUTPUT, rgba32f) uniform writeonly image2D outputImage;

void main() {
  const ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (p.x >= int(frame.width) || p.y >= int(frame.height)) return;
  const float depth = texelFetch(gbufDepth, p, 0).r;
  if (depth <= 0.0) {
    const vec3 dir = gbufViewDirection(p);
    vec3 background = envRadiance(dir);
    if (frame.hasSun != 0u)
      background += sunRadianceAlong(dir, frame.sunDirection, frame.sunCosAngle, frame.sunRadiance);
    imageStore(outputImage, p, vec4(background, 1.0));
    return;
  }
  const vec4 albedo = texelFetch(gbufAlbedo, p, 0);
  const vec4 nr = texelFetch(gbufNormal, p, 0);
  const vec4 emissive = texelFetch(gbufEmissive, p, 0);
  const vec3 n = normalize(nr.xyz);
  const vec3 position = gbufWorldPosition(p, depth);
  const vec3 wo = normalize(frame.cameraPosition - position);
  const SurfaceMaterial m = hybridMaterial(albedo.rgb, albedo.a, nr.w, emissive.a);
  const float shadow = imageLoad(shadowMask, p).r;
  const float ao = (frame.flags & WB_HYBRID_FLAG_AO) != 0u ? imageLoad(aoMask, p).r : 1.0;

  vec3 color = emissive.rgb + sunDirect(m, n, wo, shadow) + ao * envRadiance(n) * diffuseAlbedo(m, n, wo);
  const vec3 spec = specularAlbedo(m, n, wo);
  const vec4 reflection = (frame.flags & WB_HYBRID_FLAG_REFLECTIONS) != 0u ? imageLoad(reflectionImage, p)
                                                                           : vec4(0.0);
  if (reflection.a > 0.0) {
    color += spec * reflection.rgb;
  } else {
    color += ao * spec * envRadiance(reflect(-wo, n));
  }
  imageStore(outputImage, p, vec4(color, 1.0));
}
