// The pass list's validator (a read before its write, an output nobody writes), and the
// denoiser's and timewarp's lists: that they validate, run in the order they declare, and
// name the resources their shaders use (the temporal pass reads last frame's history, each
// a-trous iteration what the previous one wrote, the panel pass the tile bounds).
#include <algorithm>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "gl/denoiser.h"
#include "gl/pass_list.h"
#include "gl/timewarp.h"
#include "hmd/lens.h"
#include "tests/gl/denoiser_test_util.h"
#include "tests/gl/gl_test_util.h"

namespace photovr {
namespace {

using gl::PassDecl;
using gl::PassList;

bool has(const std::vector<std::string>& names, const std::string& name) {
  return std::find(names.begin(), names.end(), name) != names.end();
}

std::vector<std::string> names(const PassList& list) {
  std::vector<std::string> out;
  for (const PassDecl& p : list.passes()) out.push_back(p.name);
  return out;
}

// The logic_error's message, or "" when 'make' does not throw one.
template <typename F>
std::string logicError(F&& make) {
  try {
    make();
  } catch (const std::logic_error& e) {
    return e.what();
  }
  return "";
}

TEST(PassList, RunsValidPassesInTheirOrder) {
  std::vector<std::string> ran;
  const PassList list({"in"}, {"out"},
                      {{"a", {"in"}, {"mid"}, [&] { ran.push_back("a"); }},
                       {"b", {"mid", "in"}, {"out"}, [&] { ran.push_back("b"); }}});
  list.run();
  EXPECT_EQ(ran, (std::vector<std::string>{"a", "b"}));
  EXPECT_EQ(list.writer("mid", 1), 0);
  EXPECT_EQ(list.writer("mid", 0), -1);  // only passes before the one asked about count
  EXPECT_EQ(list.writer("in", 2), -1);   // external
}

TEST(PassList, RejectsAReadBeforeItsWrite) {
  const std::string what = logicError([] {
    PassList({"in"}, {"out"},
             {{"first", {"in", "late"}, {"out"}, [] {}}, {"second", {"in"}, {"late"}, [] {}}});
  });
  EXPECT_NE(what.find("pass 0 'first'"), std::string::npos) << what;
  EXPECT_NE(what.find("'late'"), std::string::npos) << what;
  // A pass reading its own output has not had it written before it either.
  EXPECT_NE(logicError([] { PassList({}, {"x"}, {{"self", {"x"}, {"x"}, [] {}}}); }), "");
}

TEST(PassList, RejectsAnOutputNoPassWrites) {
  const std::string what = logicError([] {
    PassList({"in"}, {"out", "forgotten"}, {{"only", {"in"}, {"out"}, [] {}}});
  });
  EXPECT_NE(what.find("'forgotten'"), std::string::npos) << what;
  // An external input is not an output someone wrote.
  EXPECT_NE(logicError([] { PassList({"in"}, {"in"}, {}); }), "");
}

TEST(PassList, RejectsAPassWithNothingToRun) {
  const std::string what = logicError([] { PassList({}, {"x"}, {{"empty", {}, {"x"}, {}}}); });
  EXPECT_NE(what.find("pass 0 'empty'"), std::string::npos) << what;
}

// For every a-trous iteration: its colour input is what the pass just before it wrote (the
// firefly clamp or the previous iteration), and the resolve reads the last one's composite.
void expectFilterChain(const PassList& list, const std::string& firstInput) {
  const auto& p = list.passes();
  std::vector<size_t> atrous = list.find("atrous");
  const std::vector<size_t> last = list.find("atrous+composite");
  ASSERT_EQ(last.size(), 1u);
  atrous.push_back(last[0]);
  std::string previous = firstInput;
  for (size_t k = 0; k < atrous.size(); ++k) {
    const size_t i = atrous[k];
    const std::string out = "atrous" + std::to_string(k);
    EXPECT_TRUE(has(p[i].reads, previous)) << "iteration " << k << " reads " << previous;
    EXPECT_EQ(list.writer(previous, i), int(i) - 1) << "iteration " << k;
    EXPECT_TRUE(has(p[i].writes, out)) << "iteration " << k;
    previous = out;
  }
  const std::vector<size_t> resolve = list.find("resolve");
  ASSERT_EQ(resolve.size(), 1u);
  EXPECT_EQ(list.writer("composited", resolve[0]), int(last[0]));
  EXPECT_TRUE(has(p[resolve[0]].reads, "prev.resolveHistory"));
}

TEST(PassList, DenoiserDefaultListsNameTheirResources) {
  testing::osmesaContext();
  const gl::Denoiser dn(8, 6);
  const PassList& full = dn.passes(gl::DenoiseMode::Full);
  // The names benches record (DenoiseParams defaults: firefly clamp, 5 iterations).
  EXPECT_EQ(names(full),
            (std::vector<std::string>{"upload", "temporal", "firefly", "atrous", "atrous", "atrous",
                                      "atrous", "atrous+composite", "resolve"}));
  const PassDecl& temporal = full.passes()[1];
  for (const char* r : {"prev.history", "prev.geometry", "prev.aux", "prev.moments", "noisy",
                        "gbuffer.motion", "gbuffer.depth"})
    EXPECT_TRUE(has(temporal.reads, r)) << r;
  EXPECT_TRUE(has(full.inputs(), "prev.history"));
  EXPECT_TRUE(has(full.outputs(), "history"));
  // The history is the temporal output after the clamp (DenoiseParams::
  // historyFromFirstIteration), not the first iteration's.
  EXPECT_EQ(full.writer("history", full.passes().size()), 2);
  EXPECT_TRUE(has(full.passes()[2].reads, "temporal"));
  expectFilterChain(full, "firefly");

  const PassList& temporalOnly = dn.passes(gl::DenoiseMode::Temporal);
  EXPECT_EQ(names(temporalOnly), (std::vector<std::string>{"upload", "temporal", "composite"}));
  EXPECT_EQ(temporalOnly.writer("history", 3), 1);
  const PassList& off = dn.passes(gl::DenoiseMode::Off);
  EXPECT_EQ(names(off), (std::vector<std::string>{"upload", "composite"}));
  EXPECT_TRUE(has(off.passes()[1].reads, "noisy"));
  EXPECT_FALSE(has(off.outputs(), "history"));  // 'off' does not maintain it
}

TEST(PassList, DenoiserListsFollowTheParameters) {
  testing::osmesaContext();
  gl::Denoiser dn(8, 6);
  gl::DenoiseParams p;
  p.historyFromFirstIteration = true;  // SVGF's arrangement
  p.iterations = 3;
  dn.setParams(p);
  const PassList& svgf = dn.passes(gl::DenoiseMode::Full);
  EXPECT_EQ(names(svgf), (std::vector<std::string>{"upload", "temporal", "firefly", "atrous",
                                                   "atrous", "atrous+composite", "resolve"}));
  EXPECT_EQ(svgf.writer("history", svgf.passes().size()), 3);  // the first iteration
  expectFilterChain(svgf, "firefly");
  p.suppressFireflies = false;
  dn.setParams(p);
  expectFilterChain(dn.passes(gl::DenoiseMode::Full), "temporal");
  p.iterations = 0;  // 'full' without a filter is 'temporal'
  dn.setParams(p);
  EXPECT_EQ(names(dn.passes(gl::DenoiseMode::Full)),
            (std::vector<std::string>{"upload", "temporal", "composite"}));
}

TEST(PassList, DenoiserTimingsAreItsPasses) {
  testing::osmesaContext();
  const int w = 8, h = 6;
  testing::SyntheticFrame f(w, h);
  testing::SyntheticGBuffer gbuffer(w, h);
  gbuffer.upload(f);
  gl::Denoiser dn(w, h);
  dn.setTiming(true);
  for (gl::DenoiseMode mode :
       {gl::DenoiseMode::Off, gl::DenoiseMode::Temporal, gl::DenoiseMode::Full}) {
    dn.run(gbuffer.geometry(), f.eyes(), 2, mode, false);
    std::vector<std::string> timed;
    for (const gl::PassTiming& t : dn.timings()) timed.push_back(t.name);
    EXPECT_EQ(timed, names(dn.passes(mode))) << gl::denoiseModeName(mode);
  }
}

TEST(PassList, TimewarpListsNameTheSearchBounds) {
  testing::osmesaContext();
  hmd::LensModel m;
  m.panel.hResolution = 192;
  m.panel.vResolution = 108;
  const gl::Timewarp tw(hmd::flattenLens(m), 48, 54,
                        {FovTangents::dk2LeftEye(), FovTangents::dk2LeftEye().mirrored()});
  const PassList& panel = tw.passes(gl::TimewarpRun::Panel);
  EXPECT_EQ(names(panel), (std::vector<std::string>{"tileRange", "tileBound", "panel"}));
  EXPECT_EQ(panel.writer("tileRange", 1), 0);
  EXPECT_EQ(panel.writer("tileBound", 2), 1);
  for (const char* r : {"color", "depth", "tileBound", "lensTable", "lensGroups"})
    EXPECT_TRUE(has(panel.passes()[2].reads, r)) << r;
  const PassList& eyes = tw.passes(gl::TimewarpRun::Eyes);
  EXPECT_EQ(names(eyes), (std::vector<std::string>{"tileRange", "tileBound", "eyes"}));
  EXPECT_EQ(eyes.writer("tileBound", 2), 1);
  EXPECT_EQ(eyes.outputs(), (std::vector<std::string>{"eyeColor", "eyeDepth", "stats"}));
  // Without re-projection the frame's depth is not read, and there is nothing to search.
  const PassList& asRendered = tw.passes(gl::TimewarpRun::PanelAsRendered);
  ASSERT_EQ(asRendered.passes().size(), 1u);
  EXPECT_FALSE(has(asRendered.passes()[0].reads, "depth"));
  EXPECT_EQ(names(tw.passes(gl::TimewarpRun::PanelFloor)),
            (std::vector<std::string>{"panelFloor"}));
}

}  // namespace
}  // namespace photovr
