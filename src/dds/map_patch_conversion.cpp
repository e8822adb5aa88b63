#include "litamin2/dds/map_patch_conversion.hpp"

#include "litamin2/dds/odometry_conversion.hpp"
#include "litamin2/dds/pose_conversion.hpp"
#include "litamin2/dds/time_conversion.hpp"
#include "litamin2/service/topic_names.hpp"

#include <Eigen/LU>
#include <algorithm>
#include <cmath>

namespace litamin2::dds {
namespace {

constexpr std::int64_t kNsPerSecond = 1'000'000'000;

bool finite(const geometry_msgs::msg::Pose& p) {
  return std::isfinite(p.position().x()) && std::isfinite(p.position().y()) &&
         std::isfinite(p.position().z()) && std::isfinite(p.orientation().x()) &&
         std::isfinite(p.orientation().y()) && std::isfinite(p.orientation().z()) &&
         std::isfinite(p.orientation().w());
}

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
    case PatchError::kNonFinitePose:
      return "non_finite_pose";
    case PatchError::kBadStamp:
      return "bad_stamp";
    case PatchError::kNonFiniteCovariance:
      return "non_finite_covariance";
    case PatchError::kBadVoxelSize:
      return "bad_voxel_size";
    case PatchError::kNonFiniteDistribution:
      return "non_finite_distribution";
  }
  return "unknown";
}

PatchConversion from_map_patch(const litamin2::msg::MapPatch& msg) {
  if (const auto why = service::stream_id_error(msg.stream_id()))
    return rejected(PatchError::kBadStreamId, "stream id '" + msg.stream_id() + "': " + *why);
  const std::string where =
      "patch " + msg.stream_id() + "/" + std::to_string(msg.keyframe_id()) + ": ";
  if (!finite(msg.pose())) return rejected(PatchError::kNonFinitePose, where + "non-finite pose");
  if (msg.stamp().nanosec() >= kNsPerSecond)
    return rejected(PatchError::kBadStamp,
                    where + "stamp nanosec " + std::to_string(msg.stamp().nanosec()) + " >= 1e9");
  for (double c : msg.covariance())
    if (!std::isfinite(c))
      return rejected(PatchError::kNonFiniteCovariance, where + "non-finite covariance");
  if (!(std::isfinite(msg.voxel_size()) && msg.voxel_size() > 0.0f))
    return rejected(PatchError::kBadVoxelSize,
                    where + "voxel size " + std::to_string(msg.voxel_size()) + " is not positive");

  PatchConversion out;
  Keyframe& kf = out.keyframe;
  kf.key.stream = msg.stream_id();
  kf.key.id = msg.keyframe_id();
  kf.stamp = to_stamp(msg.stamp());
  kf.odom_pose = from_pose_msg(msg.pose());
  kf.covariance = left_covariance_from_ros(msg.covariance(), kf.odom_pose);
  kf.voxel_size = msg.voxel_size();
  const auto& in = msg.distributions();
  kf.distributions.resize(in.size());
  for (std::size_t i = 0; i < in.size(); ++i) {
    const auto& v = in[i];
    for (float x : v.mean())
      if (!std::isfinite(x))
        return rejected(PatchError::kNonFiniteDistribution,
                        where + "distribution " + std::to_string(i) + " has a non-finite mean");
    for (float x : v.cov())
      if (!std::isfinite(x))
        return rejected(
            PatchError::kNonFiniteDistribution,
            where + "distribution " + std::to_string(i) + " has a non-finite covariance");
    Distribution& d = kf.distributions[i];
    d.mean = Eigen::Vector3d(v.mean()[0], v.mean()[1], v.mean()[2]);
    const auto& c = v.cov();
    d.cov << c[0], c[1], c[2], c[1], c[3], c[4], c[2], c[4], c[5];
    d.count = static_cast<int>(std::min<std::uint32_t>(v.count(), 0x7fffffff));
    d.shape_cov = d.cov;
    bool invertible = false;
    Eigen::Matrix3d inverse;
    d.cov.computeInverseWithCheck(inverse, invertible);
    d.shape_cov_inv = invertible ? inverse : Eigen::Matrix3d::Identity();
  }
  return out;
}

}  // namespace litamin2::dds
