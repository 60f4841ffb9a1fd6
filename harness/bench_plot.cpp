// The bench's plots: bench/plot.gp run by gnuplot on the CSV files of a run.

#include <cstdlib>
#include <filesystem>
#include <iostream>

#include "harness/bench_report.h"

namespace photovr::harness {
namespace {

// bench/plot.gp from the working folder (a source checkout), else from the parent of the
// executable's folder (the build folder inside the checkout).
std::string findPlotScript() {
  namespace fs = std::filesystem;
  if (fs::exists("bench/plot.gp")) return "bench/plot.gp";
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  for (fs::path dir = exe.parent_path(); !ec && !dir.empty() && dir != dir.parent_path();
       dir = dir.parent_path())
    if (fs::exists(dir / "bench/plot.gp")) return (dir / "bench/plot.gp").string();
  return "";
}

}  // namespace

bool plot(const std::string& dir) {
  if (std::system("command -v gnuplot >/dev/null 2>&1") != 0) {
    std::cout << "gnuplot not installed: no plots (the CSV files have the data)\n";
    return false;
  }
  const std::string script = findPlotScript();
  if (script.empty()) {
    std::cout << "bench/plot.gp not found: run gnuplot -e \"dir='" << dir
              << "'\" bench/plot.gp from the source folder\n";
    return false;
  }
  const std::string cmd = "gnuplot -e \"dir='" + dir + "'\" " + script;
  if (std::system(cmd.c_str()) != 0) {
    std::cout << "gnuplot failed: " << cmd << "\n";
    return false;
  }
  std::cout << "wrote " << dir << "/bench_error_vs_time.png and bench_stages.png\n";
  return true;
}

}  // namespace photovr::harness
