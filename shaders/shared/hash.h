// Integer hashes shared by shaders and CPU tests (GLSL and C++, see glsl_cpp.h).
#ifndef WB_HASH_H
#define WB_HASH_H
#include "glsl_cpp.h"

WB_NAMESPACE_BEGIN

// Jarzynski & Olano 2020, "Hash Functions for GPU Rendering", JCGT 9(3): the PCG hash (RXS-M-XS output).
WB_FN uint pcgHash(uint v) {
  uint state = v * 747796405u + 2891336453u;
  uint word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
  return (word >> 22u) ^ word;
}

// Folds v into the running hash h (boost's combine, then a PCG step): hashes of several integers, e.g. pixel,
// sample and primitive for stochastic transparency.
WB_FN uint hashCombine(uint h, uint v) {
  h ^= v + 0x9e3779b9u + (h << 6u) + (h >> 2u);
  h = h * 747796405u + 2891336453u;
  return ((h >> ((h >> 28u) + 4u)) ^ h) * 277803737u;
}

WB_NAMESPACE_END

#endif
