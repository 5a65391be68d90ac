#pragma once
// Axis Neuron's (and Axis Studio's) "BVH broadcasting" in its string format: what the Perception
// Neuron plugins for Unity, Unreal and MotionBuilder read over TCP. One line per frame:
//   <avatar index> <avatar name> v1 v2 ... vN ||
// the values a BVH skeleton's channels in its file's order (degrees, the file's units). With
// Axis's "reference" option six more values come first (a reference root's position and
// rotation): a line of N + 6 values. Pure functions on text, no I/O: the sockets are the app's.
#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace mostyle {

constexpr int kAxisReferenceValues = 6;  // the "reference" option's leading values
// Significant digits of the values written: within 5e-7 of each value, relative.
constexpr int kAxisValueDigits = 7;

struct AxisFrame {
  int avatar_index = 0;
  std::string avatar_name;         // one token, never empty
  std::vector<double> reference;   // empty, or the kAxisReferenceValues leading values
  std::vector<double> values;      // the channel values, as many as the skeleton has channels
};

enum class AxisLineStatus {
  kOk,
  kBlank,        // nothing but whitespace: not a frame, not an error
  kMalformed,    // *reason says why
};

// Parses one line (without its line end; a trailing '\r' and whitespace anywhere are
// tolerated, and "||" may touch the last value) into *frame, whose vectors are reused (no
// allocation once they hold a line's values). `channels` is N, the skeleton's channel count.
// kMalformed, with a clause in *reason (e.g. "expected 96 values (102 with a reference), found
// 95", "value 7 is not a finite number: 'nan'", "the line does not end in '||'"), when the line
// is not a frame: *frame is then unspecified. O(length).
AxisLineStatus parse_axis_line(std::string_view line, int channels, AxisFrame* frame, std::string* reason);

// Appends one line, "<index> <name> [reference] values ||\n", to *out. The reference (when
// non-empty) is written as it came (shortest text that reads back as the same double), the
// values with kAxisValueDigits significant digits, trailing zeros dropped ("12.5", "-0.0001234",
// "1.234568e+07"). `name` must be one token (no whitespace). O(count).
void append_axis_line(std::string* out, int avatar_index, std::string_view name, const double* reference,
                      int reference_count, const double* values, int count);

// A value as append_axis_line writes it (kAxisValueDigits significant digits; digits 0: the
// shortest text that reads back exactly).
void append_axis_number(std::string* out, double value, int digits = kAxisValueDigits);

// Cuts a TCP byte stream into lines. A line ends at '\n' (a '\r' before it is dropped) or just
// after "||" (Axis ends each frame with "||"; whether a line end follows it varies); lines of
// whitespace only are skipped. A line longer than max_line_bytes is dropped whole (its bytes
// skipped up to its end) and counted, so the memory held stays within max_line_bytes however
// the bytes come.
class AxisLineSplitter {
 public:
  explicit AxisLineSplitter(size_t max_line_bytes = size_t{1} << 16);

  // Takes bytes from the front of *chunk until a line is complete: returns true with *line set
  // (valid until the next call), or false once *chunk is used up (a partial line is kept for the
  // next chunk). Call it again with what is left of *chunk until it returns false.
  bool next(std::string_view* chunk, std::string_view* line);

  // The 1-based number of the last line returned, counting line ends ('\n') in the stream.
  long long line_number() const { return line_number_; }
  // Lines dropped as longer than max_line_bytes, and the number of the last one.
  long long dropped() const { return dropped_; }
  long long dropped_line_number() const { return dropped_line_number_; }
  // Whether a partial line is held (the stream ended in the middle of a line when it closes).
  bool has_partial() const { return !buffer_.empty() || discarding_; }
  // Forgets a partial line and the counts: a new stream.
  void reset();

 private:
  // Ends the current line: what is buffered and the first `end` bytes of *chunk; consumes
  // `consumed` bytes of *chunk (end + 1 when a '\n' ends the line). False when the line is
  // blank or too long (then dropped and counted).
  bool finish(std::string_view* chunk, size_t end, size_t consumed, std::string_view* line);

  size_t max_line_bytes_;
  std::string buffer_;         // the start of a line that began in an earlier chunk
  bool discarding_ = false;    // inside a line that is too long
  bool last_bar_ = false;      // the last byte taken was '|' (a "||" may span two chunks)
  bool clear_buffer_ = false;  // the last line returned is buffer_: clear it at the next call
  long long newlines_ = 0;    // line ends seen
  long long start_line_ = 1;  // line number where the current line started
  long long line_number_ = 0;
  long long dropped_ = 0;
  long long dropped_line_number_ = 0;
};

}  // namespace mostyle
