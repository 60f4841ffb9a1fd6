// The photovr command line, run as a user would: exit codes, one-line errors, outputs.
#include <filesystem>
#include <fstream>
#include <iostream>
#include <string>
#include <utility>

#include <unistd.h>

#include <gtest/gtest.h>

#include "core/memory.h"
#include "core/image_io.h"
#include "tests/app/cli_util.h"
#include "tests/core/skinned_glb.h"

namespace photovr {
namespace {

using testing::runPhotovr;
using testing::tempDir;
namespace fs = std::filesystem;

size_t lineCount(const std::string& s) {
  size_t n = 0;
  for (char c : s) n += c == '\n';
  return n;
}

TEST(Cli, HelpForEveryCommand) {
  for (const char* cmd :
       {"--help", "render --help", "info --help", "export-scene --help", "view --help"}) {
    const auto r = runPhotovr(cmd);
    EXPECT_EQ(r.status, 0) << cmd;
    EXPECT_NE(r.output.find("usage: photovr"), std::string::npos) << cmd;
  }
}

TEST(Cli, BadArgumentsAreOneLineErrorsWithExitCode2) {
  const char* cases[][2] = {
      {"frobnicate", "unknown command 'frobnicate'"},
      {"render --width 0", "--width: 0 is out of range"},
      {"render --width 99999999999", "--width"},
      {"render --height abc", "--height: 'abc' is not an integer"},
      {"render --scene nosuchscene", "neither a built-in scene"},
      {"render --eyes triple", "--eyes: 'triple' is not one of stereo, mono"},
      {"render --look-at 1,2", "--look-at: '1,2' is not three"},
      {"render --fovy 1e9", "--fovy"},
      {"render --fovy nan", "--fovy: 'nan' is not a finite number"},
      {"render --backend vulkan", "unknown backend 'vulkan'"},
      {"render --frobs 3", "unknown option '--frobs'"},
      {"render --camera 7 --scene cornell", "--camera: '7' is not a camera of this scene"},
      {"info", "expected exactly one SCENE"},
      {"export-scene nosuch /tmp/x.glb", "unknown built-in scene 'nosuch'"},
      {"export-scene cornell /tmp/x.obj", "/tmp/x.obj: expected a .glb or .gltf path"},
      {"render --fovy 40", "--fovy: only with --eyes mono"},
      {"render --out ''", "--out: empty value"},  // it wrote into the root folder
      {"render --width 4 --width 8", "--width: given twice"},
      {"render --no-skip all,refit", "unknown skip 'all' (expected 'all' alone"},
      {"view --scene cornell --eyes mono", "view: --eyes and --fovy are not headset options"},
  };
  for (const auto& c : cases) {
    const auto r = runPhotovr(c[0]);
    EXPECT_EQ(r.status, 2) << c[0] << "\n" << r.output;
    EXPECT_NE(r.output.find(c[1]), std::string::npos) << c[0] << "\n" << r.output;
    EXPECT_EQ(lineCount(r.output), 1u) << c[0] << "\n" << r.output;
  }
}

// Sizes each within range but together beyond this machine's memory are refused before
// anything is allocated (the kernel would kill the render part-way). Each command is the
// largest its options allow: render 8192x8192 per eye, and view 4096x4096 with --overscan 10,
// which grows the eyes to 6768x6620 over the lens's field. A machine that holds one of them
// does not run that one, and says so; one that holds both skips the test, saying why.
TEST(Cli, FrameLargerThanMemoryIsAUsageError) {
  const double physical = double(sysconf(_SC_PHYS_PAGES)) * double(sysconf(_SC_PAGE_SIZE));
  const std::pair<const char*, double> commands[] = {
      {"render --width 8192 --height 8192", 8192.0 * 8192.0},
      {"view --width 4096 --height 4096 --overscan 10", 6768.0 * 6620.0}};
  int ran = 0;
  for (const auto& [command, eyePixels] : commands) {
    if (kBytesPerEyePixel * eyePixels <= physical) {
      std::cout << "not run: '" << command << "' fits in this machine's memory\n";
      continue;
    }
    ++ran;
    const auto r = runPhotovr(command);
    EXPECT_EQ(r.status, 2) << command << "\n" << r.output;
    EXPECT_NE(r.output.find("--width/--height: "), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("more than this machine's"), std::string::npos) << r.output;
    EXPECT_EQ(lineCount(r.output), 1u) << r.output;
  }
  if (ran == 0) GTEST_SKIP() << "this machine holds the largest frame of every command";
}

// view's eyes are the headset's: its help offers no option it would refuse.
TEST(Cli, ViewHelpOffersNoEyeOptions) {
  const auto r = runPhotovr("view --help");
  EXPECT_EQ(r.status, 0);
  EXPECT_NE(r.output.find("--look-at"), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find("--eyes"), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find("--fovy"), std::string::npos) << r.output;
}

TEST(Cli, MissingSceneFileIsAnInputErrorNamingTheFile) {
  const auto r = runPhotovr("info /nonexistent/scene.glb");
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.output.find("/nonexistent/scene.glb"), std::string::npos) << r.output;
  EXPECT_EQ(lineCount(r.output), 1u) << r.output;
}

TEST(Cli, InfoOnEveryBuiltinScene) {
  for (const char* name : {"atrium", "cornell", "spheres"}) {
    const auto r = runPhotovr(std::string("info ") + name);
    EXPECT_EQ(r.status, 0) << r.output;
    EXPECT_NE(r.output.find("triangles"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("renderer will use"), std::string::npos) << r.output;
  }
}

TEST(Cli, ExportedSceneLoadsBackWithTheSameCounts) {
  const std::string dir = tempDir("export");
  const auto w = runPhotovr("export-scene atrium " + dir + "/atrium.glb");
  ASSERT_EQ(w.status, 0) << w.output;
  const auto a = runPhotovr("info atrium"), b = runPhotovr("info " + dir + "/atrium.glb");
  ASSERT_EQ(b.status, 0) << b.output;
  // The triangle line (stored and instanced) must agree between built-in and exported.
  auto triangles = [](const std::string& s) {
    const size_t p = s.find("triangles");
    return s.substr(s.rfind('\n', p) + 1, s.find('\n', p) - s.rfind('\n', p) - 1);
  };
  EXPECT_EQ(triangles(a.output), triangles(b.output));
  EXPECT_NE(b.output.find("textures"), std::string::npos);
}

// Issue 23: a scene with nothing that emits renders black; render says so before it does.
TEST(Cli, RenderWarnsWhenNothingLightsTheScene) {
  const std::string dir = tempDir("unlit");
  const std::string gltf = dir + "/dark.gltf";
  std::ofstream(gltf) << R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],
"nodes":[{"mesh":0}],"meshes":[{"primitives":[{"attributes":{"POSITION":0}}]}],
"buffers":[{"byteLength":36,"uri":"data:application/octet-stream;base64,AAAAAAAAAAAAAADAAACAPwAAAAAAAADAAAAAAAAAgD8AAADA"}],
"bufferViews":[{"buffer":0,"byteLength":36}],
"accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3","min":[0,0,-2],"max":[1,1,-2]}]})";
  const std::string args = " --mode pt --eyes mono --width 8 --height 8 --out " + dir + "/out";
  const auto dark = runPhotovr("render --scene " + gltf + args);
  ASSERT_EQ(dark.status, 0) << dark.output;
  EXPECT_NE(dark.output.find("warning: no light, emitter or environment"), std::string::npos)
      << dark.output;
  const auto lit = runPhotovr("render --scene cornell" + args);
  ASSERT_EQ(lit.status, 0) << lit.output;
  EXPECT_EQ(lit.output.find("warning"), std::string::npos) << lit.output;
}

