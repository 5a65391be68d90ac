#pragma once
// A static indexed triangle mesh drawn many times per call, each instance with its own few
// vec4 attributes (a quad per joint sphere, a tube per bone, a quad per shadow blob). Vertex
// attribute 0 is the mesh's vec3 position; attributes 1..n are the instance's vec4s.
// Needs a current GL context for every call and for destruction. Move-only.
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "render/gl.h"

namespace mostyle::render {

class InstancedMesh {
 public:
  InstancedMesh() = default;
  // vertices: mesh positions; indices: triangles (3 per); vec4s_per_instance in [1, 8].
  InstancedMesh(const std::vector<glm::vec3>& vertices, const std::vector<std::uint32_t>& indices,
                int vec4s_per_instance);
  ~InstancedMesh();
  InstancedMesh(InstancedMesh&& other) noexcept;
  InstancedMesh& operator=(InstancedMesh&& other) noexcept;
  InstancedMesh(const InstancedMesh&) = delete;
  InstancedMesh& operator=(const InstancedMesh&) = delete;

  // Draws the mesh once per instance; `instances` holds vec4s_per_instance vec4s per
  // instance, its size a multiple of that. Uploads them (streamed) first. O(instances).
  void draw(const std::vector<glm::vec4>& instances) const;

 private:
  void release();
  GLuint vao_ = 0, vertex_buffer_ = 0, index_buffer_ = 0, instance_buffer_ = 0;
  GLsizei index_count_ = 0;
  int vec4s_per_instance_ = 1;
};

// Open cylinder side: x = cos, z = sin of the angle (radius 1), y in {0, 1} (start, end).
void make_unit_tube(int slices, std::vector<glm::vec3>* vertices, std::vector<std::uint32_t>* indices);
// Disc in the xz plane, radius 1 around the origin, `segments` sides, facing +y, with a ring
// of vertices at each of `ring_radii` (increasing, the last 1).
void make_unit_disc(int segments, const std::vector<float>& ring_radii, std::vector<glm::vec3>* vertices,
                    std::vector<std::uint32_t>* indices);
// Quad in the xz plane, [-1, 1]^2 at y = 0, facing +y.
void make_unit_quad(std::vector<glm::vec3>* vertices, std::vector<std::uint32_t>* indices);

}  // namespace mostyle::render
