// G-buffer read-backs turned into files: per eye depth.exr (reversed-Z, linear float, as
// the compositor consumes it), normal.png, albedo.png, ids.png, and a side-by-side
// gbuffer.png mosaic for people.
#pragma once

#include <string>
#include <vector>

#include "core/image_io.h"
#include "gl/gbuffer.h"

namespace photovr::app {

// Images are flipped from GL's bottom-up rows to top-down files here.
ImageF depthImage(const gl::GBufferImage& g);
Image8 normalImage(const gl::GBufferImage& g);   // n * 0.5 + 0.5, background black
Image8 albedoImage(const gl::GBufferImage& g);   // sRGB-encoded base colour
Image8 idImage(const gl::GBufferImage& g);       // false colour per instance
Image8 depthPreview(const gl::GBufferImage& g);  // depth scaled to the image's range

// Albedo | normal over ids | depth, per eye at half size; eyes side by side.
Image8 gbufferMosaic(const gl::GBufferImage& left, const gl::GBufferImage* right);

// Writes the per-eye files into 'dir' and returns their paths.
std::vector<std::string> writeEyeFiles(const gl::GBufferImage& g, const std::string& dir);

}  // namespace photovr::app
