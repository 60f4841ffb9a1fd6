// The 'sim' headset's pose scripts: interpolation and one-line errors for bad CSV.
#include "hmd/pose_script.h"

#include <cmath>
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

#include "core/error.h"
#include "hmd/head_tracker.h"

namespace photovr::hmd {
namespace {

std::string errorOf(const std::string& text) {
  try {
    parsePoseScript(text, "walk.csv");
  } catch (const InputError& e) {
    return e.what();
  }
  return "(accepted)";
}

TEST(PoseScript, InterpolatesPositionLinearlyAndOrientationBySlerp) {
  const PoseScript s = parsePoseScript(
      "# a turn\n t, x, y, z, yaw, pitch, roll\n0,0,1.6,0,0,0,0\n\n2,1,1.6,-2,90,0,0\n",
      "walk.csv");
  ASSERT_EQ(s.keys.size(), 2u);
  const Pose mid = s.sample(1.0);
  EXPECT_NEAR(mid.position.x, 0.5f, 1e-6f);
  EXPECT_NEAR(mid.position.z, -1.0f, 1e-6f);
  // Halfway through a 90 deg yaw: 45 deg, forward (-Z) turned toward -X.
  const glm::vec3 f = mid.orientation * glm::vec3(0, 0, -1);
  EXPECT_NEAR(std::atan2(-f.x, -f.z), glm::radians(45.0f), 1e-5f);
  EXPECT_EQ(s.sample(-1.0).position, s.keys[0].pose.position);  // ends hold
  EXPECT_EQ(s.sample(9.0).orientation, s.keys[1].pose.orientation);
  EXPECT_DOUBLE_EQ(s.duration(), 2.0);
}

TEST(PoseScript, AnglesFollowTheDocumentedConvention) {
  const glm::vec3 f = yawPitchRoll(0, 30, 0) * glm::vec3(0, 0, -1);
  EXPECT_NEAR(f.y, 0.5f, 1e-6f);  // positive pitch looks up
  const glm::vec3 r = yawPitchRoll(0, 0, 30) * glm::vec3(1, 0, 0);
  EXPECT_NEAR(r.y, 0.5f, 1e-6f);  // positive roll lifts the right ear: head tilts left
  const glm::vec3 l = yawPitchRoll(30, 0, 0) * glm::vec3(0, 0, -1);
  EXPECT_NEAR(l.x, -0.5f, 1e-6f);  // positive yaw turns left
}

TEST(PoseScript, SlerpTakesTheShortWayAcrossPlusMinus180) {
  const PoseScript s =
      parsePoseScript("t,x,y,z,yaw,pitch,roll\n0,0,0,0,170,0,0\n1,0,0,0,-170,0,0\n", "a.csv");
  const glm::vec3 f = s.sample(0.5).orientation * glm::vec3(0, 0, -1);
  EXPECT_NEAR(f.z, 1.0f, 1e-5f);  // 180 deg, not 0 deg
}

TEST(PoseScript, BadCsvNamesTheFileAndLine) {
  EXPECT_EQ(errorOf(""), "walk.csv: empty (expected the header t,x,y,z,yaw,pitch,roll)");
  EXPECT_EQ(errorOf("time,x,y,z\n"),
            "walk.csv: line 1: expected the header t,x,y,z,yaw,pitch,roll");
  EXPECT_EQ(errorOf("t,x,y,z,yaw,pitch,roll\n"), "walk.csv: no pose rows after the header");
  EXPECT_EQ(errorOf("t,x,y,z,yaw,pitch,roll\n0,0,0,0,0,0,0\n1,2,3\n"),
            "walk.csv: line 3: expected 7 comma-separated numbers (t,x,y,z,yaw,pitch,roll), got 3");
  EXPECT_EQ(errorOf("t,x,y,z,yaw,pitch,roll\n0,0,0,zero,0,0,0\n"),
            "walk.csv: line 2: 'zero' is not a number (expected t,x,y,z,yaw,pitch,roll)");
  EXPECT_EQ(errorOf("t,x,y,z,yaw,pitch,roll\n1,0,0,0,0,0,0\n1,0,0,0,0,0,0\n"),
            "walk.csv: line 3: t must increase from row to row");
  // Found by InputFilesFuzz: finite as a double, infinite as the float pose.
  EXPECT_EQ(errorOf("t,x,y,z,yaw,pitch,roll\n0,1e53,0,0,0,0,0\n"),
            "walk.csv: line 2: '1e53' is beyond float range (about 3.4e38)");
  EXPECT_EQ(errorOf("t,x,y,z,yaw,pitch,roll\n0,0,0,0,0,0,nan\n"),
            "walk.csv: line 2: 'nan' is not a number (expected t,x,y,z,yaw,pitch,roll)");
  for (const char* bad :
       {"t,x,y,z,yaw,pitch,roll\n0,0,0,0,0,0,0,\n", "t,x,y,z,yaw,pitch,roll\n0,,0,0,0,0,0\n"})
    EXPECT_NE(errorOf(bad).find("walk.csv: line 2: "), std::string::npos) << bad;
}

TEST(SimHeadset, FollowsAScriptFile) {
  const std::string path =
      (std::filesystem::temp_directory_path() / "photovr_hmd_sim.csv").string();
  std::ofstream(path) << "t,x,y,z,yaw,pitch,roll\n0,0,1.7,0,0,0,0\n4,0,1.7,-4,0,0,0\n";
  SimHeadset sim(loadPoseScript(path));
  EXPECT_NEAR(sim.pose(1.0).position.z, -1.0f, 1e-6f);
  EXPECT_EQ(sim.status(), "sim " + path);
  std::filesystem::remove(path);
  EXPECT_THROW(loadPoseScript(path), InputError);
}

}  // namespace
}  // namespace photovr::hmd
