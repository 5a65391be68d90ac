#include "engine/live/axis_stream.h"

#include <charconv>
#include <cmath>
#include <cstring>

namespace mostyle {
namespace {

bool is_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\f' || c == '\v'; }

// The next whitespace-separated token of [*p, end), or an empty view at the end.
std::string_view next_token(const char** p, const char* end) {
  while (*p < end && is_space(**p)) ++*p;
  const char* begin = *p;
  while (*p < end && !is_space(**p)) ++*p;
  return std::string_view(begin, static_cast<size_t>(*p - begin));
}

// A token as a message quotes it: at most 24 characters, bytes that are not printable ASCII as
// '?', so a stream cannot put control sequences on the terminal.
std::string shown(std::string_view token) {
  constexpr size_t kMax = 24;
  std::string out = "'";
  for (size_t i = 0; i < token.size() && i < kMax; ++i) {
    const unsigned char c = static_cast<unsigned char>(token[i]);
    out += (c >= 0x20 && c < 0x7f) ? static_cast<char>(c) : '?';
  }
  if (token.size() > kMax) out += "...";
  return out + "'";
}

enum class Value { kNumber, kNotANumber, kOutOfRange };

// A decimal number filling the whole token ("-1.5", "2e-3", "+4", "inf"); kOutOfRange for one
// beyond a double's range either way ("1e999", "1e-999").
Value parse_value(std::string_view token, double* value) {
  const char* first = token.data();
  const char* last = first + token.size();
  if (first < last && *first == '+') {  // from_chars takes no '+', C's strtod does
    ++first;
    if (first < last && (*first == '+' || *first == '-')) return Value::kNotANumber;
  }
  if (first == last) return Value::kNotANumber;
  const auto r = std::from_chars(first, last, *value);
  if (r.ptr != last) return Value::kNotANumber;
  if (r.ec == std::errc::result_out_of_range) return Value::kOutOfRange;
  return r.ec == std::errc() ? Value::kNumber : Value::kNotANumber;
}

bool blank(std::string_view s) {
  for (char c : s)
    if (!is_space(c)) return false;
  return true;
}

}  // namespace

AxisLineStatus parse_axis_line(std::string_view line, int channels, AxisFrame* frame, std::string* reason) {
  const char* p = line.data();
  const char* end = p + line.size();
  while (end > p && is_space(end[-1])) --end;
  if (end == p) return AxisLineStatus::kBlank;
  auto malformed = [&](std::string why) {
    *reason = std::move(why);
    return AxisLineStatus::kMalformed;
  };
  if (end - p < 2 || end[-1] != '|' || end[-2] != '|') return malformed("the line does not end in '||'");
  end -= 2;

  const std::string_view index = next_token(&p, end);
  const auto r = std::from_chars(index.data(), index.data() + index.size(), frame->avatar_index);
  if (index.empty() || r.ec != std::errc() || r.ptr != index.data() + index.size())
    return malformed("expected an avatar index, found " + (index.empty() ? std::string("'||'") : shown(index)));
  const std::string_view name = next_token(&p, end);
  if (name.empty()) return malformed("expected an avatar name after the avatar index");
  frame->avatar_name.assign(name.data(), name.size());

  std::vector<double>& values = frame->values;
  values.clear();
  for (std::string_view token = next_token(&p, end); !token.empty(); token = next_token(&p, end)) {
    double v = 0.0;
    const Value kind = parse_value(token, &v);
    if (kind == Value::kNotANumber)
      return malformed("value " + std::to_string(values.size() + 1) + " is not a number: " + shown(token));
    if (kind == Value::kOutOfRange || !std::isfinite(v))
      return malformed("value " + std::to_string(values.size() + 1) + " is not a finite number: " + shown(token));
    values.push_back(v);
  }
  const size_t n = static_cast<size_t>(channels);
  if (values.size() == n) {
    frame->reference.clear();
  } else if (values.size() == n + kAxisReferenceValues) {
    frame->reference.assign(values.begin(), values.begin() + kAxisReferenceValues);
    values.erase(values.begin(), values.begin() + kAxisReferenceValues);
  } else {
    return malformed("expected " + std::to_string(n) + " values (" + std::to_string(n + kAxisReferenceValues) +
                     " with a reference), found " + std::to_string(values.size()));
  }
  return AxisLineStatus::kOk;
}

void append_axis_number(std::string* out, double value, int digits) {
  char buffer[64];
  const auto r = digits > 0 ? std::to_chars(buffer, buffer + sizeof buffer, value, std::chars_format::general, digits)
                            : std::to_chars(buffer, buffer + sizeof buffer, value);
  out->append(buffer, r.ptr);
}

void append_axis_line(std::string* out, int avatar_index, std::string_view name, const double* reference,
                      int reference_count, const double* values, int count) {
  char buffer[16];
  const auto r = std::to_chars(buffer, buffer + sizeof buffer, avatar_index);
  out->append(buffer, r.ptr);
  out->push_back(' ');
  out->append(name.data(), name.size());
  for (int i = 0; i < reference_count; ++i) {
    out->push_back(' ');
    append_axis_number(out, reference[i], 0);
  }
  for (int i = 0; i < count; ++i) {
    out->push_back(' ');
    append_axis_number(out, values[i]);
  }
  out->append(" ||\n");
}

AxisLineSplitter::AxisLineSplitter(size_t max_line_bytes) : max_line_bytes_(max_line_bytes) {}

void AxisLineSplitter::reset() {
  buffer_.clear();
  discarding_ = false;
  last_bar_ = false;
  clear_buffer_ = false;
  newlines_ = 0;
  start_line_ = 1;
  line_number_ = 0;
  dropped_ = 0;
  dropped_line_number_ = 0;
}

bool AxisLineSplitter::finish(std::string_view* chunk, size_t end, size_t consumed, std::string_view* line) {
  const bool newline = consumed > end;  // the '\n' after the line is consumed with it
  const std::string_view part = chunk->substr(0, end);
  const bool too_long = buffer_.size() + part.size() > max_line_bytes_;
  bool keep = false;
  if (!discarding_ && too_long) {
    ++dropped_;
    dropped_line_number_ = start_line_;
  } else if (!discarding_) {
    if (buffer_.empty()) {
      *line = part;
    } else {
      buffer_.append(part.data(), part.size());
      *line = buffer_;
      clear_buffer_ = true;  // cleared at the next call, once the caller is done with *line
    }
    if (!line->empty() && line->back() == '\r') line->remove_suffix(1);
    keep = !blank(*line);
    line_number_ = start_line_;
  }
  if (!keep) clear_buffer_ = false;
  if (!clear_buffer_) buffer_.clear();
  discarding_ = false;
  last_bar_ = false;
  chunk->remove_prefix(consumed);
  if (newline) ++newlines_;
  start_line_ = newlines_ + 1;
  return keep;
}

bool AxisLineSplitter::next(std::string_view* chunk, std::string_view* line) {
  if (clear_buffer_) {
    buffer_.clear();
    clear_buffer_ = false;
  }
  while (!chunk->empty()) {
    const char* p = chunk->data();
    const size_t n = chunk->size();
    // "||" split between two chunks.
    if (last_bar_ && p[0] == '|') {
      if (finish(chunk, 1, 1, line)) return true;
      continue;
    }
    const void* found = std::memchr(p, '\n', n);
    const size_t newline = found ? static_cast<size_t>(static_cast<const char*>(found) - p) : n;
    size_t bars = n;  // index of the first "||" before the line end
    for (size_t i = 0; i + 1 < newline;) {
      const void* bar = std::memchr(p + i, '|', newline - i);
      if (!bar) break;
      i = static_cast<size_t>(static_cast<const char*>(bar) - p);
      if (i + 1 < newline && p[i + 1] == '|') {
        bars = i;
        break;
      }
      ++i;
    }
    if (bars < n) {
      if (finish(chunk, bars + 2, bars + 2, line)) return true;
    } else if (newline < n) {
      if (finish(chunk, newline, newline + 1, line)) return true;
    } else {
      // No line end in the chunk: keep its bytes, or drop the line once it is too long.
      if (!discarding_ && buffer_.size() + n > max_line_bytes_) {
        ++dropped_;
        dropped_line_number_ = start_line_;
        discarding_ = true;
        buffer_.clear();
      }
      if (!discarding_) buffer_.append(p, n);
      last_bar_ = p[n - 1] == '|';
      chunk->remove_prefix(n);
    }
  }
  return false;
}

}  // namespace mostyle
