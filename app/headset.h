// What the headset commands share (render --hmd, view): the --hmd option and the head-pose
// source it names. The display side (compositor, lens, outputs) is display/.
#pragma once

#include <array>
#include <memory>
#include <string>
#include <vector>

#include "app/commands.h"
#include "hmd/head_tracker.h"

namespace photovr::app {

// --hmd dk2 | replay FILE | sim FILE | none.
struct HmdSpec {
  std::string kind = "none";
  std::string file;  // replay, sim
};

// Removes "--hmd KIND [FILE]" from 'args' (the shared Options parser takes one value per
// option) and returns it; UsageError for an unknown kind or a missing file argument.
HmdSpec extractHmdOption(Args& args);

// The pose source 'spec' names. dk2: the headset over hidapi, else nullptr with a one-line
// reason in 'why' (the caller decides whether that is fatal). replay: interactive plays the
// recording through the DK2 driver at its recorded pace (pose(t) on the host clock);
// otherwise the recording is decoded and fused up front and pose(t) is the orientation at
// t seconds of device time after its first sample (deterministic, for headless runs).
// sim: the pose script. Bad files throw InputError naming the file.
std::unique_ptr<hmd::HeadPoseSource> openHeadPoseSource(const HmdSpec& spec, bool interactive,
                                                        std::string* why);

}  // namespace photovr::app
