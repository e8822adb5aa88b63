#pragma once
// The --frames option of the tools: a half-open range of frames "A:B" (B exclusive), "A:" (from
// A to the end) or ":B".

#include <cstddef>
#include <limits>
#include <optional>
#include <regex>
#include <string>
#include <utility>

namespace litamin2::tools {

struct FrameRange {
  std::size_t first = 0;
  /// One past the last frame; the largest size_t means "to the end".
  std::size_t last = std::numeric_limits<std::size_t>::max();

  /// [first, min(last, size)) of a sequence of `size` frames; nothing if that is empty.
  std::optional<std::pair<std::size_t, std::size_t>> within(std::size_t size) const {
    const std::size_t end = last < size ? last : size;
    if (first >= end) return std::nullopt;
    return std::make_pair(first, end);
  }
};

/// Parses "A:B", "A:" or ":B"; an empty text is the whole sequence. Returns std::nullopt and
/// sets *error when the text has another form, a number is out of range or A >= B.
inline std::optional<FrameRange> parse_frame_range(const std::string& text, std::string* error) {
  FrameRange range;
  if (text.empty()) return range;
  static const std::regex re(R"(^\s*(\d*)\s*:\s*(\d*)\s*$)");
  std::smatch m;
  const auto fail = [&](const std::string& message) -> std::optional<FrameRange> {
    if (error) *error = message;
    return std::nullopt;
  };
  if (!std::regex_match(text, m, re))
    return fail("--frames must look like A:B (B exclusive), A: or :B, got '" + text + "'");
  try {
    if (m[1].length()) range.first = std::stoull(m[1]);
    if (m[2].length()) range.last = std::stoull(m[2]);
  } catch (const std::exception&) {
    return fail("--frames " + text + ": number out of range");
  }
  if (range.first >= range.last) return fail("--frames " + text + " is empty");
  return range;
}

}  // namespace litamin2::tools
