#pragma once
// PNG files for screenshots and tests, through the packaged stb_image / stb_image_write.
#include <string>

#include "render/image.h"

namespace mostyle::render {

// Writes `image` as an RGBA PNG: to a temporary file beside `path`, then renamed over it, so
// a failure never leaves a partial file. Throws mostyle::InputError ("PATH: cannot write PNG")
// when the image is empty or the file cannot be written. O(width * height).
void write_png(const Image& image, const std::string& path);

// Reads any PNG as RGBA. Throws mostyle::InputError naming the file and stb's reason.
Image read_png(const std::string& path);

}  // namespace mostyle::render
