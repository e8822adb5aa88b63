#pragma once
/// DDS topic names of the product, in ROS 2's convention ("rt/" + ROS topic name), and sensor
/// stream ids (the ROS namespace of a sensor's topics).

#include <optional>
#include <string>
#include <string_view>

namespace litamin2::service {

/// Prefix ROS 2 puts in front of a topic name to get the DDS topic name.
inline constexpr std::string_view kRosTopicPrefix = "rt/";
/// Map patches of every stream (litamin2::msg::dds_::MapPatch_, keyed by stream id).
inline constexpr std::string_view kMapPatchesTopic = "rt/litamin2/map_patches";
/// Daemon status (diagnostic_msgs::msg::dds_::DiagnosticArray_).
inline constexpr std::string_view kStatusTopic = "rt/litamin2/status";
/// Default discovery pattern of the daemon: every stream's point topic.
inline constexpr std::string_view kDefaultPointsPattern = "rt/*/points";
/// Longest DDS topic name accepted (ROS 2's limit is 255 characters for the full name).
inline constexpr std::size_t kMaxTopicLength = 255;

/// Input point clouds of a stream: "rt/<stream>/points" (ROS topic /<stream>/points).
std::string points_topic(std::string_view stream);
/// Odometry of a stream: "rt/<stream>/odom" (ROS topic /<stream>/odom).
std::string odom_topic(std::string_view stream);
/// "rt/litamin2/map_patches".
std::string map_patches_topic();
/// "rt/litamin2/status".
std::string status_topic();

/// Checks a stream id against ROS 2's name rules, as a relative name used as a namespace:
/// one or more tokens separated by single '/'; each token made of ASCII letters, digits and
/// '_', not starting with a digit; no "__"; no leading or trailing '/'; at most
/// kMaxTopicLength - 10 characters so that every topic of the stream stays within the limit.
/// Returns std::nullopt when valid, else a reason ("token '1car' starts with a digit").
std::optional<std::string> stream_id_error(std::string_view stream);
/// True when stream_id_error(stream) is std::nullopt.
bool is_valid_stream_id(std::string_view stream);

/// Checks a DDS topic name given in a config: not empty, at most kMaxTopicLength characters, no
/// spaces or control characters, no '*' or '?'. Returns std::nullopt when valid, else a reason.
std::optional<std::string> topic_name_error(std::string_view topic);

/// A topic-name pattern with exactly one '*' that stands for a stream id, e.g. "rt/*/points".
/// '*' matches one or more characters, '/' included, so "rt/fleet/car1/points" gives the stream
/// "fleet/car1"; a topic only matches if what '*' covers is a valid stream id.
class TopicPattern {
 public:
  /// Parses a pattern; returns std::nullopt and sets *error (if given) when the pattern does
  /// not contain exactly one '*', holds a space, a control character or '?', or is longer
  /// than kMaxTopicLength.
  static std::optional<TopicPattern> parse(std::string_view pattern, std::string* error = nullptr);

  /// The stream id of a matching topic, std::nullopt if the topic does not match.
  std::optional<std::string> match(std::string_view topic) const;
  /// The topic of a stream (the pattern with '*' replaced by the stream id).
  std::string topic_for(std::string_view stream) const;
  /// The pattern as given.
  const std::string& str() const { return pattern_; }

 private:
  TopicPattern(std::string pattern, std::size_t star) : pattern_(std::move(pattern)), star_(star) {}
  std::string pattern_;
  std::size_t star_ = 0;
};

/// Shorthand: the stream id of `topic` under `pattern` (std::nullopt if the pattern is invalid
/// or the topic does not match).
std::optional<std::string> stream_from_topic(std::string_view pattern, std::string_view topic);

}  // namespace litamin2::service
