#include "core/environment_io.h"

#include <cmath>
#include <filesystem>

#include "core/error.h"
#include "core/image_io.h"

namespace photovr {
namespace {

glm::vec3 rgbAt(const ImageF& image, int x, int y) {
  const float* p = image.at(x, y);
  return image.channels >= 3 ? glm::vec3(p[0], p[1], p[2]) : glm::vec3(p[0]);
}

bool validRadiance(const glm::vec3& c) {
  return std::isfinite(c.x) && std::isfinite(c.y) && std::isfinite(c.z) && c.x >= 0.0f &&
         c.y >= 0.0f && c.z >= 0.0f;
}

std::string describe(const glm::vec3& c) {
  return "(" + std::to_string(c.x) + ", " + std::to_string(c.y) + ", " + std::to_string(c.z) + ")";
}

// OpenImageIO's error text can span lines; the error policy wants one.
ImageF readOneLineErrors(const std::string& path) {
  try {
    return readImageF(path);
  } catch (const InputError& e) {
    const std::string what = e.what();
    throw InputError("", what.substr(0, what.find('\n')));
  }
}

}  // namespace

Environment loadEnvironment(const std::string& path, std::string* warning) {
  const ImageF image = readOneLineErrors(path);
  Environment env;
  env.type = Environment::Type::Map;
  env.name = std::filesystem::path(path).filename().string();
  env.width = image.width;
  env.height = image.height;
  env.pixels.resize(size_t(image.width) * image.height);
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      const glm::vec3 c = rgbAt(image, x, y);
      if (!validRadiance(c))
        throw InputError(path, "pixel (" + std::to_string(x) + ", " + std::to_string(y) +
                                   ") is negative or not finite " + describe(c) +
                                   "; radiance must be finite and >= 0");
      env.pixels[size_t(y) * image.width + x] = c;
    }
  if (warning) warning->clear();
  // Equirectangular maps span 360 x 180 degrees; another aspect means texels are stretched.
  if (warning && image.width != 2 * image.height)
    *warning = path + ": " + std::to_string(image.width) + "x" + std::to_string(image.height) +
               " is not 2:1, stretched to the equirectangular sphere";
  return env;
}

}  // namespace photovr
