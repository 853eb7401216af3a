#include "scene/accessor_reader.h"

#include <algorithm>
#include <cstring>

namespace wb::scene {
namespace {

constexpr uint64_t kMaxElements = uint64_t{1} << 31;

int componentSize(int componentType) {
  switch (componentType) {
    case TINYGLTF_COMPONENT_TYPE_BYTE:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
      return 1;
    case TINYGLTF_COMPONENT_TYPE_SHORT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
      return 2;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
    case TINYGLTF_COMPONENT_TYPE_FLOAT:
      return 4;
    default:
      return 0;  // INT and DOUBLE are not glTF 2.0 accessor component types
  }
}

int componentCount(int type) {
  switch (type) {
    case TINYGLTF_TYPE_SCALAR:
      return 1;
    case TINYGLTF_TYPE_VEC2:
      return 2;
    case TINYGLTF_TYPE_VEC3:
      return 3;
    case TINYGLTF_TYPE_VEC4:
    case TINYGLTF_TYPE_MAT2:
      return 4;
    case TINYGLTF_TYPE_MAT3:
      return 9;
    case TINYGLTF_TYPE_MAT4:
      return 16;
    default:
      return 0;
  }
}

// A proven-in-bounds run of elements: element i, component j starts at base + i * stride + j * size.
struct ElementRun {
  const unsigned char* base = nullptr;
  size_t stride = 0;
  size_t count = 0;
  int componentType = 0;
  int components = 0;
};

// Locates `count` elements at `byteOffset` in bufferView `viewIndex`; `allowStride` is false for sparse data.
ElementRun locate(const LoadContext& ctx, int viewIndex, uint64_t byteOffset, uint64_t count,
                  int componentType, int components, bool allowStride, const std::string& what) {
  const tinygltf::Model& model = ctx.model();
  if (viewIndex < 0 || static_cast<size_t>(viewIndex) >= model.bufferViews.size()) {
    ctx.fail(what + " refers to bufferView " + std::to_string(viewIndex) + ", which does not exist (" +
             std::to_string(model.bufferViews.size()) + " bufferViews)");
  }
  const tinygltf::BufferView& view = model.bufferViews[static_cast<size_t>(viewIndex)];
  const uint64_t elementSize = static_cast<uint64_t>(componentSize(componentType)) * components;
  uint64_t stride = elementSize;
  if (allowStride && view.byteStride != 0) {
    stride = view.byteStride;
    if (stride < elementSize || stride > 252 ||
        stride % static_cast<uint64_t>(componentSize(componentType)) != 0) {
      ctx.fail(what + ": bufferView " + std::to_string(viewIndex) + " byteStride " + std::to_string(stride) +
               " is invalid for " + std::to_string(elementSize) + "-byte elements");
    }
  }
  if (count == 0 || count > kMaxElements) ctx.fail(what + ": invalid element count " + std::to_string(count));
  // All terms are below 2^31 * 252 + 2^32 or so, so the 64-bit sums cannot overflow.
  const uint64_t end = byteOffset + (count - 1) * stride + elementSize;
  if (byteOffset > view.byteLength || end > view.byteLength) {
    ctx.fail(what + ": " + std::to_string(count) + " elements at byteOffset " + std::to_string(byteOffset) +
             " (stride " + std::to_string(stride) + ") need " + std::to_string(end) +
             " bytes but bufferView " + std::to_string(viewIndex) + " has " +
             std::to_string(view.byteLength));
  }
  // The bufferView itself was checked against its buffer by validateBufferViewsAndAccessors.
  const tinygltf::Buffer& buffer = model.buffers[static_cast<size_t>(view.buffer)];
  ElementRun run;
  run.base = buffer.data.data() + view.byteOffset + byteOffset;
  run.stride = static_cast<size_t>(stride);
  run.count = static_cast<size_t>(count);
  run.componentType = componentType;
  run.components = components;
  return run;
}

double readComponent(const unsigned char* p, int componentType, bool normalized) {
  switch (componentType) {
    case TINYGLTF_COMPONENT_TYPE_BYTE: {
      int8_t v;
      std::memcpy(&v, p, 1);
      return normalized ? std::max(v / 127.0, -1.0) : v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: {
      uint8_t v;
      std::memcpy(&v, p, 1);
      return normalized ? v / 255.0 : v;
    }
    case TINYGLTF_COMPONENT_TYPE_SHORT: {
      int16_t v;
      std::memcpy(&v, p, 2);
      return normalized ? std::max(v / 32767.0, -1.0) : v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
      uint16_t v;
      std::memcpy(&v, p, 2);
      return normalized ? v / 65535.0 : v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: {
      uint32_t v;
      std::memcpy(&v, p, 4);
      return normalized ? v / 4294967295.0 : v;
    }
    default: {
      float v;
      std::memcpy(&v, p, 4);
      return v;
    }
  }
}

std::string accessorName(int index) {
  return "accessor " + std::to_string(index);
}

const tinygltf::Accessor& accessorAt(const LoadContext& ctx, int index, const std::string& what) {
  const auto& accessors = ctx.model().accessors;
  if (index < 0 || static_cast<size_t>(index) >= accessors.size()) {
    ctx.fail(what + " refers to accessor " + std::to_string(index) + ", which does not exist (" +
             std::to_string(accessors.size()) + " accessors)");
  }
  return accessors[static_cast<size_t>(index)];
}

struct SparseRuns {
  ElementRun indices, values;
};

SparseRuns locateSparse(const LoadContext& ctx, const tinygltf::Accessor& accessor, const std::string& what) {
  const auto& sparse = accessor.sparse;
  const int indexType = sparse.indices.componentType;
  if (indexType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE &&
      indexType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
      indexType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT) {
    ctx.fail(what + ": sparse indices have invalid componentType " + std::to_string(indexType));
  }
  if (sparse.count <= 0 || static_cast<size_t>(sparse.count) > accessor.count) {
    ctx.fail(what + ": sparse count " + std::to_string(sparse.count) + " not in [1, " +
             std::to_string(accessor.count) + "]");
  }
  if (sparse.indices.byteOffset < 0 || sparse.values.byteOffset < 0)
    ctx.fail(what + ": negative sparse byteOffset");
  SparseRuns runs;
  runs.indices = locate(ctx, sparse.indices.bufferView, static_cast<uint64_t>(sparse.indices.byteOffset),
                        static_cast<uint64_t>(sparse.count), indexType, 1, false, what + " sparse indices");
  runs.values = locate(ctx, sparse.values.bufferView, static_cast<uint64_t>(sparse.values.byteOffset),
                       static_cast<uint64_t>(sparse.count), accessor.componentType,
                       componentCount(accessor.type), false, what + " sparse values");
  return runs;
}

// Checks the accessor's own fields and locates its dense data (base null when it has no bufferView).
ElementRun locateAccessor(const LoadContext& ctx, const tinygltf::Accessor& accessor,
                          const std::string& what) {
  if (componentSize(accessor.componentType) == 0) {
    ctx.fail(what + " has invalid componentType " + std::to_string(accessor.componentType));
  }
  const int components = componentCount(accessor.type);
  if (components == 0) ctx.fail(what + " has invalid type " + std::to_string(accessor.type));
  if (accessor.count == 0 || accessor.count > kMaxElements) {
    ctx.fail(what + " has invalid count " + std::to_string(accessor.count));
  }
  ElementRun run;
  run.count = accessor.count;
  run.componentType = accessor.componentType;
  run.components = components;
  if (accessor.bufferView >= 0) {
    run = locate(ctx, accessor.bufferView, accessor.byteOffset, accessor.count, accessor.componentType,
                 components, true, what);
  } else if (!accessor.sparse.isSparse && accessor.bufferView != -1) {
    ctx.fail(what + " has invalid bufferView " + std::to_string(accessor.bufferView));
  }
  return run;
}

std::vector<double> readAccessor(const LoadContext& ctx, int index, const std::string& what) {
  const tinygltf::Accessor& accessor = accessorAt(ctx, index, what);
  const std::string name = what + " (" + accessorName(index) + ")";
  const ElementRun run = locateAccessor(ctx, accessor, name);
  const size_t components = static_cast<size_t>(run.components);
  const int size = componentSize(run.componentType);
  std::vector<double> values(run.count * components, 0.0);  // no bufferView: zeros (spec)
  if (run.base) {
    for (size_t i = 0; i < run.count; ++i) {
      const unsigned char* element = run.base + i * run.stride;
      for (size_t j = 0; j < components; ++j) {
        values[i * components + j] =
            readComponent(element + j * size, run.componentType, accessor.normalized);
      }
    }
  }
  if (accessor.sparse.isSparse) {
    const SparseRuns sparse = locateSparse(ctx, accessor, name);
    for (size_t k = 0; k < sparse.indices.count; ++k) {
      const double target =
          readComponent(sparse.indices.base + k * sparse.indices.stride, sparse.indices.componentType, false);
      if (target >= static_cast<double>(run.count)) {
        ctx.fail(name + ": sparse index " + std::to_string(static_cast<uint64_t>(target)) + " >= count " +
                 std::to_string(run.count));
      }
      const size_t i = static_cast<size_t>(target);
      const unsigned char* element = sparse.values.base + k * sparse.values.stride;
      for (size_t j = 0; j < components; ++j) {
        values[i * components + j] =
            readComponent(element + j * size, run.componentType, accessor.normalized);
      }
    }
  }
  return values;
}

}  // namespace

void validateBufferViewsAndAccessors(const LoadContext& ctx) {
  const tinygltf::Model& model = ctx.model();
  for (size_t i = 0; i < model.bufferViews.size(); ++i) {
    const tinygltf::BufferView& view = model.bufferViews[i];
    const std::string name = "bufferView " + std::to_string(i);
    if (view.buffer < 0 || static_cast<size_t>(view.buffer) >= model.buffers.size()) {
      ctx.fail(name + " refers to buffer " + std::to_string(view.buffer) + ", which does not exist (" +
               std::to_string(model.buffers.size()) + " buffers)");
    }
    const size_t bufferSize = model.buffers[static_cast<size_t>(view.buffer)].data.size();
    if (view.byteLength == 0 || view.byteOffset > bufferSize ||
        view.byteLength > bufferSize - view.byteOffset) {
      ctx.fail(name + " (byteOffset " + std::to_string(view.byteOffset) + ", byteLength " +
               std::to_string(view.byteLength) + ") lies outside buffer " + std::to_string(view.buffer) +
               " of " + std::to_string(bufferSize) + " bytes");
    }
  }
  for (size_t i = 0; i < model.accessors.size(); ++i) {
    const tinygltf::Accessor& accessor = model.accessors[i];
    const std::string name = accessorName(static_cast<int>(i));
    locateAccessor(ctx, accessor, name);
    if (accessor.sparse.isSparse) locateSparse(ctx, accessor, name);
  }
}

std::vector<float> readFloatAccessor(const LoadContext& ctx, int accessorIndex, int components,
                                     const std::string& what) {
  const tinygltf::Accessor& accessor = accessorAt(ctx, accessorIndex, what);
  if (componentCount(accessor.type) != components || accessor.type == TINYGLTF_TYPE_MAT2) {
    ctx.fail(what + " (" + accessorName(accessorIndex) + ") must have " + std::to_string(components) +
             " components, has type " + std::to_string(accessor.type));
  }
  const std::vector<double> values = readAccessor(ctx, accessorIndex, what);
  return std::vector<float>(values.begin(), values.end());
}

std::vector<uint32_t> readIndexAccessor(const LoadContext& ctx, int accessorIndex, const std::string& what) {
  const tinygltf::Accessor& accessor = accessorAt(ctx, accessorIndex, what);
  const int type = accessor.componentType;
  if (accessor.type != TINYGLTF_TYPE_SCALAR || accessor.normalized ||
      (type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE && type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
       type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)) {
    ctx.fail(what + " (" + accessorName(accessorIndex) +
             ") must be SCALAR unsigned byte/short/int, has componentType " + std::to_string(type));
  }
  const std::vector<double> values = readAccessor(ctx, accessorIndex, what);
  std::vector<uint32_t> indices(values.size());
  for (size_t i = 0; i < values.size(); ++i) indices[i] = static_cast<uint32_t>(values[i]);
  return indices;
}

}  // namespace wb::scene
