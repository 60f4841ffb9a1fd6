#include "trace/texture_sampling.h"

#include <array>
#include <cmath>

#include "core/image_io.h"

namespace photovr {
namespace {

int wrapIndex(int i, int n, Texture::Wrap mode) {
  // Inside the texture every mode is the identity; only outside it need Repeat and Mirror
  // run an integer division, which the texel's address waits on.
  if (unsigned(i) < unsigned(n)) return i;
  switch (mode) {
    case Texture::Wrap::Clamp:
      return i < 0 ? 0 : (i >= n ? n - 1 : i);
    case Texture::Wrap::Mirror: {
      const int period = 2 * n;
      int m = i % period;
      if (m < 0) m += period;
      return m < n ? m : period - 1 - m;
    }
    default: {
      const int m = i % n;
      return m < 0 ? m + n : m;
    }
  }
}

// 8-bit channel -> [0, 1], plain and sRGB-decoded: the same float expressions the texel
// fetch used to evaluate per channel (so results are bit-identical), looked up instead of
// calling std::pow 12 times per bilinear sample (the top texture cost in the atrium profile).
using ChannelTable = std::array<float, 256>;
ChannelTable makeChannelTable(bool srgb) {
  ChannelTable t;
  for (int i = 0; i < 256; ++i) t[i] = srgb ? srgbToLinear(float(i) / 255.0f) : float(i) / 255.0f;
  return t;
}
const ChannelTable kLinearChannel = makeChannelTable(false);
const ChannelTable kSrgbChannel = makeChannelTable(true);

// The texel at wrapped coordinates (x, y) already inside the texture.
glm::vec4 texelAt(const Texture& t, int x, int y, bool srgb) {
  const uint8_t* p = &t.rgba[(size_t(y) * t.width + size_t(x)) * 4];
  const ChannelTable& colour = srgb ? kSrgbChannel : kLinearChannel;
  return glm::vec4(colour[p[0]], colour[p[1]], colour[p[2]], kLinearChannel[p[3]]);
}

glm::vec4 texel(const Texture& t, int x, int y, bool srgb) {
  return texelAt(t, wrapIndex(x, t.width, t.wrapS), wrapIndex(y, t.height, t.wrapT), srgb);
}

// fmod(x, 4096): x itself inside (-4096, 4096), as fmod returns it there exactly, without the
// libm call that every other coordinate would pay.
float saneRange(float x) {
  return std::abs(x) < 4096.0f ? x : std::fmod(x, 4096.0f);
}

}  // namespace

glm::vec4 sampleTexture(const Texture& t, glm::vec2 uv, bool srgb) {
  if (t.width <= 0 || t.height <= 0 || !std::isfinite(uv.x) || !std::isfinite(uv.y))
    return glm::vec4(0.0f, 0.0f, 0.0f, 1.0f);
  // Keep uv in a sane range before converting to int: wrap modes are periodic anyway.
  const glm::vec2 p = glm::vec2(saneRange(uv.x) * t.width, saneRange(uv.y) * t.height);
  if (t.nearest) return texel(t, int(std::floor(p.x)), int(std::floor(p.y)), srgb);
  const glm::vec2 q = p - 0.5f;
  const int x0 = int(std::floor(q.x)), y0 = int(std::floor(q.y));
  const float fx = q.x - float(x0), fy = q.y - float(y0);
  // The four texels share two columns and two rows: wrap each once.
  const int xa = wrapIndex(x0, t.width, t.wrapS), xb = wrapIndex(x0 + 1, t.width, t.wrapS);
  const int ya = wrapIndex(y0, t.height, t.wrapT), yb = wrapIndex(y0 + 1, t.height, t.wrapT);
  // GL filters sRGB textures after decoding (EXT_texture_sRGB), so decode per texel first.
  const glm::vec4 top = glm::mix(texelAt(t, xa, ya, srgb), texelAt(t, xb, ya, srgb), fx);
  const glm::vec4 bottom = glm::mix(texelAt(t, xa, yb, srgb), texelAt(t, xb, yb, srgb), fx);
  return glm::mix(top, bottom, fy);
}

glm::vec4 sampleSlotTexture(const Scene& scene, const TextureRef& ref, glm::vec2 uv0, glm::vec2 uv1,
                            bool srgb, glm::vec4 fallback) {
  if (!ref.valid() || ref.texture >= int(scene.textures.size())) return fallback;
  const glm::vec2 uv = ref.texCoord == 1 ? uv1 : uv0;
  // An identity transform leaves finite coordinates as they are (and sampleTexture returns
  // its black for every non-finite pair either way): no matrix built per sample.
  const glm::vec2 t =
      ref.transform.isIdentity() ? uv : glm::vec2(ref.transform.matrix() * glm::vec3(uv, 1.0f));
  return sampleTexture(scene.textures[ref.texture], t, srgb);
}

}  // namespace photovr
