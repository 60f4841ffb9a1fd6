#include "gl/panel_output.h"

#include <algorithm>
#include <string>

#include "core/error.h"
#include "gl/context.h"
#include "gl/gl_api.h"

namespace photovr::gl {

constexpr int kGroup = 8;  // panel_output.comp local size

int checkPanelRotation(int degrees) {
  if (degrees != 0 && degrees != 90 && degrees != 180 && degrees != 270)
    throw UsageError("panel rotation: " + std::to_string(degrees) +
                     " is not one of 0, 90, 180, 270");
  return degrees;
}

PanelOutput::PanelOutput(int panelWidth, int panelHeight, int rotationDegrees)
    : panelWidth_(panelWidth),
      panelHeight_(panelHeight),
      rotation_(checkPanelRotation(rotationDegrees)),
      size_(rotatedSize(rotationDegrees, panelWidth, panelHeight)),
      program_({{GL_COMPUTE_SHADER, "panel_output.comp"}}, {}) {
  if (panelWidth < 1 || panelHeight < 1) throw UsageError("panel output: empty panel");
  api::CreateTextures(GL_TEXTURE_2D, 1, &output_);
  api::TextureStorage2D(output_, 1, GL_RGBA8, size_.x, size_.y);
  api::TextureParameteri(output_, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  api::TextureParameteri(output_, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  api::CreateFramebuffers(1, &fbo_);
  api::NamedFramebufferTexture(fbo_, GL_COLOR_ATTACHMENT0, output_, 0);
}

PanelOutput::~PanelOutput() {
  api::DeleteTextures(1, &output_);
  api::DeleteFramebuffers(1, &fbo_);
}

void PanelOutput::run(unsigned linearPanel, float exposure) {
  program_.use();
  const GLuint id = program_.id();
  api::ProgramUniform2i(id, program_.uniform("uPanelSize"), panelWidth_, panelHeight_);
  program_.set("uRotation", rotation_);
  program_.set("uExposure", exposure);
  api::BindTextureUnit(0, linearPanel);
  api::BindImageTexture(0, output_, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA8);
  api::DispatchCompute(GLuint((size_.x + kGroup - 1) / kGroup),
                       GLuint((size_.y + kGroup - 1) / kGroup), 1);
  api::MemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT |
                     GL_FRAMEBUFFER_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
}

std::vector<glm::u8vec4> PanelOutput::read() const {
  std::vector<glm::u8vec4> out(size_t(size_.x) * size_.y);
  api::PixelStorei(GL_PACK_ALIGNMENT, 1);
  api::GetTextureSubImage(output_, 0, 0, 0, 0, size_.x, size_.y, 1, GL_RGBA, GL_UNSIGNED_BYTE,
                          GLsizei(out.size() * sizeof(glm::u8vec4)), out.data());
  return out;
}

void PanelOutput::present(int windowWidth, int windowHeight) const {
  const GLfloat black[4] = {0, 0, 0, 1};
  api::ClearNamedFramebufferfv(0, GL_COLOR, 0, black);
  // Largest rectangle of the output's aspect that fits, centred.
  const double scale = std::min(double(windowWidth) / size_.x, double(windowHeight) / size_.y);
  const int w = int(size_.x * scale), h = int(size_.y * scale);
  const int x0 = (windowWidth - w) / 2, y0 = (windowHeight - h) / 2;
  api::BlitNamedFramebuffer(fbo_, 0, 0, 0, size_.x, size_.y, x0, y0, x0 + w, y0 + h,
                            GL_COLOR_BUFFER_BIT, GL_LINEAR);
}

void waitForGpu() {
  api::Finish();
}

std::vector<glm::u8vec4> readDefaultFramebuffer(int width, int height) {
  std::vector<glm::u8vec4> out(size_t(width) * height);
  api::BindFramebuffer(GL_FRAMEBUFFER, 0);
  api::PixelStorei(GL_PACK_ALIGNMENT, 1);
  api::ReadPixels(0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, out.data());
  return out;
}

}  // namespace photovr::gl
