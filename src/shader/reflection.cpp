#include "shader/reflection.h"

#include <spirv_cross/spirv_cross.hpp>

#include <algorithm>
#include <map>
#include <sstream>

namespace wb::shader {

namespace {

DescriptorBinding makeBinding(const spirv_cross::Compiler& c, const spirv_cross::Resource& r,
                              VkDescriptorType type, Stage stage) {
  DescriptorBinding b;
  b.set = c.get_decoration(r.id, spv::DecorationDescriptorSet);
  b.binding = c.get_decoration(r.id, spv::DecorationBinding);
  b.type = type;
  b.stages = toVkStage(stage);
  b.name = r.name.empty() ? c.get_name(r.base_type_id) : r.name;
  const auto& t = c.get_type(r.type_id);
  b.count = 1;
  for (size_t i = 0; i < t.array.size(); ++i) {
    if (t.array[i] == 0 && t.array_size_literal[i]) {
      b.runtimeArray = true;
    } else if (t.array_size_literal[i]) {
      b.count *= t.array[i];
    }
  }
  if (b.runtimeArray) b.count = 0;
  return b;
}

bool isBufferDim(const spirv_cross::Compiler& c, const spirv_cross::Resource& r) {
  return c.get_type(r.type_id).image.dim == spv::DimBuffer;
}

// Conservative byte size of a type: scalars and vectors rounded up to 16 bytes per member, arrays multiplied.
uint32_t conservativeSize(const spirv_cross::Compiler& c, const spirv_cross::SPIRType& t) {
  uint32_t size = 0;
  if (t.basetype == spirv_cross::SPIRType::Struct) {
    for (const auto member : t.member_types) size += conservativeSize(c, c.get_type(member));
  } else {
    size = std::max<uint32_t>(16, (t.width / 8) * t.vecsize * t.columns);
    size = (size + 15) / 16 * 16;
  }
  for (size_t i = 0; i < t.array.size(); ++i) {
    if (t.array_size_literal[i]) size *= std::max<uint32_t>(t.array[i], 1);
  }
  return size;
}

}  // namespace

Reflection reflectSpirv(const std::vector<uint32_t>& spirv, Stage stage, const fs::path& file) {
  Reflection out;
  try {
    spirv_cross::Compiler c(spirv);
    const auto active = c.get_active_interface_variables();
    const auto res = c.get_shader_resources(active);
    auto add = [&](const spirv_cross::SmallVector<spirv_cross::Resource>& list, auto typeOf) {
      for (const auto& r : list) out.bindings.push_back(makeBinding(c, r, typeOf(r), stage));
    };
    add(res.uniform_buffers, [](auto&) { return VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER; });
    add(res.storage_buffers, [](auto&) { return VK_DESCRIPTOR_TYPE_STORAGE_BUFFER; });
    add(res.storage_images, [&](auto& r) {
      return isBufferDim(c, r) ? VK_DESCRIPTOR_TYPE_STORAGE_TEXEL_BUFFER : VK_DESCRIPTOR_TYPE_STORAGE_IMAGE;
    });
    add(res.sampled_images, [&](auto& r) {
      return isBufferDim(c, r) ? VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER
                               : VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
    });
    add(res.separate_images, [&](auto& r) {
      return isBufferDim(c, r) ? VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER : VK_DESCRIPTOR_TYPE_SAMPLED_IMAGE;
    });
    add(res.separate_samplers, [](auto&) { return VK_DESCRIPTOR_TYPE_SAMPLER; });
    add(res.acceleration_structures, [](auto&) { return VK_DESCRIPTOR_TYPE_ACCELERATION_STRUCTURE_KHR; });
    add(res.subpass_inputs, [](auto&) { return VK_DESCRIPTOR_TYPE_INPUT_ATTACHMENT; });
    // Ray payloads, callable data and hit attributes are no "resources" to SPIRV-Cross: find their
    // OpVariables (and the pointer types that name what they hold) in the module itself.
    std::map<uint32_t, uint32_t> pointee;                  // OpTypePointer id -> pointed-to type
    std::vector<std::pair<uint32_t, uint32_t>> variables;  // (pointer type, storage class)
    for (size_t i = 5; i < spirv.size();) {
      const uint32_t count = spirv[i] >> 16, op = spirv[i] & 0xFFFFu;
      if (count == 0 || i + count > spirv.size()) break;
      if (op == spv::OpTypePointer && count >= 4) pointee[spirv[i + 1]] = spirv[i + 3];
      if (op == spv::OpVariable && count >= 4) variables.emplace_back(spirv[i + 1], spirv[i + 3]);
      i += count;
    }
    for (const auto& [pointerType, storage] : variables) {
      const bool payload =
          storage == spv::StorageClassRayPayloadKHR || storage == spv::StorageClassIncomingRayPayloadKHR ||
          storage == spv::StorageClassCallableDataKHR || storage == spv::StorageClassIncomingCallableDataKHR;
      const bool attribute = storage == spv::StorageClassHitAttributeKHR;
      const auto it = pointee.find(pointerType);
      if ((!payload && !attribute) || it == pointee.end()) continue;
      const uint32_t bytes = conservativeSize(c, c.get_type(it->second));
      uint32_t& field = payload ? out.rayPayloadBytes : out.hitAttributeBytes;
      field = std::max(field, bytes);
    }
    for (const auto& pc : res.push_constant_buffers) {
      const auto& type = c.get_type(pc.base_type_id);
      const uint32_t size = static_cast<uint32_t>(c.get_declared_struct_size(type));
      uint32_t offset = size;
      for (uint32_t i = 0; i < type.member_types.size(); ++i)
        offset = std::min(offset, c.type_struct_member_offset(type, i));
      if (type.member_types.empty()) offset = 0;
      out.pushConstants.push_back({static_cast<VkShaderStageFlags>(toVkStage(stage)), offset, size - offset});
    }
  } catch (const spirv_cross::CompilerError& e) {
    throw CompileError({{file, 0, "error", std::string("SPIRV-Cross reflection: ") + e.what()}});
  }
  std::sort(out.bindings.begin(), out.bindings.end(), [](const auto& a, const auto& b) {
    return std::tie(a.set, a.binding) < std::tie(b.set, b.binding);
  });
  return out;
}

PipelineLayoutDesc mergeLayouts(const std::vector<std::shared_ptr<const CompiledShader>>& stages) {
  struct Slot {
    DescriptorBinding b;
    fs::path file;
  };
  std::map<std::pair<uint32_t, uint32_t>, Slot> slots;
  PipelineLayoutDesc out;
  std::vector<Diagnostic> errors;
  for (const auto& s : stages) {
    if (!s) continue;
    const fs::path file = s->files.empty() ? s->key.path : s->files.front();
    for (const auto& b : s->reflection.bindings) {
      auto [it, inserted] = slots.try_emplace({b.set, b.binding}, Slot{b, file});
      if (inserted) continue;
      DescriptorBinding& m = it->second.b;
      const bool countsAgree = m.runtimeArray || b.runtimeArray || m.count == b.count;
      if (m.type != b.type || !countsAgree) {
        auto describe = [](const DescriptorBinding& x) {
          std::ostringstream d;
          d << descriptorTypeName(x.type) << " '" << x.name << "'";
          if (x.runtimeArray)
            d << "[]";
          else if (x.count != 1)
            d << '[' << x.count << ']';
          return d.str();
        };
        std::ostringstream w;
        w << "set " << b.set << " binding " << b.binding;
        const std::string where = w.str();
        errors.push_back({it->second.file, 0, "error",
                          "binding conflict at " + where + ": " + describe(m) + " here, but " + describe(b) +
                              " in " + file.string()});
        errors.push_back({file, 0, "error",
                          "binding conflict at " + where + ": " + describe(b) + " here, but " + describe(m) +
                              " in " + it->second.file.string()});
        continue;
      }
      m.stages |= b.stages;
      if (b.runtimeArray && !m.runtimeArray) {
        m.runtimeArray = true;
        m.count = 0;
      }
    }
    for (const auto& pc : s->reflection.pushConstants) {
      if (out.pushConstants.empty()) {
        out.pushConstants.push_back(pc);
      } else {
        auto& r = out.pushConstants.front();
        const uint32_t begin = std::min(r.offset, pc.offset);
        const uint32_t end = std::max(r.offset + r.size, pc.offset + pc.size);
        r.offset = begin;
        r.size = end - begin;
        r.stageFlags |= pc.stageFlags;
      }
    }
  }
  if (!errors.empty()) throw CompileError(std::move(errors));
  for (auto& [k, slot] : slots) out.bindings.push_back(std::move(slot.b));
  return out;
}

}  // namespace wb::shader
