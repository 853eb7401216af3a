// Shader execution reordering's hit objects (SPV_NV_shader_invocation_reorder) in a module the reflection
// reads.
#pragma once
#include <cstdint>
#include <vector>

namespace wb::shader {

// True when the module uses hit objects (declares the type OpTypeHitObjectNV).
bool usesHitObjects(const std::vector<uint32_t>& spirv);

// The module as reflection sees it without hit objects: each hitObjectTraceRayNV becomes the traceRayEXT with
// the same operands (so the acceleration structure and the payload stay in use), each query of a hit object
// an undefined value of its type, every other hit object instruction, the type, its pointers and variables,
// their names and decorations, the capability and the extension are left out. SPIRV-Cross of Debian 12 (2021)
// cannot parse the hit object type; a hit object holds no descriptor, so the descriptors, push constants and
// payloads the reflection finds are the module's own. The result is for reflection only, never for a driver.
// A module without hit objects comes back unchanged.
std::vector<uint32_t> withoutHitObjects(const std::vector<uint32_t>& spirv);

}  // namespace wb::shader
