// Descriptor set 0 binding numbers of every pipeline, defined once for C++ and GLSL: the path tracer (and its
// inspector build), the hybrid modes (which share the scene's bindings with the path tracer).
#ifndef WB_BINDINGS_H
#define WB_BINDINGS_H

// ---- the path tracer; the scene's bindings (TLAS, geometries, materials, textures, environment map) are the
// hybrid modes' too ----
#define WB_BIND_TLAS 0          // accelerationStructureEXT
#define WB_BIND_ACCUM 1         // rgba32f storage image: running average of radiance
#define WB_BIND_FRAME 2         // uniform buffer FrameUniforms
#define WB_BIND_GEOMETRIES 3    // storage buffer GeometryInfo[] (indexed by instance custom index + geometry index)
#define WB_BIND_MATERIALS 4     // storage buffer Material[]
#define WB_BIND_LIGHTS 5        // storage buffer DirectionalLight[]
#define WB_BIND_TEXTURES 6      // sampler2D[] (runtime array, descriptor indexing)
#define WB_BIND_ENV_MAP 7       // sampler2D: equirectangular environment (1x1 when constant colour)
#define WB_BIND_ENV_ALIAS 8     // storage buffer EnvAliasEntry[] (importance sampling table)
#define WB_BIND_AOV_ALBEDO 9    // rgba16f storage image: first-hit base colour, a = fraction of samples dropped (NaN/Inf)
#define WB_BIND_AOV_NORMAL 10   // rgba16f storage image: first-hit shading normal, a = first-hit distance (-1 = miss)
#define WB_BIND_COUNTERS 11     // storage buffer Counters
#define WB_BIND_BLUE_NOISE 12   // storage buffer uint[] 128x128 blue-noise (rg in 16 bits each)
#define WB_BIND_SOBOL 13        // storage buffer uint[] Sobol direction numbers [dim * 32 + bit]
#define WB_BIND_AOV_INFO 14     // rgba16f storage image: first-hit geometric normal, a = path vertices traced
#define WB_BIND_EMITTERS 15     // storage buffer EmissiveTriangle[] (world space), for next-event estimation
#define WB_BIND_EMITTER_ALIAS 16  // storage buffer EnvAliasEntry[] over emitters, weights = luminance * area
// rgba32f storage image, the heat maps' data (AOV): r = mean luminance^2 of the accumulated samples (with the
// accumulation's mean: per-pixel variance), g = fraction of paths Russian roulette ended, b = mean over all paths
// of the bounce where it ended them (0 for the others: b / g is the mean over those it ended), a = the lowest
// bounce at which a sample became NaN/Inf (WB_NO_NON_FINITE: none)
#define WB_BIND_AOV_STATS 20
#define WB_BIND_REFLECTORS 21   // storage buffer vec4[]: glossy reflectors' bounding spheres (xyz centre, w radius)
// storage buffer vec4[]: the radiance of each sample of a launch of several (launch depth > 1), [z][y][x]; the resolve
// pass (pathtracer/resolve.comp) accumulates them into WB_BIND_ACCUM in sample order
#define WB_BIND_SAMPLE_SLOTS 22
// The path inspector's buffers, declared only by the WB_INSPECT build of the path tracer (shaders/pathtracer/inspect.glsl).
#define WB_BIND_INSPECT_HEADER 17    // storage buffer InspectHeader: which pixel and how many records
#define WB_BIND_INSPECT_SAMPLES 18   // storage buffer InspectSample[]: one per recorded sample
#define WB_BIND_INSPECT_VERTICES 19  // storage buffer InspectVertex[]: vertexCapacity per recorded sample
// The cost variant's AOV (WB_COST, shaders/pathtracer/raygen.rgen), rgba32f storage image in the shader clock's
// units per sample: means over the accumulated samples of r = the whole sample, g = its trace calls less the hit
// and miss shaders they ran (traversal, any-hit), b = closest-hit and environment miss shading; a = a running
// median of the whole sample (robust to preempted invocations on a CPU device)
#define WB_BIND_AOV_COST 23
// wbPrint's records in the WB_INSPECT build (shaders/pathtracer/debug.glsl): storage buffer PrintRecord[],
// WB_PRINTS_PER_SAMPLE per recorded sample
#define WB_BIND_INSPECT_PRINTS 24
// wbAssert's failures in the WB_ASSERTS build: storage buffers AssertHeader and AssertRecord[]
#define WB_BIND_ASSERT_HEADER 25
#define WB_BIND_ASSERT_RECORDS 26
// The split of next-event estimation's shadow rays into a launch of their own (WB_SPLIT_SHADOWS;
// docs/bench/roofline.md): storage buffer vec4[] of PushConstants::splitSlots requests per pixel and sample of
// the launch, 3 vec4 each (origin and tMax, direction, the contribution if unoccluded and the bounce it leaves
// from), and vec4[] per pixel and sample (the path's own radiance and what raygen traced itself, a = the requests
// left for the shadow launch), in the split's variant with AOVs (WB_SPLIT_AOVS) WB_SPLIT_PATH_VEC4S_AOV vec4 per
// record: then the sample's AOVs (accumulate.glsl, SampleAovs)
#define WB_BIND_SPLIT_REQUESTS 27
#define WB_BIND_SPLIT_PATHS 28
#define WB_SPLIT_PATH_VEC4S_AOV 5u

// ---- the hybrid modes (G-buffer raster, shadow/AO and reflection ray tracing, composite compute) ----
#define WB_BIND_HYBRID_FRAME 40      // uniform buffer HybridUniforms
#define WB_BIND_GBUF_ALBEDO 41       // sampler2D rgba8: rgb base colour (linear), a metallic
#define WB_BIND_GBUF_NORMAL 42       // sampler2D rgba16f: xyz world shading normal facing the camera, w roughness
#define WB_BIND_GBUF_DEPTH 43        // sampler2D D32: reversed-Z depth (0 = background)
#define WB_BIND_GBUF_EMISSIVE 44     // sampler2D rgba16f: rgb emitted radiance, a unused
#define WB_BIND_SHADOW_MASK 45       // r8 storage image: sun visibility (temporally averaged when enabled)
#define WB_BIND_AO_MASK 46           // r8 storage image: ambient occlusion (1 = open)
#define WB_BIND_HYBRID_HISTORY 47    // rgba32f storage image: r shadow, g AO running averages (exact over frames)
#define WB_BIND_REFLECTION 48        // rgba16f storage image: rgb reflected radiance, a 1 where traced
#define WB_BIND_HYBRID_OUTPUT 49     // rgba32f storage image: composited linear radiance
#define WB_BIND_HYBRID_INSPECT 50    // storage buffer HybridInspectRecord: the rays of the inspected pixel

// ---- the bare-ray roofline (shaders/roofline; the scene's TLAS and geometries at their path tracer bindings) ----
#define WB_BIND_ROOFLINE_HITS 60     // rgba32f storage image: camera ray hit position, a = 1 hit, 0 miss
#define WB_BIND_ROOFLINE_NORMALS 61  // rgba32f storage image: geometric normal at the hit, facing the camera
#define WB_BIND_ROOFLINE_RESULT 62   // rgba32f storage image: what a launch found (keeps its rays from being unused)

#endif
