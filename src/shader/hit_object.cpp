#include "shader/hit_object.h"

#include <glslang/SPIRV/spirv.hpp>

#include <algorithm>
#include <set>
#include <string>

namespace wb::shader {

namespace {

constexpr size_t kHeaderWords = 5;

bool isHitObjectOp(uint32_t op) {
  return op >= spv::OpHitObjectRecordHitMotionNV && op <= spv::OpTypeHitObjectNV;
}

// The hit object instructions that give a value (<result type> <result id> ...): queries of the hit.
bool givesValue(uint32_t op) {
  switch (op) {
    case spv::OpHitObjectGetWorldToObjectNV:
    case spv::OpHitObjectGetObjectToWorldNV:
    case spv::OpHitObjectGetObjectRayDirectionNV:
    case spv::OpHitObjectGetObjectRayOriginNV:
    case spv::OpHitObjectGetShaderRecordBufferHandleNV:
    case spv::OpHitObjectGetShaderBindingTableRecordIndexNV:
    case spv::OpHitObjectGetCurrentTimeNV:
    case spv::OpHitObjectGetHitKindNV:
    case spv::OpHitObjectGetPrimitiveIndexNV:
    case spv::OpHitObjectGetGeometryIndexNV:
    case spv::OpHitObjectGetInstanceIdNV:
    case spv::OpHitObjectGetInstanceCustomIndexNV:
    case spv::OpHitObjectGetWorldRayDirectionNV:
    case spv::OpHitObjectGetWorldRayOriginNV:
    case spv::OpHitObjectGetRayTMaxNV:
    case spv::OpHitObjectGetRayTMinNV:
    case spv::OpHitObjectIsEmptyNV:
    case spv::OpHitObjectIsHitNV:
    case spv::OpHitObjectIsMissNV:
      return true;
    default:
      return false;
  }
}

// The literal string starting at word `at` of an instruction of `count` words (nul-terminated, padded to
// words: it takes size / 4 + 1 words).
std::string literalString(const uint32_t* words, size_t at, size_t count) {
  std::string s;
  for (size_t i = at; i < count; ++i)
    for (int b = 0; b < 4; ++b) {
      const char c = char((words[i] >> (8 * b)) & 0xFFu);
      if (c == 0) return s;
      s += c;
    }
  return s;
}

}  // namespace

bool usesHitObjects(const std::vector<uint32_t>& spirv) {
  for (size_t i = kHeaderWords; i < spirv.size();) {
    const uint32_t count = spirv[i] >> 16, op = spirv[i] & 0xFFFFu;
    if (count == 0 || i + count > spirv.size()) return false;
    if (op == spv::OpTypeHitObjectNV) return true;
    i += count;
  }
  return false;
}

std::vector<uint32_t> withoutHitObjects(const std::vector<uint32_t>& spirv) {
  if (!usesHitObjects(spirv)) return spirv;
  // The ids that go: the hit object type, pointers to it, variables of those pointers (and the hit object
  // attribute variables, which only hit object instructions read). A module declares a type before what
  // uses it, so one pass in order finds them all.
  std::set<uint32_t> removed;
  for (size_t i = kHeaderWords; i < spirv.size();) {
    const uint32_t count = spirv[i] >> 16, op = spirv[i] & 0xFFFFu;
    if (count == 0 || i + count > spirv.size()) break;
    if (op == spv::OpTypeHitObjectNV && count >= 2) removed.insert(spirv[i + 1]);
    if (op == spv::OpTypePointer && count >= 4 && removed.count(spirv[i + 3])) removed.insert(spirv[i + 1]);
    if (op == spv::OpVariable && count >= 4 &&
        (removed.count(spirv[i + 1]) || spirv[i + 3] == spv::StorageClassHitObjectAttributeNV))
      removed.insert(spirv[i + 2]);
    i += count;
  }
  std::vector<uint32_t> out(spirv.begin(), spirv.begin() + kHeaderWords);
  out.reserve(spirv.size());
  for (size_t i = kHeaderWords; i < spirv.size();) {
    const uint32_t count = spirv[i] >> 16, op = spirv[i] & 0xFFFFu;
    if (count == 0 || i + count > spirv.size()) break;
    const uint32_t* words = spirv.data() + i;
    i += count;
    if (op == spv::OpHitObjectTraceRayNV && count == 13) {
      // OpHitObjectTraceRayNV <hit object> <11 operands of OpTraceRayKHR>.
      out.push_back((12u << 16) | spv::OpTraceRayKHR);
      out.insert(out.end(), words + 2, words + 13);
      continue;
    }
    if (givesValue(op) && count >= 3) {
      // A query's value becomes undefined: what reads it stays valid, and no resource hangs on it.
      out.insert(out.end(), {(3u << 16) | spv::OpUndef, words[1], words[2]});
      continue;
    }
    if (isHitObjectOp(op)) continue;
    if (op == spv::OpCapability && count >= 2 && words[1] == spv::CapabilityShaderInvocationReorderNV)
      continue;
    if (op == spv::OpExtension && literalString(words, 1, count) == "SPV_NV_shader_invocation_reorder")
      continue;
    if ((op == spv::OpName || op == spv::OpMemberName || op == spv::OpDecorate ||
         op == spv::OpMemberDecorate) &&
        count >= 2 && removed.count(words[1]))
      continue;
    if ((op == spv::OpTypePointer && count >= 2 && removed.count(words[1])) ||
        (op == spv::OpVariable && count >= 3 && removed.count(words[2])))
      continue;
    if (op == spv::OpEntryPoint && count >= 4) {
      // <model> <function> <name> <interface ids>: the removed variables leave the interface.
      const size_t interfaceAt = 3 + literalString(words, 3, count).size() / 4 + 1;
      std::vector<uint32_t> kept(words, words + std::min<size_t>(interfaceAt, count));
      for (size_t w = interfaceAt; w < count; ++w)
        if (!removed.count(words[w])) kept.push_back(words[w]);
      kept[0] = (uint32_t(kept.size()) << 16) | op;
      out.insert(out.end(), kept.begin(), kept.end());
      continue;
    }
    out.insert(out.end(), words, words + count);
  }
  return out;
}

}  // namespace wb::shader
