#pragma once
// A headless OpenGL 3.3 core context for render tests: OSMesa (llvmpipe) drawing into a
// buffer in memory, made current on construction. One per test case; not thread-safe.
#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace mostyle::test {

class OsMesaContext {
 public:
  explicit OsMesaContext(const glm::ivec2& size);
  ~OsMesaContext();
  OsMesaContext(const OsMesaContext&) = delete;
  OsMesaContext& operator=(const OsMesaContext&) = delete;

  bool ok() const { return context_ != nullptr; }
  const std::string& error() const { return error_; }
  glm::ivec2 size() const { return size_; }

 private:
  void* context_ = nullptr;  // OSMesaContext
  std::vector<std::uint8_t> buffer_;
  glm::ivec2 size_;
  std::string error_;
};

}  // namespace mostyle::test
