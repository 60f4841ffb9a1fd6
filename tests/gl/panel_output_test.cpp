// The panel output pass against the CPU display transform (core/tonemap.cpp) and the
// rotation rule (gl/panel_output.h panelSourceTexel) on a tiny image, every rotation.
#include <cmath>
#include <cstdlib>
#include <limits>
#include <vector>

#include <gtest/gtest.h>

#include "core/error.h"
#include "core/tonemap.h"
#include "gl/gl_api.h"
#include "gl/panel_output.h"
#include "tests/gl/gl_test_util.h"

namespace photovr {
namespace {

constexpr int kW = 5, kH = 3;  // odd, non-square: a wrong rotation or transpose shows

// Values across the tone curve: dark (sRGB's linear toe), mid, the shoulder above 0.76,
// far above 1, negative and NaN (shown black).
std::vector<glm::vec4> testPanel() {
  std::vector<glm::vec4> v;
  for (int i = 0; i < kW * kH; ++i) {
    const float t = float(i) / (kW * kH - 1);
    v.emplace_back(0.002f + 3.0f * t * t, 0.5f * t, 1.5f - t, 1.0f);
  }
  v[3].g = -0.5f;
  v[7].b = std::numeric_limits<float>::quiet_NaN();
  return v;
}

unsigned uploadPanel(const std::vector<glm::vec4>& v) {
  GLuint t = 0;
  gl::api::CreateTextures(GL_TEXTURE_2D, 1, &t);
  gl::api::TextureStorage2D(t, 1, GL_RGBA32F, kW, kH);
  gl::api::PixelStorei(GL_UNPACK_ALIGNMENT, 4);
  gl::api::TextureSubImage2D(t, 0, 0, 0, kW, kH, GL_RGBA, GL_FLOAT, v.data());
  return t;
}

TEST(PanelOutput, MatchesTheCpuDisplayTransformAtEveryRotation) {
  testing::osmesaContext();
  const std::vector<glm::vec4> panel = testPanel();
  const unsigned tex = uploadPanel(panel);
  const float exposure = 1.3f;
  for (int rotation : {0, 90, 180, 270}) {
    gl::PanelOutput out(kW, kH, rotation);
    out.run(tex, exposure);
    const glm::ivec2 size = gl::rotatedSize(rotation, kW, kH);
    ASSERT_EQ(out.width(), size.x);
    ASSERT_EQ(out.height(), size.y);
    const auto got = out.read();
    int worst = 0;
    for (int y = 0; y < size.y; ++y)
      for (int x = 0; x < size.x; ++x) {
        const glm::ivec2 s = gl::panelSourceTexel(rotation, kW, kH, x, y);
        ASSERT_TRUE(s.x >= 0 && s.x < kW && s.y >= 0 && s.y < kH);
        const glm::u8vec3 want = displayColor(glm::vec3(panel[s.y * kW + s.x]), exposure);
        const glm::u8vec4 g = got[size_t(y) * size.x + x];
        for (int k = 0; k < 3; ++k) worst = std::max(worst, std::abs(int(g[k]) - int(want[k])));
        EXPECT_EQ(g.a, 255);
      }
    // One 8-bit step: GL's pow/division in float may round a value sitting on a .5
    // boundary the other way than std::pow; any logic error moves values by far more.
    EXPECT_LE(worst, 1) << "rotation " << rotation;
  }
  gl::api::DeleteTextures(1, &tex);
}

TEST(PanelOutput, Dk2RotationPutsTheRightEyeOnTheFirstNativeRows) {
  // dk2.md §5: native(xp, yp) = (y, 1919 - x), right eye on native rows 0-959.
  for (int x : {0, 959, 960, 1919})
    for (int y : {0, 1079}) {
      const glm::ivec2 native(y, 1919 - x);
      EXPECT_EQ(gl::panelSourceTexel(90, 1920, 1080, native.x, native.y), glm::ivec2(x, y));
      EXPECT_EQ(native.y < 960, x >= 960);
    }
  EXPECT_EQ(gl::rotatedSize(90, 1920, 1080), glm::ivec2(1080, 1920));
}

TEST(PanelOutput, RejectsOtherRotations) {
  EXPECT_THROW(gl::checkPanelRotation(45), UsageError);
  EXPECT_EQ(gl::checkPanelRotation(270), 270);
}

}  // namespace
}  // namespace photovr
