#include "litamin2/service/topic_names.hpp"

namespace litamin2::service {

namespace {

constexpr std::string_view kPointsSuffix = "/points";
constexpr std::string_view kOdomSuffix = "/odom";
/// Longest suffix a stream's topics get ("/points"), plus the prefix "rt/".
constexpr std::size_t kMaxStreamLength = kMaxTopicLength - 10;

bool is_alpha(char c) {
  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z');
}
bool is_digit(char c) {
  return c >= '0' && c <= '9';
}

/// Space, and the ASCII control characters (DDS topic names are printable).
bool is_space_or_control(char c) {
  return static_cast<unsigned char>(c) <= ' ' || c == 0x7f;
}

std::string join(std::string_view a, std::string_view b, std::string_view c) {
  std::string out;
  out.reserve(a.size() + b.size() + c.size());
  out.append(a).append(b).append(c);
  return out;
}

}  // namespace

std::string points_topic(std::string_view stream) {
  return join(kRosTopicPrefix, stream, kPointsSuffix);
}

std::string odom_topic(std::string_view stream) {
  return join(kRosTopicPrefix, stream, kOdomSuffix);
}

std::string map_patches_topic() {
  return std::string(kMapPatchesTopic);
}

std::string status_topic() {
  return std::string(kStatusTopic);
}

std::optional<std::string> stream_id_error(std::string_view stream) {
  if (stream.empty()) return std::string("stream id is empty");
  if (stream.size() > kMaxStreamLength) {
    return "stream id is longer than " + std::to_string(kMaxStreamLength) + " characters";
  }
  if (stream.front() == '/') return std::string("stream id starts with '/'");
  if (stream.back() == '/') return std::string("stream id ends with '/'");
  std::size_t start = 0;
  while (start <= stream.size()) {
    std::size_t end = stream.find('/', start);
    if (end == std::string_view::npos) end = stream.size();
    const std::string_view token = stream.substr(start, end - start);
    if (token.empty()) return std::string("stream id contains '//'");
    if (is_digit(token.front())) {
      return "token '" + std::string(token) + "' starts with a digit";
    }
    for (std::size_t i = 0; i < token.size(); ++i) {
      const char c = token[i];
      if (!is_alpha(c) && !is_digit(c) && c != '_') {
        return "character '" + std::string(1, c) +
               "' is not allowed (only letters, digits, '_' and '/')";
      }
      if (c == '_' && i + 1 < token.size() && token[i + 1] == '_') {
        return "token '" + std::string(token) + "' contains '__'";
      }
    }
    start = end + 1;
  }
  return std::nullopt;
}

bool is_valid_stream_id(std::string_view stream) {
  return !stream_id_error(stream).has_value();
}

std::optional<std::string> topic_name_error(std::string_view topic) {
  if (topic.empty()) return std::string("empty topic name");
  if (topic.size() > kMaxTopicLength)
    return "topic name is longer than " + std::to_string(kMaxTopicLength) + " characters";
  for (char c : topic)
    if (is_space_or_control(c) || c == '*' || c == '?')
      return "'" + std::string(topic) + "' is not a valid topic name";
  return std::nullopt;
}

std::optional<TopicPattern> TopicPattern::parse(std::string_view pattern, std::string* error) {
  const auto fail = [&](std::string message) -> std::optional<TopicPattern> {
    if (error) *error = std::move(message);
    return std::nullopt;
  };
  const std::size_t star = pattern.find('*');
  if (star == std::string_view::npos) {
    return fail("topic pattern '" + std::string(pattern) + "' has no '*'");
  }
  if (pattern.find('*', star + 1) != std::string_view::npos) {
    return fail("topic pattern '" + std::string(pattern) + "' has more than one '*'");
  }
  if (pattern.size() > kMaxTopicLength) {
    return fail("topic pattern is longer than " + std::to_string(kMaxTopicLength) + " characters");
  }
  for (char c : pattern)
    if (is_space_or_control(c) || c == '?')
      return fail("'" + std::string(pattern) + "' is not a valid topic pattern");
  return TopicPattern(std::string(pattern), star);
}

std::optional<std::string> TopicPattern::match(std::string_view topic) const {
  const std::string_view prefix = std::string_view(pattern_).substr(0, star_);
  const std::string_view suffix = std::string_view(pattern_).substr(star_ + 1);
  if (topic.size() <= prefix.size() + suffix.size()) return std::nullopt;
  if (topic.substr(0, prefix.size()) != prefix) return std::nullopt;
  if (topic.substr(topic.size() - suffix.size()) != suffix) return std::nullopt;
  const std::string_view stream =
      topic.substr(prefix.size(), topic.size() - prefix.size() - suffix.size());
  if (!is_valid_stream_id(stream)) return std::nullopt;
  return std::string(stream);
}

std::string TopicPattern::topic_for(std::string_view stream) const {
  return join(std::string_view(pattern_).substr(0, star_), stream,
              std::string_view(pattern_).substr(star_ + 1));
}

std::optional<std::string> stream_from_topic(std::string_view pattern, std::string_view topic) {
  const auto parsed = TopicPattern::parse(pattern);
  if (!parsed) return std::nullopt;
  return parsed->match(topic);
}

}  // namespace litamin2::service
