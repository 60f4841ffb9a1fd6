#include "trace/trace_output.h"

#include <algorithm>

#include "core/parallel_ranges.h"
#include "core/tonemap.h"

namespace photovr {
namespace {

void meanInto(std::vector<glm::vec3>& sum, const std::vector<glm::vec3>& frame, float w) {
  glm::vec3* s = sum.data();  // the data pointers held in registers, not reloaded per pixel
  const glm::vec3* f = frame.data();
  parallelRanges(std::min(sum.size(), frame.size()), [=](size_t begin, size_t end) {
    for (size_t i = begin; i < end; ++i) s[i] += (f[i] - s[i]) * w;
  });
}

}  // namespace

void accumulate(EyeImage& sum, const EyeImage& frame, int framesSoFar) {
  if (framesSoFar == 0) {
    sum = frame;
    return;
  }
  const float w = 1.0f / float(framesSoFar + 1);
  for (EyePlane plane : kAveragedPlanes) meanInto(sum.*plane, frame.*plane, w);
  parallelRanges(sum.samples.size(), [&](size_t begin, size_t end) {
    for (size_t i = begin; i < end; ++i) sum.samples[i] += frame.samples[i];
  });
  sum.rays += frame.rays;
  sum.rejectedSamples += frame.rejectedSamples;
}

ImageF toImage(const std::vector<glm::vec3>& values, int w, int h) {
  ImageF img(w, h, 3);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const glm::vec3& v = values[size_t(h - 1 - y) * w + x];
      float* d = img.at(x, y);
      d[0] = v.x, d[1] = v.y, d[2] = v.z;
    }
  return img;
}

ImageF toImage(const std::vector<float>& values, int w, int h) {
  ImageF img(w, h, 1);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) *img.at(x, y) = values[size_t(h - 1 - y) * w + x];
  return img;
}

std::vector<OutputFile> eyeImageFiles(const EyeImage& e, const std::string& dir) {
  std::vector<OutputFile> files;
  auto rgb = [&](const char* name, const std::vector<glm::vec3>& v) {
    if (v.empty()) return;
    files.push_back({dir + "/" + name, [&e, &v](const std::string& path) {
                       writeImage(path, toImage(v, e.width, e.height));
                     }});
  };
  rgb("color.exr", e.color);
  rgb("albedo.exr", e.albedo);
  rgb("normal.exr", e.normal);
  files.push_back({dir + "/depth.exr", [&e](const std::string& path) {
                     writeImage(path, toImage(e.depth, e.width, e.height));
                   }});
  files.push_back({dir + "/samples.exr", [&e](const std::string& path) {
                     const std::vector<float> samples(e.samples.begin(), e.samples.end());
                     writeImage(path, toImage(samples, e.width, e.height));
                   }});
  rgb("diffuse.exr", e.diffuse);
  rgb("specular.exr", e.specular);
  rgb("diffuse_albedo.exr", e.diffuseAlbedo);
  rgb("specular_albedo.exr", e.specularAlbedo);
  return files;
}

Image8 sideBySide(const std::vector<const EyeImage*>& eyes, float exposure) {
  const int w = eyes[0]->width, h = eyes[0]->height;
  Image8 out(w * int(eyes.size()), h, 3);
  for (size_t e = 0; e < eyes.size(); ++e)
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        const glm::u8vec3 c = displayColor(eyes[e]->color[size_t(h - 1 - y) * w + x], exposure);
        uint8_t* d = out.at(int(e) * w + x, y);
        d[0] = c.r, d[1] = c.g, d[2] = c.b;
      }
  return out;
}

}  // namespace photovr
