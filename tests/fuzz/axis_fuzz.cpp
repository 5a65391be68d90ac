// libFuzzer target: the bytes as an Axis Neuron BVH broadcasting stream (AxisLineSplitter,
// parse_axis_line, append_axis_line). Built and run by tests/fuzz/run.sh; the checks are in
// fuzz_readers.cpp.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "tests/fuzz/fuzz_readers.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  mostyle::fuzz::read_axis_stream(std::string_view(reinterpret_cast<const char*>(data), size));
  return 0;
}
