// Lets one header compile as GLSL (glslang) and as C++ (with GLM), so host and shaders share every struct that
// crosses the boundary and the CPU tests exercise the very sampling/BRDF code the shaders run.
// Rules for code in shared headers: no swizzles (write vec2(v.x, v.y)), parameters that are written use
// OUT(T)/INOUT(T), functions are declared WB_FN, float literals carry a decimal point.
#ifndef WB_GLSL_CPP_H
#define WB_GLSL_CPP_H

#ifdef __cplusplus
#include <cmath>
#include <cstdint>
#include <glm/glm.hpp>
#include <glm/gtc/type_ptr.hpp>
namespace wb::gpu {
using namespace glm;
using uint = std::uint32_t;
}  // namespace wb::gpu
#define WB_NAMESPACE_BEGIN namespace wb::gpu {
#define WB_NAMESPACE_END }
#define WB_FN inline
#define OUT(T) T&
#define INOUT(T) T&
#define WB_CONST constexpr
#else
#define WB_NAMESPACE_BEGIN
#define WB_NAMESPACE_END
#define WB_FN
#define OUT(T) out T
#define INOUT(T) inout T
#define WB_CONST const
#endif

#endif
