// Stereo reuse's split in lanes (trace/split_lanes.h) gives the scalar answerSplit's answers
// for every sample it takes: a split that is not whole, at a vertex without glass or layers.
#include "trace/split_lanes.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "trace/bsdf_stage.h"
#include "trace/path_stages.h"

namespace photovr {
namespace {

// A reused right sample at a random plain vertex facing anywhere: the left's record at a
// normal tens of degrees from the right's (a curved surface, a normal map), both views and
// the left's bounce random (some below a horizon), every flag sometimes off, and normals
// with z = +-0.
struct Case {
  FirstBounce left;
  PathState path;
  VertexShading vs;
  VertexNumbers u;
};

glm::vec3 unitNear(std::mt19937& rng, const glm::vec3& n, float spread) {
  std::normal_distribution<float> g(0.0f, spread);
  return glm::normalize(n + glm::vec3(g(rng), g(rng), g(rng)));
}

void makeCase(Case& c, std::mt19937& rng) {
  std::uniform_real_distribution<float> u01(0.0f, 1.0f);
  const bool flatZ = u01(rng) < 0.05f;  // orthonormalBasis's sign of +-0
  // Any direction: orthonormalBasis takes another branch for z < 0.
  glm::vec3 n = unitNear(rng, glm::vec3(0, 0, u01(rng) < 0.5f ? 1.0f : -1.0f), 1.5f);
  if (flatZ) n = glm::normalize(glm::vec3(n.x, n.y, 0.0f)), n.z = u01(rng) < 0.5f ? 0.0f : -0.0f;
  SurfaceHit& hit = c.path.hit;
  hit.shadingNormal = n;
  hit.geometricNormal = unitNear(rng, n, 0.1f);
  hit.bsdf.baseColor = glm::vec3(u01(rng), u01(rng), u01(rng));
  hit.bsdf.metallic = u01(rng) < 0.3f ? 1.0f : u01(rng);
  hit.bsdf.roughness = u01(rng) < 0.2f ? 0.0f : u01(rng);
  FirstBounce& b = c.left;
  b = FirstBounce{};
  b.normal = u01(rng) < 0.1f ? n : unitNear(rng, n, 0.3f);
  b.geometricNormal = unitNear(rng, b.normal, 0.1f);
  b.wo = unitNear(rng, b.normal, 0.8f);
  b.woAbove = u01(rng) < 0.9f;
  b.specularProbability = u01(rng);
  b.sampled = u01(rng) < 0.9f;
  b.dir = unitNear(rng, b.normal, 1.0f);
  b.pdf = 1.0f;
  c.path.wo = unitNear(rng, b.wo, 0.05f);
  c.path.reuse = &b;
  VertexShading& vs = c.vs;
  vs.frame.setZ(n);
  vs.wo = vs.frame.toLocal(c.path.wo);
  vs.bsdf = prepareBsdf(hit.bsdf, vs.wo);
  vs.reusing = b.sampled;
  vs.wiReused = vs.frame.toLocal(b.dir);
  vs.reused = evalBsdfAndPdf(vs.bsdf, vs.wiReused);
  c.u.bsdf = glm::vec2(u01(rng), u01(rng));
}

TEST(SplitLanes, AnswerAsTheScalarSplitDoes) {
  std::mt19937 rng(21);
  std::vector<Case> cases(2003);  // no multiple of 8: a partly filled last group runs too
  std::vector<SplitJob> jobs;
  std::vector<SplitAnswers> lanes(cases.size());
  for (Case& c : cases) makeCase(c, rng);
  for (size_t i = 0; i < cases.size(); ++i) {
    Case& c = cases[i];
    ASSERT_TRUE(plainBsdf(c.path.hit.bsdf));
    if (reusesWhole(c.left, c.path.hit, c.vs.bsdf, c.path.wo)) continue;  // not the lanes'
    jobs.push_back({&c.left, &c.vs.bsdf, &c.vs.frame, c.path.hit.geometricNormal, c.vs.reusing,
                    c.vs.reused.pdf, c.u.bsdf, &lanes[i]});
  }
  splitAnswers(jobs);
  size_t reused = 0, traced = 0;
  for (const SplitJob& job : jobs) {
    const size_t i = size_t(job.out - lanes.data());
    const SplitAnswers one = answerSplit(cases[i].path, cases[i].vs, cases[i].u);
    EXPECT_EQ(lanes[i].leftDirReused, one.leftDirReused) << i;
    EXPECT_EQ(lanes[i].ownTraced, one.ownTraced) << i;
    reused += one.leftDirReused;
    traced += one.ownTraced;
  }
  // Every branch ran: most splits are not whole, and each answer came out both ways.
  EXPECT_GT(jobs.size(), cases.size() * 3 / 4);
  EXPECT_GT(reused, 0u);
  EXPECT_LT(reused, jobs.size());
  EXPECT_GT(traced, 0u);
  EXPECT_LT(traced, jobs.size());
}

TEST(SplitLanes, NoJobsIsNothing) {
  splitAnswers({});
}

}  // namespace
}  // namespace photovr