// render --play: frame f of an animated scene at --time + f / 75 s, posed by the pipeline
// (its time in the stage line); refused where there is nothing to accumulate.
TEST(Cli, RenderPlayPosesEachFrame) {
  const std::string dir = tempDir("play");
  testing::SkinOptions bar;
  bar.emissive = true;
  const std::string scene = testing::skinnedFile(dir, bar);
  const std::string args = " --scene " + scene + " --mode pt --eyes mono --width 8 --height 8" +
                           " --frames 3 --out " + dir + "/out";
  const auto played = runPhotovr("render --play" + args);
  ASSERT_EQ(played.status, 0) << played.output;
  EXPECT_NE(played.output.find("posing the scene"), std::string::npos) << played.output;
  const auto still = runPhotovr("render" + args);
  ASSERT_EQ(still.status, 0) << still.output;
  EXPECT_EQ(still.output.find("posing the scene"), std::string::npos) << still.output;
  const auto gbuffer =
      runPhotovr("render --play --mode gbuffer --scene " + scene + " --out " + dir);
  EXPECT_EQ(gbuffer.status, 2) << gbuffer.output;
  EXPECT_NE(gbuffer.output.find("--play: needs a traced mode"), std::string::npos)
      << gbuffer.output;
}

TEST(Cli, RenderWritesEveryImageForBothEyes) {
  const std::string dir = tempDir("render");
  const auto r = runPhotovr(
      "render --mode gbuffer --scene cornell --backend osmesa --width 64 --height 72 --out " + dir);
  ASSERT_EQ(r.status, 0) << r.output;
  for (const char* eye : {"left", "right"})
    for (const char* file : {"depth.exr", "normal.png", "albedo.png", "ids.png"})
      EXPECT_TRUE(fs::exists(dir + "/" + eye + "/" + file)) << eye << "/" << file;
  const Image8 mosaic = readImageRGBA8(dir + "/gbuffer.png");
  EXPECT_EQ(mosaic.width, 2 * 64);
  EXPECT_EQ(mosaic.height, 72);
  const ImageF depth = readImageF(dir + "/left/depth.exr");
  ASSERT_EQ(depth.width, 64);
  // The camera is inside the closed box: every pixel sees a wall, at reversed-Z depth
  // near / distance with distance between 0.05 m and the box diagonal (3.5 m).
  for (float d : depth.data) {
    EXPECT_GT(d, 0.05f / 3.5f);
    EXPECT_LE(d, 1.0f);
  }
}

