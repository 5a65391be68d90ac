#include "render/png_io.h"

#include <cstdio>
#include <filesystem>
#include <system_error>

// The implementations live in Debian's libstb (pkg-config stb), so no *_IMPLEMENTATION here:
// defining it as well would give two copies of every stbi_ symbol in the program.
#include <stb/stb_image.h>
#include <stb/stb_image_write.h>

#include "engine/base/error.h"

namespace mostyle::render {

void write_png(const Image& image, const std::string& path) {
  if (image.empty() || image.rgba.size() != static_cast<size_t>(image.width) * static_cast<size_t>(image.height) * 4) {
    throw InputError(path + ": cannot write PNG: the image is empty");
  }
  namespace fs = std::filesystem;
  const std::string temporary = path + ".tmp";
  if (!stbi_write_png(temporary.c_str(), image.width, image.height, 4, image.rgba.data(), image.width * 4)) {
    std::remove(temporary.c_str());
    throw InputError(path + ": cannot write PNG (is the folder there and writable?)");
  }
  std::error_code ec;
  fs::rename(temporary, path, ec);
  if (ec) {
    std::remove(temporary.c_str());
    throw InputError(path + ": cannot write PNG: " + ec.message());
  }
}

Image read_png(const std::string& path) {
  int width = 0, height = 0, channels = 0;
  unsigned char* pixels = stbi_load(path.c_str(), &width, &height, &channels, 4);
  if (pixels == nullptr) {
    const char* reason = stbi_failure_reason();
    throw InputError(path + ": cannot read PNG: " + (reason ? reason : "unknown error"));
  }
  Image image;
  image.width = width;
  image.height = height;
  image.rgba.assign(pixels, pixels + static_cast<size_t>(width) * static_cast<size_t>(height) * 4);
  stbi_image_free(pixels);
  return image;
}

}  // namespace mostyle::render
