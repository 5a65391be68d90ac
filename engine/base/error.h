#pragma once
// The one error type for bad outside input (files, user parameters).
#include <stdexcept>
#include <string>
#include <string_view>

namespace mostyle {

// A full sentence that says where, e.g. "walk.bvh:42: expected CHANNELS, found '{'".
// Thrown by the engine, caught at the edges (CLI, worker, UI) and shown as it is.
class InputError : public std::runtime_error {
 public:
  explicit InputError(const std::string& message) : std::runtime_error(message) {}
};

// Bytes from a file as a message may show them: in quotes, printable ASCII as it is, every other
// byte as \xNN (so a NUL, a line end or invalid UTF-8 cannot cut or break the one line), at most
// max_length bytes of it, then "...". O(max_length).
inline std::string quoted_bytes(std::string_view bytes, size_t max_length = 40) {
  std::string out = "'";
  for (size_t i = 0; i < bytes.size() && i < max_length; ++i) {
    const unsigned char c = static_cast<unsigned char>(bytes[i]);
    if (c >= 32 && c < 127) {
      out += static_cast<char>(c);
    } else {
      static const char* kHex = "0123456789abcdef";
      out += "\\x";
      out += kHex[c >> 4];
      out += kHex[c & 15];
    }
  }
  if (bytes.size() > max_length) out += "...";
  return out + "'";
}

}  // namespace mostyle
