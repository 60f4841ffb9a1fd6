// photovr stress: the numerical stress suite at full size, with its report.
#include <iostream>

#include "app/commands.h"
#include "gl/render_context.h"
#include "core/options.h"
#include "core/error.h"
#include "hybrid/stress.h"

namespace photovr::app {

int runStress(const Args& args) {
  if (wantsHelp(args)) {
    std::cout << "usage: photovr stress [--quick] [--backend B]\n"
                 "Renders every numerical stress case (far from the origin, extreme scales,\n"
                 "degenerate triangles, denormals, roughness/metallic 0 and 1, a tiny bright\n"
                 "light, coincident surfaces) in hybrid and pt mode and prints the report:\n"
                 "NaN/Inf pixels, rejected samples, pixels off each case's expected images\n"
                 "(its well-conditioned twin), pixels where hybrid and pt differ. Exit\n"
                 "status 1 if a case fails.\n";
    return 0;
  }
  const Options o(args, {"--backend"}, {"--quick"});
  if (!o.positional().empty())
    throw UsageError("stress: unexpected argument '" + o.positional()[0] + "'");
  auto context = gl::createRenderContext(o.text("--backend", ""));
  const auto results = runStressSuite(o.has("--quick"));
  std::cout << formatStressReport(results);
  for (const StressResult& r : results)
    if (!r.passed) return 1;
  return 0;
}

}  // namespace photovr::app
