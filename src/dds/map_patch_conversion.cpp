#include "litamin2/dds/map_patch_conversion.hpp"

#include "litamin2/core/value_checks.hpp"
#include "litamin2/dds/distribution_conversion.hpp"
#include "litamin2/dds/odometry_conversion.hpp"
#include "litamin2/dds/pose_conversion.hpp"
#include "litamin2/dds/time_conversion.hpp"
#include "litamin2/service/topic_names.hpp"

#include <cmath>
#include <limits>

namespace litamin2::dds {
namespace {

constexpr std::int64_t kNsPerSecond = 1'000'000'000;

PatchConversion rejected(PatchError error, std::string message) {
  PatchConversion out;
  out.error = error;
  out.message = std::move(message);
  return out;
}

}  // namespace

litamin2::msg::MapPatch to_map_patch(const Keyframe& keyframe, const std::string& frame_id) {
  litamin2::msg::MapPatch msg;
  msg.stream_id(keyframe.key.stream);
  msg.keyframe_id(keyframe.key.id);
  msg.stamp(to_time(keyframe.stamp));
  msg.frame_id(frame_id);
  msg.pose(to_pose_msg(keyframe.odom_pose));
  msg.covariance(ros_pose_covariance(keyframe.covariance, keyframe.odom_pose));
  msg.voxel_size(static_cast<float>(keyframe.voxel_size));
  auto& out = msg.distributions();
  out.resize(keyframe.distributions.size());
  for (std::size_t i = 0; i < keyframe.distributions.size(); ++i)
    out[i] = to_voxel_distribution(keyframe.distributions[i]);
  return msg;
}

const char* to_string(PatchError error) {
  switch (error) {
    case PatchError::kNone:
      return "none";
    case PatchError::kBadStreamId:
      return "bad_stream_id";
    case PatchError::kBadKeyframeId:
      return "bad_keyframe_id";
    case PatchError::kBadPose:
      return "bad_pose";
    case PatchError::kBadStamp:
      return "bad_stamp";
    case PatchError::kBadCovariance:
      return "bad_covariance";
    case PatchError::kBadVoxelSize:
      return "bad_voxel_size";
    case PatchError::kTooManyDistributions:
      return "too_many_distributions";
    case PatchError::kBadDistribution:
      return "bad_distribution";
  }
  return "unknown";
}

PatchConversion from_map_patch(const litamin2::msg::MapPatch& msg,
                               const PatchConversionOptions& options) {
  if (const auto why = service::stream_id_error(msg.stream_id()))
    return rejected(PatchError::kBadStreamId, "stream id '" + msg.stream_id() + "': " + *why);
  const std::string where =
      "patch " + msg.stream_id() + "/" + std::to_string(msg.keyframe_id()) + ": ";
  if (msg.keyframe_id() > static_cast<std::uint64_t>(std::numeric_limits<std::int64_t>::max()))
    return rejected(PatchError::kBadKeyframeId, where + "keyframe id is beyond 2^63 - 1");
  if (const auto why = pose_msg_error(msg.pose()))
    return rejected(PatchError::kBadPose, where + "pose: " + *why);
  if (msg.stamp().nanosec() >= kNsPerSecond)
    return rejected(PatchError::kBadStamp,
                    where + "stamp nanosec " + std::to_string(msg.stamp().nanosec()) + " >= 1e9");
  if (const auto why = checks::covariance_error<6>(ros_covariance_matrix(msg.covariance())))
    return rejected(PatchError::kBadCovariance, where + "covariance " + *why);
  if (!(msg.voxel_size() >= kMinVoxelSize && msg.voxel_size() <= kMaxVoxelSize))
    return rejected(
        PatchError::kBadVoxelSize,
        where + "voxel size " + checks::number_text(msg.voxel_size()) + " is not in [0.05, 50] m");
  const auto& in = msg.distributions();
  if (options.max_distributions > 0 && in.size() > options.max_distributions)
    return rejected(PatchError::kTooManyDistributions,
                    where + std::to_string(in.size()) + " distributions > limit " +
                        std::to_string(options.max_distributions));

  PatchConversion out;
  Keyframe& kf = out.keyframe;
  kf.key.stream = msg.stream_id();
  kf.key.id = msg.keyframe_id();
  kf.stamp = to_stamp(msg.stamp());
  kf.odom_pose = from_pose_msg(msg.pose());
  kf.covariance = left_covariance_from_ros(msg.covariance(), kf.odom_pose);
  if (const auto why = checks::covariance_error<6>(kf.covariance))
    return rejected(PatchError::kBadCovariance, where + "covariance in (phi, tau) " + *why);
  kf.voxel_size = msg.voxel_size();
  kf.distributions.resize(in.size());
  for (std::size_t i = 0; i < in.size(); ++i) {
    if (const auto why = convert_distribution(in[i], kf.distributions[i]))
      return rejected(PatchError::kBadDistribution,
                      where + "distribution " + std::to_string(i) + ": " + *why);
  }
  return out;
}

}  // namespace litamin2::dds
