#include "gl/program.h"

#include "gl/context.h"
#include "gl/gl_api.h"
#include "gl/shader_source.h"

namespace photovr::gl {
namespace {

std::string shaderLog(GLuint shader) {
  GLint len = 0;
  api::GetShaderiv(shader, GL_INFO_LOG_LENGTH, &len);
  std::string log(size_t(len > 0 ? len : 1), '\0');
  api::GetShaderInfoLog(shader, len, nullptr, log.data());
  return log;
}

GLuint compile(const Program::Stage& stage, const std::vector<std::string>& defines) {
  std::string text = "#version 450 core\n";
  for (const std::string& d : defines) text += "#define " + d + "\n";
  text += "#line 1\n" + shaderSource(stage.file);
  const GLuint shader = api::CreateShader(stage.type);
  const char* src = text.c_str();
  api::ShaderSource(shader, 1, &src, nullptr);
  api::CompileShader(shader);
  GLint ok = 0;
  api::GetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    const std::string log = shaderLog(shader);
    api::DeleteShader(shader);
    throw ContextError("shaders/" + stage.file + ": does not compile: " + log);
  }
  return shader;
}

}  // namespace

Program::Program(const std::vector<Stage>& stages, const std::vector<std::string>& defines) {
  id_ = api::CreateProgram();
  std::vector<GLuint> shaders;
  try {
    for (const Stage& s : stages) shaders.push_back(compile(s, defines));
  } catch (...) {
    for (GLuint s : shaders) api::DeleteShader(s);
    api::DeleteProgram(id_);
    throw;
  }
  for (GLuint s : shaders) api::AttachShader(id_, s);
  api::LinkProgram(id_);
  for (GLuint s : shaders) api::DeleteShader(s);
  GLint ok = 0;
  api::GetProgramiv(id_, GL_LINK_STATUS, &ok);
  if (!ok) {
    GLint len = 0;
    api::GetProgramiv(id_, GL_INFO_LOG_LENGTH, &len);
    std::string log(size_t(len > 0 ? len : 1), '\0');
    api::GetProgramInfoLog(id_, len, nullptr, log.data());
    api::DeleteProgram(id_);
    throw ContextError("shaders/" + stages.front().file + ": does not link: " + log);
  }
}

Program::~Program() {
  api::DeleteProgram(id_);
}

void Program::use() const {
  api::UseProgram(id_);
}
int Program::uniform(const char* name) const {
  return api::GetUniformLocation(id_, name);
}
void Program::set(const char* name, unsigned v) const {
  api::ProgramUniform1ui(id_, uniform(name), v);
}
void Program::set(const char* name, int v) const {
  api::ProgramUniform1i(id_, uniform(name), v);
}
void Program::set(const char* name, float v) const {
  api::ProgramUniform1f(id_, uniform(name), v);
}

}  // namespace photovr::gl
