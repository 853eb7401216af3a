#include "shader/reflection.h"

#include "shader/hash.h"
#include "shader/hit_object.h"

#include <spirv_cross/spirv_cross.hpp>

#include <algorithm>
#include <cctype>
#include <regex>
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

bool isWordChar(char c) {
  return std::isalnum(static_cast<unsigned char>(c)) || c == '_';
}

bool hasWord(const std::string& line, const std::string& word) {
  if (word.empty()) return false;
  for (size_t at = line.find(word); at != std::string::npos; at = line.find(word, at + 1)) {
    const bool before = at == 0 || !isWordChar(line[at - 1]);
    const bool after = at + word.size() >= line.size() || !isWordChar(line[at + word.size()]);
    if (before && after) return true;
  }
  return false;
}

std::vector<std::string> fileLines(const fs::path& p) {
  std::vector<std::string> lines;
  const auto text = readFile(p);
  if (!text) return lines;
  std::istringstream in(*text);
  std::string line;
  while (std::getline(in, line)) lines.push_back(line);
  return lines;
}

// See findDeclaration (reflection.h).
std::pair<fs::path, int> declarationIn(const std::vector<fs::path>& files, const std::string& name,
                                       uint32_t binding) {
  for (const auto& f : files) {
    const auto lines = fileLines(f);
    for (size_t i = 0; i < lines.size(); ++i) {
      if (!hasWord(lines[i], name)) continue;
      for (size_t back = 0; back <= 2 && back <= i; ++back)
        if (lines[i - back].find("layout") != std::string::npos) return {f, int(i + 1)};
    }
  }
  const std::regex literal("binding\\s*=\\s*" + std::to_string(binding) + "\\b");
  for (const auto& f : files) {
    const auto lines = fileLines(f);
    for (size_t i = 0; i < lines.size(); ++i)
      if (std::regex_search(lines[i], literal)) return {f, int(i + 1)};
  }
  return {files.empty() ? fs::path() : files.front(), 0};
}

}  // namespace

Reflection reflectSpirv(const std::vector<uint32_t>& module, Stage stage, const fs::path& file) {
  Reflection out;
  const std::vector<uint32_t> spirv = withoutHitObjects(module);  // what SPIRV-Cross can parse
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

std::pair<fs::path, int> findDeclaration(const CompiledShader& stage, const DescriptorBinding& binding) {
  std::vector<fs::path> files = stage.files;
  if (files.empty()) files.push_back(stage.key.path);
  return declarationIn(files, binding.name, binding.binding);
}

void checkBindingAliases(const CompiledShader& stage) {
  // Every declared resource, used or not: a binding has one descriptor type in a pipeline layout.
  struct Declared {
    uint32_t set, binding;
    std::string type, name;
  };
  std::vector<Declared> declared;
  try {
    spirv_cross::Compiler c(withoutHitObjects(stage.spirv));
    const auto res = c.get_shader_resources();
    auto add = [&](const spirv_cross::SmallVector<spirv_cross::Resource>& list, const char* type) {
      for (const auto& r : list) {
        declared.push_back({c.get_decoration(r.id, spv::DecorationDescriptorSet),
                            c.get_decoration(r.id, spv::DecorationBinding), type,
                            r.name.empty() ? c.get_name(r.base_type_id) : r.name});
      }
    };
    add(res.uniform_buffers, "uniform-buffer");
    add(res.storage_buffers, "storage-buffer");
    add(res.storage_images, "storage-image");
    add(res.sampled_images, "sampled-image");
    add(res.separate_images, "separate-image");
    add(res.separate_samplers, "sampler");
    add(res.acceleration_structures, "acceleration-structure");
    add(res.subpass_inputs, "input-attachment");
  } catch (const spirv_cross::CompilerError&) {
    return;  // reflectSpirv reports an unreadable module
  }
  std::vector<fs::path> files = stage.files;
  if (files.empty()) files.push_back(stage.key.path);
  std::vector<Diagnostic> errors;
  for (size_t i = 0; i < declared.size(); ++i) {
    for (size_t j = i + 1; j < declared.size(); ++j) {
      const auto &a = declared[i], &b = declared[j];
      if (a.set != b.set || a.binding != b.binding || a.type == b.type) continue;
      const auto whereA = declarationIn(files, a.name, a.binding);
      const auto whereB = declarationIn(files, b.name, b.binding);
      const std::string at = "set " + std::to_string(a.set) + " binding " + std::to_string(a.binding);
      errors.push_back({whereB.first, whereB.second, "error",
                        "binding conflict at " + at + ": " + b.type + " '" + b.name + "' here, but " +
                            a.type + " '" + a.name + "' at " + whereA.first.string() + ":" +
                            std::to_string(whereA.second)});
    }
  }
  if (!errors.empty()) throw CompileError(std::move(errors));
}

PipelineLayoutDesc mergeLayouts(const std::vector<std::shared_ptr<const CompiledShader>>& stages) {
  struct Slot {
    DescriptorBinding b;
    fs::path file;
    const CompiledShader* stage;
  };
  std::map<std::pair<uint32_t, uint32_t>, Slot> slots;
  PipelineLayoutDesc out;
  std::vector<Diagnostic> errors;
  for (const auto& s : stages) {
    if (!s) continue;
    const fs::path file = s->files.empty() ? s->key.path : s->files.front();
    for (const auto& b : s->reflection.bindings) {
      auto [it, inserted] = slots.try_emplace({b.set, b.binding}, Slot{b, file, s.get()});
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
        const auto here = findDeclaration(*it->second.stage, m);
        const auto there = findDeclaration(*s, b);
        errors.push_back({here.first, here.second, "error",
                          "binding conflict at " + where + ": " + describe(m) + " here, but " + describe(b) +
                              " in " + there.first.string() + ":" + std::to_string(there.second)});
        errors.push_back({there.first, there.second, "error",
                          "binding conflict at " + where + ": " + describe(b) + " here, but " + describe(m) +
                              " in " + here.first.string() + ":" + std::to_string(here.second)});
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
