// Work a scene does not need, and the switch that turns each skip off (issue 7, item 3).
//
// photovr decides at load what a scene needs (core/scene_info.h analyzeScene; `photovr info`
// prints it) and the modules leave out the rest. Each skip is a flag here, on by default;
// turning one off (`--no-skip NAME,...`) makes the renderer do the generic work a renderer
// without the analysis would do, so tests can show a skip changes nothing but the time
// (tests/trace/work_skips_test.cpp, tests/hybrid/) and bench/bench_skips.cpp what it saves.
#pragma once

#include <string>
#include <vector>

namespace photovr {

struct WorkSkips {
  // No punctual light: none is sampled and no shadow ray is cast for one. Off: a dark
  // stand-in point light at the scene centre takes a typical share of light samples,
  // each with its shadow ray (a renderer that cannot know a light is dark must test it).
  bool punctualLights = true;
  // No emissive triangle: no area-light sampling. Off: a dark stand-in area light.
  bool areaLights = true;
  // No environment: it is not sampled (misses are black). Off: a black environment is
  // sampled uniformly over the sphere like any other light, shadow ray included.
  bool environment = true;
  // Meshes without a MASK or BLEND material get no any-hit filter (a single-sided mesh's
  // back faces are culled for camera rays by a filter in their context alone). Off: the
  // alpha filter is installed on every mesh and runs for every candidate hit.
  bool anyHitFilter = true;
  // A static scene's BVH is never refit. Off: the top level is re-committed every frame,
  // as a renderer that cannot tell a static scene from a moving one must.
  bool refit = true;
  // Hybrid: pixels the G-buffer saw no surface in take the environment directly. Off: their
  // primary ray is traced by Embree first.
  bool skyPixels = true;
  // Emissive triangles are light-sampled in proportion to the power their emissive texture
  // gives them, and those black under it not at all (trace/lights.cpp, meanEmission). Off:
  // every emissive triangle is sampled by its emission factor x area, texture unseen.
  bool darkEmitters = true;

  // Every skip by its command-line name, with its flag.
  static std::vector<std::string> names();
  bool* flag(const std::string& name);  // null for an unknown name
  // "all" turns every skip off; else a comma-separated list of names. Throws
  // std::invalid_argument naming the unknown entry.
  void disable(const std::string& list);
};

}  // namespace photovr
