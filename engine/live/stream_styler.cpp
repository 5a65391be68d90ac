#include "engine/live/stream_styler.h"

#include <algorithm>
#include <cmath>

namespace mostyle {

size_t max_stream_line_bytes(int channels) {
  return std::max<size_t>(size_t{1} << 16, static_cast<size_t>(channels + kAxisReferenceValues) * 64 + 1024);
}

StreamStyler::StreamStyler(int channels)
    : channels_(channels),
      max_line_bytes_(max_stream_line_bytes(channels)),
      splitter_(max_line_bytes_),
      styled_(static_cast<size_t>(channels)) {}

void StreamStyler::feed(std::string_view bytes, Sink& sink) {
  std::string_view line;
  while (splitter_.next(&bytes, &line)) style_line(line, sink);
  for (; dropped_ < splitter_.dropped(); ++dropped_)
    sink.skipped(splitter_.dropped_line_number(),
                 "the line is longer than " + std::to_string(max_line_bytes_) + " bytes");
}

void StreamStyler::end(Sink& sink) {
  if (splitter_.has_partial()) sink.skipped(splitter_.line_number() + 1, "the stream ended inside a line");
}

void StreamStyler::restart() {
  splitter_.reset();
  avatar_ = -1;
  dropped_ = 0;
}

void StreamStyler::style_line(std::string_view line, Sink& sink) {
  const long long number = splitter_.line_number();
  if (parse_axis_line(line, channels_, &frame_, &reason_) != AxisLineStatus::kOk) return sink.skipped(number, reason_);
  // A stream may carry several avatars; the first one seen is the performer styled.
  if (avatar_ < 0) avatar_ = frame_.avatar_index;
  if (frame_.avatar_index != avatar_)
    return sink.skipped(number, "avatar " + std::to_string(frame_.avatar_index) + " is not the one styled (" +
                                    std::to_string(avatar_) + ")");
  sink.styler().style_frame(frame_.values.data(), styled_.data());
  for (double v : styled_)
    if (!std::isfinite(v)) return sink.skipped(number, "the styled frame holds a value that is not a finite number");
  sink.styled(frame_, styled_.data());
}

}  // namespace mostyle
