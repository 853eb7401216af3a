// bench's roofline keys (app/bench_roofline.h) on the default scene: every bare rate and the path tracer's
// rate are there and positive, each rate is its rays per launch over its time per launch, and the ratio is
// the path tracer's rate over the bare diffuse rate and over the bare paths' rate.
#include <gtest/gtest.h>

#include "app/bench_roofline.h"
#include "render/render_session.h"

using namespace wb;

TEST(BenchRoofline, ReportsTheBareRatesAndThePathTracersRatioToThem) {
  render::SessionOptions o;
  o.settings.width = o.settings.height = 32;
  o.context.validation = true;
  o.quiet = true;
  render::RenderSession s(o);
  const auto j = app::benchRoofline(s, 1);
  for (const char* kind : {"primary", "diffuse", "shadow", "path"}) {
    const std::string k = std::string("bare_") + kind;
    ASSERT_TRUE(j.contains(k + "_rays_per_second")) << j.dump();
    const double rate = j[k + "_rays_per_second"].get<double>();
    EXPECT_GT(rate, 0.0) << kind;
    EXPECT_NEAR(rate * j[k + "_seconds_per_launch"].get<double>(), j[k + "_rays_per_launch"].get<double>(),
                1e-6 * rate)
        << kind;
  }
  EXPECT_EQ(j["bare_primary_rays_per_launch"].get<uint64_t>(), 32u * 32u);
  const double pt = j["pathtracer_gpu_rays_per_second"].get<double>();
  EXPECT_GT(pt, 0.0);
  EXPECT_NEAR(j["pathtracer_vs_bare_diffuse_ratio"].get<double>(),
              pt / j["bare_diffuse_rays_per_second"].get<double>(), 1e-9);
  EXPECT_NEAR(j["pathtracer_vs_bare_path_ratio"].get<double>(),
              pt / j["bare_path_rays_per_second"].get<double>(), 1e-9);
  // Bare paths trace at least the camera rays, and more where they hit.
  EXPECT_GT(j["bare_path_rays_per_launch"].get<uint64_t>(), 32u * 32u);
  EXPECT_EQ(s.context().validationErrors(), 0u);
}
