// panelDifference (core/error_metrics.h): the mean is over the RGB of the pixels both
// panels show, and black (outside the lens, or nothing in the frame) is counted apart.
#include <gtest/gtest.h>

#include "core/error_metrics.h"

namespace photovr {
namespace {

TEST(PanelDifference, MeanIsOverThePixelsBothShow) {
  const glm::u8vec4 black(0, 0, 0, 255);
  const std::vector<glm::u8vec4> a = {{10, 20, 30, 255}, {100, 100, 100, 255}, black, black};
  const std::vector<glm::u8vec4> b = {
      {13, 20, 30, 255}, {100, 94, 100, 255}, {50, 50, 50, 255}, black};
  const PanelDifference d = panelDifference(a, b);
  EXPECT_EQ(d.shown, 2);
  EXPECT_EQ(d.blackInOne, 1);  // the third pixel; the fourth is black in both
  EXPECT_EQ(d.maxLevels, 6);
  EXPECT_DOUBLE_EQ(d.meanLevels, (3.0 + 6.0) / 6.0);  // 6 channels of 2 pixels
}

TEST(PanelDifference, IdenticalPanelsDifferByNothing) {
  const std::vector<glm::u8vec4> a = {{1, 2, 3, 255}, {0, 0, 0, 255}, {255, 255, 255, 255}};
  const PanelDifference d = panelDifference(a, a);
  EXPECT_EQ(d.shown, 2);
  EXPECT_EQ(d.blackInOne, 0);
  EXPECT_EQ(d.maxLevels, 0);
  EXPECT_EQ(d.meanLevels, 0.0);
}

TEST(PanelDifference, NothingShownIsNoDifference) {
  const std::vector<glm::u8vec4> a(4, glm::u8vec4(0, 0, 0, 255));
  const PanelDifference d = panelDifference(a, a);
  EXPECT_EQ(d.shown, 0);
  EXPECT_EQ(d.meanLevels, 0.0);
}

}  // namespace
}  // namespace photovr
