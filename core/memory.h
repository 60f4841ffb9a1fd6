// Memory: the bench's peak resident figure, and the check that a frame size fits in this
// machine's memory before anything is allocated for it.
#pragma once

namespace photovr {

// Peak resident memory of the process (the bench runs each configuration in its own child
// process, harness/bench_child.h, so this is the configuration's peak: scene, GL context,
// renderer, denoiser and frames together). VmHWM from /proc/self/status, else getrusage's
// ru_maxrss (the same figure on Linux).
double peakRssMiB();

// Bytes the default pipeline (hybrid, denoised, both eyes) holds per pixel of one eye:
// peak RSS of `render --scene cornell --denoise full` at 960x1080 and 1920x2160 per eye
// was 1.13 and 3.83 GB, 870 bytes per eye pixel between them (G-buffer layers and their
// read-back, traced images, denoiser textures, llvmpipe's copies).
constexpr double kBytesPerEyePixel = 870.0;

// UsageError naming the options when width x height eye buffers would need more than this
// machine's physical memory: the kernel would kill the process part-way instead.
void checkFrameFitsInMemory(int width, int height, const char* options);

}  // namespace photovr
