// GPU tests: a render session on the machine's device under the validation layer; any validation error fails.
#pragma once
#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "render/render_session.h"

namespace wb::testing {

inline std::unique_ptr<render::RenderSession> makeSession(render::SessionOptions o) {
  o.context.validation = true;
  return std::make_unique<render::RenderSession>(o);
}

inline void expectNoValidationErrors(render::RenderSession& s) {
  EXPECT_EQ(s.context().validationErrors(), 0u);
  for (const auto& m : s.context().validationMessages()) ADD_FAILURE() << "validation: " << m;
}

struct ImageStats {
  double mean[3] = {0, 0, 0};
  size_t nonFinite = 0;
  float maxValue = 0;
};

inline ImageStats imageStats(const eval::ImageRGBA& img) {
  ImageStats s;
  const size_t n = size_t(img.width) * img.height;
  for (size_t i = 0; i < n; ++i) {
    for (int c = 0; c < 3; ++c) {
      float v = img.pixels[4 * i + c];
      if (!std::isfinite(v)) {
        s.nonFinite++;
        continue;
      }
      s.mean[c] += v;
      s.maxValue = std::max(s.maxValue, v);
    }
  }
  for (double& m : s.mean) m /= double(n);
  return s;
}

}  // namespace wb::testing
