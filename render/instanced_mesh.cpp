#include "render/instanced_mesh.h"

#include <cassert>
#include <cmath>
#include <utility>

namespace mostyle::render {

InstancedMesh::InstancedMesh(const std::vector<glm::vec3>& vertices,
                             const std::vector<std::uint32_t>& indices, int vec4s_per_instance)
    : index_count_(static_cast<GLsizei>(indices.size())), vec4s_per_instance_(vec4s_per_instance) {
  assert(vec4s_per_instance >= 1 && vec4s_per_instance <= 8);
  glGenVertexArrays(1, &vao_);
  glBindVertexArray(vao_);

  glGenBuffers(1, &vertex_buffer_);
  glBindBuffer(GL_ARRAY_BUFFER, vertex_buffer_);
  glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(vertices.size() * sizeof(glm::vec3)),
               vertices.data(), GL_STATIC_DRAW);
  glEnableVertexAttribArray(0);
  glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, sizeof(glm::vec3), nullptr);

  glGenBuffers(1, &index_buffer_);
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, index_buffer_);
  glBufferData(GL_ELEMENT_ARRAY_BUFFER, static_cast<GLsizeiptr>(indices.size() * sizeof(std::uint32_t)),
               indices.data(), GL_STATIC_DRAW);

  glGenBuffers(1, &instance_buffer_);
  glBindBuffer(GL_ARRAY_BUFFER, instance_buffer_);
  const GLsizei stride = static_cast<GLsizei>(vec4s_per_instance * sizeof(glm::vec4));
  for (int i = 0; i < vec4s_per_instance; ++i) {
    GLuint attribute = static_cast<GLuint>(1 + i);
    glEnableVertexAttribArray(attribute);
    glVertexAttribPointer(attribute, 4, GL_FLOAT, GL_FALSE, stride,
                          reinterpret_cast<const void*>(static_cast<uintptr_t>(i * sizeof(glm::vec4))));
    glVertexAttribDivisor(attribute, 1);
  }
  glBindVertexArray(0);
  glBindBuffer(GL_ARRAY_BUFFER, 0);
}

InstancedMesh::~InstancedMesh() { release(); }

void InstancedMesh::release() {
  if (vao_ != 0) glDeleteVertexArrays(1, &vao_);
  GLuint buffers[] = {vertex_buffer_, index_buffer_, instance_buffer_};
  if (vertex_buffer_ != 0) glDeleteBuffers(3, buffers);
  vao_ = vertex_buffer_ = index_buffer_ = instance_buffer_ = 0;
}

InstancedMesh::InstancedMesh(InstancedMesh&& o) noexcept
    : vao_(std::exchange(o.vao_, 0)),
      vertex_buffer_(std::exchange(o.vertex_buffer_, 0)),
      index_buffer_(std::exchange(o.index_buffer_, 0)),
      instance_buffer_(std::exchange(o.instance_buffer_, 0)),
      index_count_(o.index_count_),
      vec4s_per_instance_(o.vec4s_per_instance_) {}

InstancedMesh& InstancedMesh::operator=(InstancedMesh&& o) noexcept {
  if (this != &o) {
    release();
    vao_ = std::exchange(o.vao_, 0);
    vertex_buffer_ = std::exchange(o.vertex_buffer_, 0);
    index_buffer_ = std::exchange(o.index_buffer_, 0);
    instance_buffer_ = std::exchange(o.instance_buffer_, 0);
    index_count_ = o.index_count_;
    vec4s_per_instance_ = o.vec4s_per_instance_;
  }
  return *this;
}

void InstancedMesh::draw(const std::vector<glm::vec4>& instances) const {
  assert(instances.size() % static_cast<size_t>(vec4s_per_instance_) == 0);
  const GLsizei count = static_cast<GLsizei>(instances.size() / static_cast<size_t>(vec4s_per_instance_));
  if (count == 0 || vao_ == 0) return;
  glBindBuffer(GL_ARRAY_BUFFER, instance_buffer_);
  const GLsizeiptr bytes = static_cast<GLsizeiptr>(instances.size() * sizeof(glm::vec4));
  glBufferData(GL_ARRAY_BUFFER, bytes, nullptr, GL_STREAM_DRAW);  // orphan: no stall on the last use
  glBufferSubData(GL_ARRAY_BUFFER, 0, bytes, instances.data());
  glBindVertexArray(vao_);
  glDrawElementsInstanced(GL_TRIANGLES, index_count_, GL_UNSIGNED_INT, nullptr, count);
  glBindVertexArray(0);
  glBindBuffer(GL_ARRAY_BUFFER, 0);
}

void make_unit_tube(int slices, std::vector<glm::vec3>* vertices, std::vector<std::uint32_t>* indices) {
  vertices->clear();
  indices->clear();
  const float pi = 3.14159265358979f;
  for (int end = 0; end <= 1; ++end) {
    for (int i = 0; i <= slices; ++i) {
      float theta = 2.0f * pi * static_cast<float>(i) / static_cast<float>(slices);
      vertices->emplace_back(std::cos(theta), static_cast<float>(end), std::sin(theta));
    }
  }
  const std::uint32_t row = static_cast<std::uint32_t>(slices + 1);
  for (std::uint32_t i = 0; i < static_cast<std::uint32_t>(slices); ++i) {
    std::uint32_t a = i, b = i + row;
    indices->insert(indices->end(), {a, b, a + 1, a + 1, b, b + 1});
  }
}

void make_unit_disc(int segments, const std::vector<float>& ring_radii, std::vector<glm::vec3>* vertices,
                    std::vector<std::uint32_t>* indices) {
  vertices->assign(1, glm::vec3(0.0f));
  indices->clear();
  const float pi = 3.14159265358979f;
  const std::uint32_t n = static_cast<std::uint32_t>(segments);
  for (float r : ring_radii) {
    for (int i = 0; i < segments; ++i) {
      float theta = 2.0f * pi * static_cast<float>(i) / static_cast<float>(segments);
      vertices->emplace_back(r * std::cos(theta), 0.0f, r * std::sin(theta));
    }
  }
  for (std::uint32_t i = 0; i < n; ++i) indices->insert(indices->end(), {0, 1 + (i + 1) % n, 1 + i});
  for (std::uint32_t ring = 1; ring < ring_radii.size(); ++ring) {
    const std::uint32_t inner = 1 + (ring - 1) * n, outer = 1 + ring * n;
    for (std::uint32_t i = 0; i < n; ++i) {
      std::uint32_t j = (i + 1) % n;
      indices->insert(indices->end(), {inner + i, inner + j, outer + i, inner + j, outer + j, outer + i});
    }
  }
}

void make_unit_quad(std::vector<glm::vec3>* vertices, std::vector<std::uint32_t>* indices) {
  *vertices = {{-1, 0, -1}, {1, 0, -1}, {1, 0, 1}, {-1, 0, 1}};
  *indices = {0, 2, 1, 0, 3, 2};
}

}  // namespace mostyle::render
