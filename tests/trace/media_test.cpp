// The medium stack (trace/media.h): which volume a path is in, and what lies outside it.
#include "trace/media.h"

#include <gtest/gtest.h>

namespace photovr {
namespace {

TEST(MediumStack, EntersAndLeavesInNestingOrder) {
  MediumStack m;
  EXPECT_EQ(m.current(), MediumStack::kNone);  // air
  m.enter(7);                                  // into the glass of water ...
  m.enter(3);                                  // ... and the ice in it
  EXPECT_EQ(m.current(), 3u);
  EXPECT_EQ(m.outsideOf(3), 7u);  // leaving the ice: the water
  EXPECT_EQ(m.outsideOf(7), 3u);  // the innermost other medium
  m.leave(3);
  EXPECT_EQ(m.current(), 7u);
  EXPECT_EQ(m.outsideOf(7), MediumStack::kNone);
  m.leave(7);
  EXPECT_EQ(m.size, 0);
}

TEST(MediumStack, LeavingOutOfOrderOrWhatWasNeverEnteredKeepsTheRest) {
  MediumStack m;
  m.enter(1), m.enter(2), m.enter(3);
  m.leave(2);  // overlapping volumes: the middle one is left first
  EXPECT_EQ(m.size, 2);
  EXPECT_EQ(m.instance[0], 1u);
  EXPECT_EQ(m.instance[1], 3u);
  m.leave(9);  // never entered (a path that started inside): nothing changes
  EXPECT_EQ(m.size, 2);
}

TEST(MediumStack, DeeperNestingThanItsDepthIsNotTracked) {
  MediumStack m;
  for (uint32_t k = 0; k < MediumStack::kDepth + 2; ++k) m.enter(k);
  EXPECT_EQ(m.size, MediumStack::kDepth);
  EXPECT_EQ(m.current(), uint32_t(MediumStack::kDepth - 1));
}

}  // namespace
}  // namespace photovr
