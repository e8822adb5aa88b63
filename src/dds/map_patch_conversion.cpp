#include "litamin2/dds/map_patch_conversion.hpp"

#include "litamin2/core/value_checks.hpp"
#include "litamin2/dds/odometry_conversion.hpp"
#include "litamin2/dds/pose_conversion.hpp"
#include "litamin2/dds/time_conversion.hpp"
#include "litamin2/service/topic_names.hpp"

#include <Eigen/LU>
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

/// Why distribution `v` cannot be a distribution; fills `d` when it can.
std::optional<std::string> convert_distribution(const litamin2::msg::VoxelDistribution& v,
                                                Distribution& d) {
  const auto& m = v.mean();
  d.mean = Eigen::Vector3d(m[0], m[1], m[2]);
  if (auto why = checks::position_error(d.mean)) return "mean " + *why;
  const auto& c = v.cov();
  d.cov << c[0], c[1], c[2], c[1], c[3], c[4], c[2], c[4], c[5];
  if (auto why = checks::covariance_error<3>(d.cov)) return "covariance " + *why;
  if (v.count() == 0) return std::string("point count is 0");
  if (v.count() > static_cast<std::uint32_t>(std::numeric_limits<int>::max()))
    return "point count " + std::to_string(v.count()) + " is beyond 2^31 - 1";
  d.count = static_cast<int>(v.count());
  d.shape_cov = d.cov;
  bool invertible = false;
  Eigen::Matrix3d inverse;
  d.cov.computeInverseWithCheck(inverse, invertible);
  d.shape_cov_inv = invertible ? inverse : Eigen::Matrix3d::Identity();
  return std::nullopt;
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
  for (std::size_t i = 0; i < keyframe.distributions.size(); ++i) {
    const Distribution& d = keyframe.distributions[i];
    auto& v = out[i];
    v.mean({static_cast<float>(d.mean.x()), static_cast<float>(d.mean.y()),
            static_cast<float>(d.mean.z())});
    v.cov({static_cast<float>(d.cov(0, 0)), static_cast<float>(d.cov(0, 1)),
           static_cast<float>(d.cov(0, 2)), static_cast<float>(d.cov(1, 1)),
           static_cast<float>(d.cov(1, 2)), static_cast<float>(d.cov(2, 2))});
    v.count(static_cast<std::uint32_t>(d.count < 0 ? 0 : d.count));
  }
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
