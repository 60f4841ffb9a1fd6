// Bounded fuzzing of the headset's two input files (fixed seeds; the ASan/UBSan build runs
// this too): mutated pose scripts and HID recordings are read or refused with one
// InputError line naming the file, never another exception or a crash; what is read keeps
// the format's promises (finite, increasing times and unit orientations; records of 1 to
// kMaxRecordBytes bytes).
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>

#include <gtest/gtest.h>

#include "core/error.h"
#include "hmd/pose_script.h"
#include "hmd/recording.h"

namespace photovr::hmd {
namespace {

// 4000 of each run in about half a second in Release.
constexpr int kIterations = 4000;

std::string mutate(std::string s, std::mt19937& rng, const std::string& alphabet) {
  const auto at = [&](size_t n) { return n ? size_t(rng() % n) : 0; };
  switch (rng() % 4) {
    case 0:
      for (int i = 0, n = 1 + int(rng() % 4); i < n && !s.empty(); ++i)
        s[at(s.size())] = alphabet.empty() ? char(rng()) : alphabet[at(alphabet.size())];
      break;
    case 1:
      s.erase(at(s.size()), 1 + at(24));
      break;
    case 2: {
      const size_t begin = at(s.size());
      s.insert(begin, s.substr(begin, 1 + at(24)));
      break;
    }
    default:
      s.resize(at(s.size() + 1));
  }
  return s;
}

void expectOneLine(const InputError& e, const std::string& file, const std::string& input) {
  const std::string what = e.what();
  EXPECT_EQ(what.find('\n'), std::string::npos) << what << "\n" << input;
  EXPECT_EQ(what.rfind(file, 0), 0u) << what << "\n" << input;
}

TEST(InputFilesFuzz, MutatedPoseScriptsParseSoundlyOrFailWithOneLine) {
  const std::string seed =
      "t,x,y,z,yaw,pitch,roll\n# a walk\n0,0,1.6,0,0,0,0\n0.5,0.1,1.6,-0.2,30,-5,2\n\n"
      "1.25,0.2,1.7,-0.4,-45.5,10,0\n2,1e-3,1.6,-1,179,89,-30\n";
  std::mt19937 rng(20261202);
  int parsed = 0, refused = 0;
  for (int it = 0; it < kIterations; ++it) {
    const std::string input = mutate(seed, rng, "0123456789-+.eE,\n# natyxzwpirol");
    try {
      const PoseScript script = parsePoseScript(input, "walk.csv");
      ASSERT_FALSE(script.keys.empty()) << input;
      for (size_t k = 0; k < script.keys.size(); ++k) {
        const PoseKey& key = script.keys[k];
        ASSERT_TRUE(std::isfinite(key.t)) << input;
        if (k > 0) {
          ASSERT_GT(key.t, script.keys[k - 1].t) << input;
        }
        for (int c = 0; c < 3; ++c) ASSERT_TRUE(std::isfinite(key.pose.position[c])) << input;
        // A quaternion built from finite angles: unit to float rounding.
        ASSERT_NEAR(glm::length(key.pose.orientation), 1.0f, 1e-5f) << input;
      }
      // Poses sampled between and beyond the rows stay finite.
      const double t0 = script.keys.front().t, span = script.duration();
      for (double f : {-0.5, 0.0, 0.3, 0.5, 0.77, 1.0, 2.0}) {
        const Pose p = script.sample(t0 + f * span);
        for (int c = 0; c < 3; ++c) ASSERT_TRUE(std::isfinite(p.position[c])) << f << input;
        ASSERT_NEAR(glm::length(p.orientation), 1.0f, 1e-5f) << f << input;
      }
      ++parsed;
    } catch (const InputError& e) {
      expectOneLine(e, "walk.csv", input);
      ++refused;
    } catch (const std::exception& e) {
      FAIL() << it << ": " << e.what() << "\n" << input;
    }
    if (HasFatalFailure()) return;
  }
  std::printf("pose script fuzz: %d parsed, %d refused with one line\n", parsed, refused);
  EXPECT_GT(parsed, 0);
  EXPECT_GT(refused, 0);
}

TEST(InputFilesFuzz, MutatedRecordingsReadSoundlyOrFailWithOneLine) {
  const std::string path =
      (std::filesystem::temp_directory_path() / "photovr_fuzz_recording.pvrhid").string();
  {
    RecordingWriter w(path);
    w.write({HidRecord::FeatureSet, 5, {0x11, 0, 0, 0x0B, 0x10, 0x27}});
    w.write({HidRecord::FeatureGet, 9, std::vector<uint8_t>(8, 0x04)});
    for (uint64_t i = 0; i < 4; ++i)
      w.write({HidRecord::Input, 1000000 * i, std::vector<uint8_t>(64, uint8_t(0x0B + i))});
  }
  std::ifstream in(path, std::ios::binary);
  const std::string seed((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::mt19937 rng(20261202);
  int read = 0, refused = 0;
  for (int it = 0; it < kIterations; ++it) {
    const std::string input = mutate(seed, rng, "");
    std::ofstream(path, std::ios::binary | std::ios::trunc) << input;
    try {
      for (const HidRecord& r : readRecording(path)) {
        ASSERT_TRUE(r.kind >= HidRecord::Input && r.kind <= HidRecord::FeatureSet);
        ASSERT_TRUE(!r.bytes.empty() && r.bytes.size() <= kMaxRecordBytes);
      }
      ++read;
    } catch (const InputError& e) {
      expectOneLine(e, path, "(binary)");
      ++refused;
    } catch (const std::exception& e) {
      FAIL() << it << ": " << e.what();
    }
    if (HasFatalFailure()) break;
  }
  std::filesystem::remove(path);
  std::printf("recording fuzz: %d read, %d refused with one line\n", read, refused);
  EXPECT_GT(read, 0);
  EXPECT_GT(refused, 0);
}

}  // namespace
}  // namespace photovr::hmd