// Where the kernel gives huge pages on request only, photovr re-executes itself with
// malloc asking for them (core/huge_pages.h) and says so, with its arguments intact;
// PHOTOVR_HUGE_PAGES=0 keeps ordinary pages.
TEST(Cli, MallocAsksForHugePagesWhereTheKernelWantsToBeAsked) {
  std::ifstream policyFile("/sys/kernel/mm/transparent_hugepage/enabled");
  std::string policy;
  std::getline(policyFile, policy);
  const bool onRequest = policy.find("[madvise]") != std::string::npos;
  const std::string dir = tempDir("huge-pages");
  const std::string render =
      "render --mode gbuffer --scene cornell --backend osmesa --width 16 --height 18 --out " + dir;
  const auto asked = runPhotovr(render, "env -u GLIBC_TUNABLES -u PHOTOVR_HUGE_PAGES");
  ASSERT_EQ(asked.status, 0) << asked.output;
  EXPECT_EQ(asked.output.find("malloc on huge pages") != std::string::npos, onRequest)
      << "kernel policy: " << policy << "\n"
      << asked.output;
  EXPECT_EQ(readImageRGBA8(dir + "/gbuffer.png").width, 2 * 16);  // the arguments survived
  const auto optedOut = runPhotovr(render, "env -u GLIBC_TUNABLES PHOTOVR_HUGE_PAGES=0");
  ASSERT_EQ(optedOut.status, 0) << optedOut.output;
  EXPECT_EQ(optedOut.output.find("malloc on huge pages"), std::string::npos) << optedOut.output;
  // The user's own "no" is kept, and reported as such.
  const auto refused =
      runPhotovr(render, "env -u PHOTOVR_HUGE_PAGES GLIBC_TUNABLES=glibc.malloc.hugetlb=0");
  ASSERT_EQ(refused.status, 0) << refused.output;
  EXPECT_EQ(refused.output.find("malloc on huge pages"), std::string::npos) << refused.output;
}

TEST(Cli, MonoRenderWritesOneEyeWithTheRequestedAspect) {
  const std::string dir = tempDir("mono");
  const auto r = runPhotovr(
      "render --mode gbuffer --scene spheres --eyes mono --fovy 40 --backend osmesa "
      "--width 80 --height 40 --out " +
      dir);
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_TRUE(fs::exists(dir + "/mono/albedo.png"));
  EXPECT_FALSE(fs::exists(dir + "/left"));
  EXPECT_EQ(readImageRGBA8(dir + "/gbuffer.png").width, 80);
}

