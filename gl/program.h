// GLSL program built from shader files, with the #version line and defines prepended.
#pragma once

#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace photovr::gl {

class Program {
 public:
  struct Stage {
    unsigned type;     // GL_VERTEX_SHADER, GL_FRAGMENT_SHADER, GL_COMPUTE_SHADER
    std::string file;  // in shaders/
  };
  // Throws ContextError with the file name and the compiler's log on failure.
  Program(const std::vector<Stage>& stages, const std::vector<std::string>& defines);
  ~Program();
  Program(const Program&) = delete;
  Program& operator=(const Program&) = delete;

  unsigned id() const { return id_; }
  void use() const;
  int uniform(const char* name) const;  // -1 if absent (optimised away)
  void set(const char* name, unsigned value) const;
  void set(const char* name, int value) const;
  void set(const char* name, float value) const;

 private:
  unsigned id_ = 0;
};

}  // namespace photovr::gl
