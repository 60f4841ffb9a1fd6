// photovr render: option parsing shared by every mode, then the mode itself.
#include <iostream>
#include <unistd.h>

#include "app/hmd_sequence.h"
#include "core/memory.h"
#include "app/render_request.h"
#include "core/error.h"
#include "core/files.h"
#include "core/options.h"
#include "core/scene_transform.h"
#include "hmd/headset_description.h"

namespace photovr::app {

const char* const kRenderHelp =
    "usage: photovr render [options]\n"
    "Renders a scene headless. Per eye (left/, right/ or mono/) it writes:\n"
    "  --mode hybrid (default; GL G-buffer primaries continued by Embree) and --mode pt\n"
    "    (Embree alone): color.exr (linear radiance), albedo.exr, normal.exr, depth.exr\n"
    "    (reversed-Z: near 1, far 0), samples.exr; hybrid adds the denoiser inputs\n"
    "    diffuse.exr, specular.exr (albedo-demodulated) and their albedos; and a\n"
    "    side-by-side tone-mapped color.png (Khronos PBR Neutral, sRGB);\n"
    "  --mode gbuffer: depth.exr, normal.png, albedo.png, ids.png and a gbuffer.png mosaic\n"
    "    (albedo, normal / ids, depth).\n"
    "  --scene NAME|FILE      atrium (default), cornell, spheres, or a .gltf/.glb file\n"
    "  --env FILE             equirectangular .hdr/.exr environment\n"
    "  --width W --height H   per-eye size (default 960x1080, the DK2's eye; 1..8192)\n"
    "  --mode hybrid|pt|gbuffer  what to render (default hybrid)\n"
    "  --spp N                samples per pixel per frame (1..65536, default 1); pt: each at\n"
    "                         its own place in the pixel; hybrid: N paths continued from\n"
    "                         the frame's one rasterized hit (antialias with --frames)\n"
    "  --bounces N            indirect bounces after the first hit (0..64, default 8)\n"
    "  --frames F             frames accumulated with sub-pixel jitter (1..65536, default 1)\n"
    "  --seed S               random seed (default 0)\n"
    "  --sampler S            sobol (default: Owen-scrambled Sobol, one sequence over the\n"
    "                         frames and samples of a pixel) or random (independent numbers)\n"
    "  --exposure E           exposure multiplier for color.png (default 1)\n"
    "  --sampling S           hybrid: uniform (default); hidden-area (pixels the DK2 lens never\n"
    "                         shows are not traced); lens-matched (--spp is the maximum,\n"
    "                         spread by the lens's magnification); thesis-zones (the\n"
    "                         thesis's Algorithm 6, for comparison)\n"
    "  --denoise off|temporal|full  SVGF denoiser in GL (default off; pt draws a G-buffer\n"
    "                         for its guides); writes\n"
    "                         denoised.png and per eye denoised.exr from the last frame\n"
    "  --stereo-reuse on|off  stereo frames: the eye traced second reuses the first eye's\n"
    "                         paths beyond each shared first hit, the eyes taking turns\n"
    "                         (default on; docs/ARCHITECTURE.md, \"Stereo path reuse\")\n"
    "  --caustics on|off      directional lights' caustics (a smooth surface throwing the\n"
    "                         sun onto a rough one) traced from the light (default on;\n"
    "                         docs/ARCHITECTURE.md, \"Caustics\")\n"
    "  --time T               an animated glTF scene posed at T seconds (default 0)\n"
    "  --play                 animated scene: frame f shows time T + f / 75 s, so --frames F\n"
    "                         accumulates F / 75 s of motion (motion blur); --hmd plays the\n"
    "                         scene on the sequence's clock without it\n"
    "  --converge E           stop accumulating frames once the estimated relMSE of the\n"
    "                         mean is below E (static view; default 0 = render every frame)\n"
    "  --no-skip LIST         turn off skips of work the scene does not need, to measure\n"
    "                         them: all, or any of punctual-lights, area-lights,\n"
    "                         environment, any-hit, refit, sky-pixels,\n"
    "                         dark-emitters (see photovr info)\n"
    "  --backend B            egl (default, falls back to osmesa), osmesa, glfw\n"
    "  --out DIR              output folder (default out/<scene>)\n";

namespace {

std::string defaultOutDir(const std::string& scene) {
  const size_t slash = scene.find_last_of('/');
  std::string stem = scene.substr(slash == std::string::npos ? 0 : slash + 1);
  stem = stem.substr(0, stem.find_last_of('.'));
  return "out/" + (stem.empty() ? std::string("scene") : stem);
}

}  // namespace

RenderRequest parseRenderRequest(const Args& args) {
  std::set<std::string> valued = {"--scene",   "--env",          "--width",   "--height",
                                  "--backend", "--out",          "--mode",    "--spp",
                                  "--bounces", "--frames",       "--seed",    "--exposure",
                                  "--denoise", "--sampling",     "--no-skip", "--converge",
                                  "--sampler", "--stereo-reuse", "--caustics"};
  valued.insert(kViewOptions.begin(), kViewOptions.end());
  const Options o(args, valued, {"--play"});
  if (!o.positional().empty())
    throw UsageError("render: unexpected argument '" + o.positional()[0] + "'");
  RenderRequest r;
  r.sceneSpec = o.text("--scene", "atrium");
  const std::string mode = o.choice("--mode", "hybrid", {"hybrid", "pt", "gbuffer"});
  r.mode = mode == "pt"        ? RenderMode::PathTraced
           : mode == "gbuffer" ? RenderMode::GBuffer
                               : RenderMode::Hybrid;
  r.backend = o.text("--backend", "");
  const hmd::HeadsetDescription headset = hmd::HeadsetDescription::dk2();
  r.width = o.integer("--width", headset.eyeWidth, 1, 8192);
  r.height = o.integer("--height", headset.eyeHeight, 1, 8192);
  checkFrameFitsInMemory(r.width, r.height, "--width/--height");
  r.spp = o.integer("--spp", 1, 1, 65536);
  r.bounces = o.integer("--bounces", 8, 0, 64);
  r.frames = o.integer("--frames", 1, 1, 65536);
  r.seed = uint32_t(o.integer("--seed", 0, 0, 2147483647));
  r.sampler = o.choice("--sampler", "sobol", {"sobol", "random"}) == "random" ? SamplerKind::Random
                                                                              : SamplerKind::Sobol;
  r.exposure = o.number("--exposure", 1.0f, 1e-6f, 1e6f);
  r.denoise = gl::parseDenoiseMode(o.choice("--denoise", "off", {"off", "temporal", "full"}));
  r.sampling = parseSampleMapKind(o.choice(
      "--sampling", "uniform", {"uniform", "hidden-area", "lens-matched", "thesis-zones"}));
  r.converge = o.number("--converge", 0.0f, 0.0f, 1.0f);
  r.stereoReuse = parseStereoReuse(o);
  r.caustics = parseCaustics(o);
  try {
    r.skips.disable(o.text("--no-skip", ""));
  } catch (const std::invalid_argument& e) {
    throw UsageError(std::string("--no-skip: ") + e.what());
  }
  if (r.denoise != gl::DenoiseMode::Off && r.mode == RenderMode::GBuffer)
    throw UsageError("--denoise: needs a traced mode (hybrid or pt)");
  r.outDir = o.text("--out", defaultOutDir(r.sceneSpec));
  createOutputFolder(r.outDir);
  r.scene = loadSceneSpec(r.sceneSpec);
  applyEnvironmentOption(r.scene, o.text("--env", ""));
  r.time = applyTimeOption(r.scene, o);
  r.play = o.has("--play");
  if (r.play && (r.mode == RenderMode::GBuffer || r.converge > 0.0))
    throw UsageError("--play: needs a traced mode (hybrid or pt) and no --converge");
  if (r.play && !isAnimated(r.scene))
    std::cerr << "photovr: warning: --play: the scene has no animation; it is rendered as is\n";
  warnAboutScene(r.scene);
  r.view = resolveView(r.scene, o);
  r.view.head = recenterOnView(r.scene, r.view.head);  // camera-relative: full precision
  if (r.sampling != SampleMapKind::Uniform && (r.mode != RenderMode::Hybrid || !r.view.stereo))
    throw UsageError("--sampling: lens-based sample maps need --mode hybrid and --eyes stereo");
  return r;
}

bool parseCaustics(const Options& o) {
  return o.choice("--caustics", kCausticsDefault ? "on" : "off", {"on", "off"}) == "on";
}

bool parseStereoReuse(const Options& o) {
  return o.choice("--stereo-reuse", kStereoReuseDefault ? "on" : "off", {"on", "off"}) == "on";
}

const char* renderModeName(RenderMode mode) {
  return mode == RenderMode::GBuffer ? "gbuffer" : mode == RenderMode::PathTraced ? "pt" : "hybrid";
}

int runRender(const Args& args) {
  if (wantsHelp(args)) {
    std::cout << kRenderHelp << kHeadHelp << kEyesHelp << kHmdRenderHelp;
    return 0;
  }
  Args rest = args;
  const HmdSpec hmd = extractHmdOption(rest);
  const HmdSequenceOptions sequence = extractHmdSequenceOptions(rest, hmd);
  RenderRequest request = parseRenderRequest(rest);
  if (hmd.kind != "none") {
    if (request.converge > 0.0)
      throw UsageError("--converge: not with --hmd (the head moves, so frames do not converge)");
    return renderHmdSequence(request, hmd, sequence);
  }
  if (request.mode == RenderMode::GBuffer) return renderGBufferMode(request);
  return renderTracedMode(request);
}

}  // namespace photovr::app
