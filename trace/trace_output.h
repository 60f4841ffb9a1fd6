// Traced eye images (pt and hybrid): accumulation over frames and the files written.
#pragma once

#include <string>
#include <vector>

#include "core/image_io.h"
#include "trace/path_tracer.h"

namespace photovr {

// The planes accumulate averages over frames (samples are summed; depth, normal and guide
// are the first frame's: frames share their view).
using EyePlane = std::vector<glm::vec3> EyeImage::*;
inline constexpr EyePlane kAveragedPlanes[] = {&EyeImage::color,         &EyeImage::albedo,
                                               &EyeImage::diffuse,       &EyeImage::specular,
                                               &EyeImage::diffuseAlbedo, &EyeImage::specularAlbedo};

// Running mean over frames of equal weight (frames share their settings).
void accumulate(EyeImage& sum, const EyeImage& frame, int framesSoFar);

// color.exr, albedo.exr, normal.exr, depth.exr, samples.exr, and where present the
// denoiser inputs diffuse.exr, specular.exr, diffuse_albedo.exr, specular_albedo.exr, in
// 'dir', for writeFiles (core/image_io.h); they refer to 'eye', which must outlive them.
std::vector<OutputFile> eyeImageFiles(const EyeImage& eye, const std::string& dir);

// The eyes side by side, tone-mapped for people.
Image8 sideBySide(const std::vector<const EyeImage*>& eyes, float exposure);

// Bottom-up rows (GL's and the tracer's) to a top-down float image.
ImageF toImage(const std::vector<glm::vec3>& values, int w, int h);
ImageF toImage(const std::vector<float>& values, int w, int h);

}  // namespace photovr
