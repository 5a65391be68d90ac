#pragma once
// A linked GLSL program (vertex + fragment) and uniform setters. Needs a current GL context
// for construction, use and destruction. Move-only.
#include <string>

#include <glm/glm.hpp>

#include "render/gl.h"

namespace mostyle::render {

class ShaderProgram {
 public:
  ShaderProgram() = default;
  // Compiles and links. `name` appears in messages. Throws std::runtime_error with the
  // driver's log when a stage fails to compile or the program fails to link (a bug of ours:
  // the sources are fixed strings).
  ShaderProgram(const std::string& name, const char* vertex_source, const char* fragment_source);
  ~ShaderProgram();
  ShaderProgram(ShaderProgram&& other) noexcept;
  ShaderProgram& operator=(ShaderProgram&& other) noexcept;
  ShaderProgram(const ShaderProgram&) = delete;
  ShaderProgram& operator=(const ShaderProgram&) = delete;

  GLuint id() const { return id_; }
  void use() const { glUseProgram(id_); }

  // Setters on the program in use; a name the linker dropped (unused) is ignored.
  GLint location(const char* uniform) const { return glGetUniformLocation(id_, uniform); }
  void set(const char* uniform, int value) const;
  void set(const char* uniform, float value) const;
  void set(const char* uniform, const glm::vec2& value) const;
  void set(const char* uniform, const glm::vec3& value) const;
  void set(const char* uniform, const glm::vec4& value) const;
  void set(const char* uniform, const glm::mat4& value) const;

 private:
  GLuint id_ = 0;
};

}  // namespace mostyle::render
