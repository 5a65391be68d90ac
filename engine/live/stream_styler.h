#pragma once
// A motion-capture stream's bytes styled line by line as they come (Axis Neuron's "BVH
// broadcasting", axis_stream.h): cut into lines, each parsed, the first frame's avatar the one
// styled, styled (live_style.h), held to finite values. What becomes of each line is the
// caller's: `mostyle-cli live` serves and records it, the editor's Live source keeps it in its
// window. Both read a stream through this one loop. No I/O: the bytes are handed in.
#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include "engine/live/axis_stream.h"
#include "engine/live/live_style.h"

namespace mostyle {

// The longest line a stream of `channels` values is read with: each value in up to 64 bytes (a
// long decimal), with room for a reference and the avatar; 64 KB at least.
size_t max_stream_line_bytes(int channels);

class StreamStyler {
 public:
  // What the lines come to, one call per line, in the stream's order.
  class Sink {
   public:
    virtual ~Sink() = default;
    // The styler for the next frame, asked before each (a styler made from new takes may take
    // over between two frames).
    virtual LiveStyle& styler() = 0;
    // A frame styled: `frame` as it came (avatar, reference, values), `styled` its channels'
    // styled values (as many, all finite). Both valid during the call only.
    virtual void styled(const AxisFrame& frame, const double* styled) = 0;
    // A line that gave no styled frame: its 1-based number in the stream and why, one clause
    // ("the line is longer than 65536 bytes").
    virtual void skipped(long long line, const std::string& why) = 0;
  };

  // channels: the stream skeleton's channel count (values per frame).
  explicit StreamStyler(int channels);

  // The stream's next bytes, every line they complete handled in turn: a line that is not a
  // frame (malformed), another avatar's than the first frame's, or one whose styled frame holds
  // a value that is not finite, skipped; the others styled. Then the lines found too long
  // (max_stream_line_bytes), skipped. A partial line waits for the next bytes. A frame costs
  // what LiveStyle::style_frame does, with no allocation once a line's values are held (a skip
  // makes its clause); memory bounded by one line.
  void feed(std::string_view bytes, Sink& sink);
  // The stream closed: a line it ended inside is skipped.
  void end(Sink& sink);
  // The next bytes are a new stream's: its lines numbered from 1, its first frame's avatar styled.
  void restart();

 private:
  void style_line(std::string_view line, Sink& sink);

  int channels_;
  size_t max_line_bytes_;
  AxisLineSplitter splitter_;
  AxisFrame frame_;
  std::string reason_;
  std::vector<double> styled_;
  int avatar_ = -1;          // the avatar styled, -1 until the first frame
  long long dropped_ = 0;    // the splitter's dropped lines already said
};

}  // namespace mostyle
