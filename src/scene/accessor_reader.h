// Bounds-checked reading of glTF accessors (any component type, byteStride, sparse substitution). Every byte
// read is first proven to lie inside its bufferView and buffer; anything else throws SceneError.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "scene/load_context.h"

namespace wb::scene {

// Checks every bufferView's range against its buffer and every accessor against its bufferView(s).
void validateBufferViewsAndAccessors(const LoadContext& ctx);

// Returns count * components floats (normalized integer types mapped per the glTF spec, other integers
// converted as is). Throws when the accessor does not have exactly `components` components.
std::vector<float> readFloatAccessor(const LoadContext& ctx, int accessorIndex, int components,
                                     const std::string& what);

// Reads an index accessor (SCALAR unsigned byte/short/int, not normalized).
std::vector<uint32_t> readIndexAccessor(const LoadContext& ctx, int accessorIndex, const std::string& what);

}  // namespace wb::scene