TEST(Cli, GlfwWithoutADisplaySaysWhatToTryInstead) {
  const auto r = runPhotovr(
      "render --backend glfw --width 8 --height 8 --scene cornell "
      "--out /tmp/photovr-nodisplay </dev/null; unset DISPLAY; " +
      std::string(PHOTOVR_BINARY) + " render --backend glfw");
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_NE(r.output.find("glfw: no display"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("--backend egl"), std::string::npos) << r.output;
}

// Refused before any rendering, naming the path; nothing written.
TEST(Cli, OutputFolderThatIsAFileIsRefusedUpFront) {
  const std::string dir = tempDir("out-is-a-file");
  std::ofstream(dir + "/afile") << "x";
  const auto r = runPhotovr("render --scene cornell --backend osmesa --width 8 --height 8 --out " +
                            dir + "/afile");
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_NE(r.output.find(dir + "/afile: cannot create the output folder"), std::string::npos)
      << r.output;
  EXPECT_EQ(r.output.find("G-buffer"), std::string::npos) << r.output;  // no frame rendered
}

// A corrupt frame count in the reference cache (negative) crashed `reference`; the cache
// is now rebuilt from scratch. Its shard file (the sums the mean is merged from) corrupt
// too, nothing is left to merge.
TEST(Cli, CorruptReferenceCacheIsRebuilt) {
  const std::string cache = tempDir("corrupt-cache");
  const std::string args =
      "reference --scene cornell --width 8 --height 8 --bounces 1 --spp 4 --backend osmesa";
  ASSERT_EQ(runPhotovr(args, "PHOTOVR_CACHE_DIR=" + cache).status, 0);
  int counters = 0, shards = 0;
  for (const auto& e : std::filesystem::recursive_directory_iterator(cache)) {
    if (e.path().filename() == "frames.txt") std::ofstream(e.path()) << "-5\n", ++counters;
    if (e.path().filename() == "shard-0-of-1.bin") std::ofstream(e.path()) << "junk\n", ++shards;
  }
  ASSERT_EQ(counters, 1);
  ASSERT_EQ(shards, 1);
  const auto r = runPhotovr(args, "PHOTOVR_CACHE_DIR=" + cache);
  EXPECT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("0 -> 4 spp"), std::string::npos) << r.output;
}

TEST(Cli, UnwritableOutputIsAnErrorNotACrash) {
  const auto r = runPhotovr(
      "render --scene cornell --backend osmesa --width 8 --height 8 --out "
      "/proc/photovr-cannot-write");
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_NE(r.output.find("/proc/photovr-cannot-write"), std::string::npos) << r.output;
}

}  // namespace
}  // namespace photovr

namespace photovr {
namespace {

TEST(Cli, HybridAndPathTracedRendersWriteColourAndAovs) {
  for (const char* mode : {"hybrid", "pt"}) {
    const std::string dir = testing::tempDir(std::string("traced-") + mode);
    const auto r = testing::runPhotovr(std::string("render --mode ") + mode +
                                       " --scene cornell --backend osmesa --width 24 --height 27 "
                                       "--spp 2 --frames 2 --out " +
                                       dir);
    ASSERT_EQ(r.status, 0) << r.output;
    EXPECT_NE(r.output.find("0 samples rejected"), std::string::npos) << r.output;
    for (const char* eye : {"left", "right"})
      for (const char* file : {"color.exr", "albedo.exr", "normal.exr", "depth.exr", "samples.exr"})
        EXPECT_TRUE(std::filesystem::exists(dir + "/" + eye + "/" + file)) << mode << " " << file;
    const ImageF samples = readImageF(dir + "/left/samples.exr");
    for (float s : samples.data) EXPECT_EQ(s, 4.0f);  // 2 spp x 2 frames, inside the box
    EXPECT_EQ(readImageRGBA8(dir + "/color.png").width, 48);
  }
}

}  // namespace
}  // namespace photovr

namespace photovr {
namespace {

TEST(Cli, DenoisedRendersForHybridAndPt) {
  for (const char* mode : {"hybrid", "pt"}) {
    const std::string dir = testing::tempDir(std::string("denoise-") + mode);
    const auto r = testing::runPhotovr(std::string("render --mode ") + mode +
                                       " --denoise full --scene cornell --backend osmesa "
                                       "--width 16 --height 18 --frames 2 --out " +
                                       dir);
    ASSERT_EQ(r.status, 0) << r.output;
    EXPECT_EQ(readImageRGBA8(dir + "/denoised.png").width, 32) << mode;
    EXPECT_EQ(readImageF(dir + "/left/denoised.exr").width, 16) << mode;
  }
  EXPECT_EQ(testing::runPhotovr("render --mode gbuffer --denoise full").status, 2);
}

}  // namespace
}  // namespace photovr
