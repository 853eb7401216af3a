#include "app/bench_cost.h"

#include <memory>
#include <vector>

#include "app/debug_json.h"
#include "common/statistics.h"
#include "render/render_session.h"

namespace wb::app {

using nlohmann::json;

json benchCostVariants(uint32_t width, uint32_t height, uint32_t spp, int repeats, const std::string& device,
                       std::string& deviceName, std::string& driver) {
  struct Variant {
    const char* name;
    std::unique_ptr<render::RenderSession> session;
    std::vector<double> seconds, pathtracerMs;
  };
  std::vector<Variant> variants;
  for (const char* name : {"default", "cost", "inspect", "asserts"}) {
    render::SessionOptions o;
    o.settings.width = width;
    o.settings.height = height;
    o.settings.aov = true;  // the cost and inefficiency views read the AOVs
    o.context.deviceName = device;
    o.quiet = true;
    Variant v{name, std::make_unique<render::RenderSession>(o), {}, {}};
    auto& tracer = v.session->pathTracer();
    const std::string n = name;
    if (n == "cost" || n == "asserts") {
      render::Instrumentation i;
      i.cost = n == "cost";
      i.asserts = n == "asserts";
      tracer.setInstrumentation(i);
    } else if (n == "inspect") {
      render::InspectRequest r;
      r.x = width / 2;
      r.y = height / 2;
      r.samples = spp;
      tracer.setInspection(r);
    }
    v.session->render(1);  // warm-up: the driver compiles the pipeline at its first trace
    deviceName = v.session->context().deviceName();
    driver = v.session->context().driverInfo();
    variants.push_back(std::move(v));
  }
  // Alternated, so that a busy spell of the machine falls on every variant alike.
  for (int r = 0; r < repeats; ++r) {
    for (auto& v : variants) {
      v.seconds.push_back(v.session->render(spp) / spp);
      const auto ms = v.session->renderer().passTimer()->medians();
      v.pathtracerMs.push_back(ms.empty() ? 0.0 : ms.front().ms);
    }
  }
  const double base = median(variants.front().seconds);
  const double baseGpu = median(variants.front().pathtracerMs);
  json rows = json::array();
  for (auto& v : variants) {
    const double s = median(v.seconds), gpu = median(v.pathtracerMs);
    json row = {{"variant", v.name},
                {"seconds_per_sample", s},
                {"overhead", base > 0 ? s / base - 1.0 : 0.0},
                {"pass_ms", passMsJson(v.session->renderer().passTimer())},
                {"pathtracer_gpu_overhead", baseGpu > 0 ? gpu / baseGpu - 1.0 : 0.0}};
    if (std::string(v.name) == "cost") {
      const auto& t = v.session->pathTracer();
      row["cost"] = costJson(t.summarizeCost(t.readAov(render::Aov::Cost)));
    }
    rows.push_back(row);
  }
  return {{"size", std::to_string(width) + "x" + std::to_string(height)},
          {"spp", spp},
          {"repeats", repeats},
          {"scene", "default"},
          {"variants", rows},
          {"what",
           "seconds per sample (median of alternated runs) of the path tracer's variants on the default "
           "scene; overhead = variant / default - 1; inspect records the centre pixel"}};
}

}  // namespace wb::app
