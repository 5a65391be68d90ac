// libFuzzer target: any take (BVH, glTF or FBX bytes) written as FBX and GLB and read back
// (fuzz_readers.h write_read_back). Built and run by tests/fuzz/run.sh; the checks are in
// fuzz_readers.cpp.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "tests/fuzz/fuzz_readers.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  mostyle::fuzz::write_read_back(std::string_view(reinterpret_cast<const char*>(data), size));
  return 0;
}
