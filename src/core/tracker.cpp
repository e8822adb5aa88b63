#include "litamin2/core/tracker.hpp"

#include "litamin2/core/global_pose_search.hpp"
#include "litamin2/core/motion_model.hpp"
#include "litamin2/core/scan_registration.hpp"
#include "litamin2/core/sensor_preset.hpp"
#include "litamin2/core/stopwatch.hpp"

#include <Eigen/Cholesky>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>

namespace litamin2 {
namespace {

/// Blur of the correlative score that ranks starts placed at `offsets` times `unit` metres
/// along the motion: the widest gap between neighbouring starts, so that the motion between two
/// of them is not missed, and at least a tenth of a voxel.
double start_blur(std::vector<double> offsets, double unit, double voxel_size) {
  std::sort(offsets.begin(), offsets.end());
  double widest_gap = 0.0;
  for (std::size_t i = 1; i < offsets.size(); ++i)
    widest_gap = std::max(widest_gap, (offsets[i] - offsets[i - 1]) * unit);
  return std::max(widest_gap, 0.1 * voxel_size);
}

double rotation_angle(const Eigen::Matrix3d& rotation) {
  return Eigen::AngleAxisd(rotation).angle();
}

/// 2 sigma^2 H^-1, sigma^2 = cost per residual degree of freedom (3 per correspondence).
Matrix6d covariance_from_hessian(const RegistrationResult& result) {
  const double dof = std::max(1.0, 3.0 * result.correspondences - 6.0);
  const double sigma_sq = result.cost / dof;
  const Eigen::LDLT<Matrix6d> ldlt(result.hessian);
  if (ldlt.info() != Eigen::Success) return Matrix6d::Zero();
  return 2.0 * sigma_sq * ldlt.solve(Matrix6d::Identity());
}

TrackerConfig with_preset(const TrackerConfig& config) {
  validate(config);
  TrackerConfig out = config;
  apply_sensor_preset(config.sensor, out);
  validate(out);
  return out;
}

}  // namespace

Tracker::Tracker(const TrackerConfig& config)
    : config_(with_preset(config)),
      ego_(config_.filter),
      voxelizer_(config_.voxelizer),
      map_(config_.voxelizer, config_.map) {}

Tracker::~Tracker() = default;

bool Tracker::below_fitting(double share) const {
  const double ratio = config_.recovery.reset_ratio;
  return ratio > 0.0 && fitting_share_ > 0.0 && share < ratio * fitting_share_;
}

bool Tracker::is_keyframe(const Eigen::Isometry3d& pose) const {
  const Eigen::Isometry3d motion = last_keyframe_.inverse() * pose;
  return motion.translation().norm() >= config_.keyframe.distance ||
         rotation_angle(motion.linear()) >= config_.keyframe.angle_deg * M_PI / 180.0;
}

const PointCloud& Tracker::without_self_hits(const PointCloud& scan, int& dropped) {
  dropped = 0;
  const ScanFilterConfig& f = config_.filter;
  bool filtered = false;
  if (f.ego == EgoFilterMode::kBox) {
    remove_box(scan, f.ego_box_min, f.ego_box_max, filtered_);
    filtered = true;
  } else if (f.ego == EgoFilterMode::kAuto) {
    ego_.observe(scan);
    filtered = ego_.filter(scan, filtered_);
  }
  if (!filtered) return scan;
  dropped = static_cast<int>(scan.points.size() - filtered_.points.size());
  return filtered_;
}

void Tracker::continue_from(TrackerSeed seed) {
  if (frames_ != 0 || prepared_)
    throw std::logic_error("Tracker::continue_from: only before the first scan");
  pending_seed_ = std::make_unique<TrackerSeed>(std::move(seed));
}

void Tracker::prepare_first_scan(const PointCloud& raw) {
  if (prepared_) return;
  prepared_ = true;
  if (config_.sensor == SensorModel::kAuto) {
    // `sensor: auto`: the first scan decides the preset; the (empty) voxeliser and map are
    // rebuilt with its values.
    apply_sensor_preset(nearest_sensor(measure_signature(raw)), config_);
    validate(config_);
    ego_ = EgoLearner(config_.filter);
    voxelizer_ = Voxelizer(config_.voxelizer);
    map_ = VoxelMap(config_.voxelizer, config_.map);
  }
  if (pending_seed_) {
    apply_seed(*pending_seed_);
    pending_seed_.reset();
  }
}

void Tracker::apply_seed(const TrackerSeed& seed) {
  const double voxel = map_.voxel_size();
  for (const SeedKeyframe& k : seed.keyframes) {
    if (std::abs(k.voxel_size - voxel) > 1e-6 * voxel) {
      ++seed_skipped_;
      continue;
    }
    map_.add_distributions(k.distributions, k.pose);
    last_keyframe_ = k.pose;
    ++seed_used_;
  }
  if (!map_.empty())
    search_ = make_correspondence_search(config_.registration.correspondence, map_);
  // The previous frame's pose is the one `velocity` leads from to the prediction.
  velocity_ = seed.velocity;
  pose_ = seed.predicted * seed.velocity.inverse();
  if (seed_used_ == 0) last_keyframe_ = pose_;
  // Counted as two frames: registration (frames_ > 0) and deskew's first pass (frames_ >= 2
  // with an interval) use the seed's map and motion; without a known motion, as one frame.
  frames_ = seed.interval_s > 0.0 ? 2 : 1;
  last_interval_ = seed.interval_s;
  seeded_scan_ = true;
}

FrameResult Tracker::process(const PointCloud& raw) {
  return process_scaled(raw, 1.0);
}

Eigen::Isometry3d Tracker::predicted_motion(double motion_scale) const {
  return motion_scale == 1.0 ? velocity_ : scaled_motion(velocity_, motion_scale);
}

Tracker::RegistrationStart Tracker::registration_start(const PointCloud& scan, double motion_scale,
                                                       double interval_s, StageTimes& spent) {
  RegistrationStart chosen;
  chosen.pose = pose_ * predicted_motion(motion_scale);
  const RecoveryConfig& recovery = config_.recovery;
  // Only the second scan of a stream that started without a motion (no seed).
  if (frames_ != 1 || !recovery.enabled || recovery.first_speeds.empty() || map_.empty() ||
      !search_ || !(interval_s > 0.0))
    return chosen;
  // Each registration's time goes to `spent`; the kept one is handed on without it.
  const auto registered_from = [&](const Eigen::Isometry3d& start) {
    ScanRegistration r =
        register_scan(scan, voxelizer_, map_, *search_, start, frame_registration_);
    spent.voxelize_ms += r.voxelize_ms;
    spent.register_ms += r.register_ms;
    r.voxelize_ms = r.register_ms = 0.0;
    return r;
  };
  const Eigen::Isometry3d at_rest = chosen.pose;
  chosen.registered = registered_from(at_rest);
  const ScanRegistration& rest = *chosen.registered;
  const double rest_share = rest.result.valid ? rest.inlier_share() : 0.0;
  // A registration that travelled from rest found a motion; one that stayed near it may be stuck.
  if (rest.result.valid && recovery.first_speeds_max_travel > 0.0 &&
      (at_rest.inverse() * rest.result.pose).translation().norm() >=
          recovery.first_speeds_max_travel)
    return chosen;
  // The starts at speed are ranked by a correlative score of the scan against the map (a few
  // hundred distribution means, no registration; as the global pose search scores its grid),
  // blurred by the widest gap between neighbouring starts; only the best is registered.
  std::vector<double> travel = {0.0};
  for (double speed : recovery.first_speeds) travel.push_back(speed * interval_s);
  const auto start_time = std::chrono::steady_clock::now();
  const PoseScorer scorer(map_, start_blur(travel, 1.0, map_.voxel_size()));
  const std::vector<Eigen::Vector3d> points =
      search_points(rest.source, at_rest.linear(), recovery.global_search.max_sources);
  Eigen::Isometry3d best_start = at_rest;
  double best_score = 0.0;
  for (double speed : recovery.first_speeds) {
    Eigen::Isometry3d moved = Eigen::Isometry3d::Identity();
    moved.translation().x() = speed * interval_s;
    const Eigen::Isometry3d start = at_rest * moved;
    const double score = scorer.score(points, start);
    if (score > best_score) {
      best_start = start;
      best_score = score;
    }
  }
  spent.register_ms += elapsed_ms(start_time);
  if (best_score <= 0.0) return chosen;  // no start at speed puts the scan on the map
  // The registration from rest travelled more than half way to the best start: it ended
  // nearer that start than the start at rest, so it found the motion the start stands for.
  if (recovery.first_speeds_skip_reached && rest.result.valid &&
      (best_start.inverse() * rest.result.pose).translation().norm() <
          (at_rest.inverse() * rest.result.pose).translation().norm())
    return chosen;
  ScanRegistration other = registered_from(best_start);
  ++chosen.speed_registrations;
  const double share = other.result.valid ? other.inlier_share() : 0.0;
  if (share > rest_share && share >= recovery.min_gain * rest_share) {
    chosen.pose = best_start;
    chosen.registered = std::move(other);
  } else {
    // The voxeliser holds the speed start's grid voxels: re-cut the kept registration's grid.
    const auto start = std::chrono::steady_clock::now();
    voxelizer_.voxelize(scan, rest.grid_pose);
    spent.voxelize_ms += elapsed_ms(start);
  }
  return chosen;
}

std::vector<Eigen::Isometry3d> Tracker::retry_starts(const std::vector<Distribution>& source,
                                                     const Eigen::Isometry3d& predicted,
                                                     double motion_scale, double& spent_ms) const {
  const RecoveryConfig& recovery = config_.recovery;
  std::vector<Eigen::Isometry3d> starts;
  starts.reserve(recovery.motion_scales.size());
  for (double s : recovery.motion_scales)
    starts.push_back(pose_ * scaled_motion(velocity_, s * motion_scale));
  const auto kept = static_cast<std::size_t>(recovery.ranked_starts);
  if (kept == 0 || starts.size() <= kept) return starts;
  // Ranked as the second scan's starts at speed are: by the correlative score of the scan's
  // distribution means on the map, blurred by the widest gap between neighbouring starts (the
  // prediction, scale 1, among them).
  const auto start_time = std::chrono::steady_clock::now();
  const double step = (pose_.inverse() * predicted).translation().norm();
  std::vector<double> scales = recovery.motion_scales;
  scales.push_back(1.0);
  const PoseScorer scorer(map_, start_blur(std::move(scales), step, map_.voxel_size()));
  const std::vector<Eigen::Vector3d> points =
      search_points(source, predicted.linear(), recovery.global_search.max_sources);
  std::vector<std::pair<double, std::size_t>> ranked;
  ranked.reserve(starts.size());
  for (std::size_t i = 0; i < starts.size(); ++i)
    ranked.emplace_back(-scorer.score(points, starts[i]), i);
  // Highest score first; equal scores keep the configured order.
  std::stable_sort(ranked.begin(), ranked.end(),
                   [](const auto& a, const auto& b) { return a.first < b.first; });
  std::vector<Eigen::Isometry3d> best_first;
  best_first.reserve(starts.size());
  for (const auto& r : ranked) best_first.push_back(starts[r.second]);
  spent_ms += elapsed_ms(start_time);
  return best_first;
}

ScanRegistration Tracker::register_from(const PointCloud& scan, RegistrationStart& start) {
  if (start.registered) return std::move(*start.registered);
  return register_scan(scan, voxelizer_, map_, *search_, start.pose, frame_registration_);
}

void Tracker::choose_frame_registration() {
  frame_registration_ = config_.registration;
  // The first scan after a handover starts far from the optimum: the Cov term's wider basin
  // (RegistrationConfig::sigma_cov_after_handover).
  if (seeded_scan_ && config_.registration.sigma_cov_after_handover > 0.0)
    frame_registration_.sigma_cov = config_.registration.sigma_cov_after_handover;
}

FrameResult Tracker::process_scaled(const PointCloud& raw, double motion_scale,
                                    std::optional<int> self_hits_removed, double interval_s) {
  prepare_first_scan(raw);
  choose_frame_registration();
  FrameResult frame;
  if (self_hits_removed) frame.self_hits = *self_hits_removed;
  const PointCloud& scan = self_hits_removed ? raw : without_self_hits(raw, frame.self_hits);
  StageTimes start_search;
  RegistrationStart start = registration_start(scan, motion_scale, interval_s, start_search);
  const Eigen::Isometry3d predicted = start.pose;
  Eigen::Isometry3d estimate = predicted;
  bool suspected_break = false;
  if (frames_ > 0 && !map_.empty() && search_) {
    ScanRegistration registration = register_from(scan, start);
    double share = registration.result.valid ? registration.inlier_share() : 0.0;
    const RecoveryConfig& recovery = config_.recovery;
    const bool below_typical =
        typical_share_ > 0.0 && share < recovery.trigger_ratio * typical_share_;
    if (recovery.enabled && (below_typical || below_fitting(share))) {
      // Registration settles near its start: try the other starts and keep the best fit. The
      // voxeliser's grid voxels must be those of the kept registration (the map merges them).
      frame.retried = true;
      const double predicted_share = share;
      const std::vector<Eigen::Isometry3d> other_starts =
          retry_starts(registration.source, predicted, motion_scale, registration.register_ms);
      for (std::size_t k = 0; k < other_starts.size(); ++k) {
        // Ranked: the best ranked_starts first; the rest only if none of them was kept.
        if (recovery.ranked_starts > 0 && k >= static_cast<std::size_t>(recovery.ranked_starts) &&
            frame.recovered)
          break;
        ScanRegistration other =
            register_scan(scan, voxelizer_, map_, *search_, other_starts[k], frame_registration_);
        ++frame.retry_registrations;
        const double other_share = other.result.valid ? other.inlier_share() : 0.0;
        registration.voxelize_ms += other.voxelize_ms;
        registration.register_ms += other.register_ms;
        if (other_share > share && other_share >= recovery.min_gain * predicted_share) {
          other.voxelize_ms = registration.voxelize_ms;
          other.register_ms = registration.register_ms;
          registration = std::move(other);
          share = other_share;
          frame.recovered = true;
        }
      }
      const GlobalPoseSearchConfig& search = recovery.global_search;
      if (search.trigger_ratio > 0.0 && share < search.trigger_ratio * typical_share_) {
        // Beyond every scaled start: a break. Locate the scan in the map, register from the
        // best candidates, keep one only if it fits about as well as frames usually do.
        frame.pose_searched = true;
        const auto start = std::chrono::steady_clock::now();
        const std::vector<PoseCandidate> candidates = search_global_pose(
            search_points(registration.source, predicted.linear(), search.max_sources), map_, pose_,
            predicted, search);
        registration.register_ms += elapsed_ms(start);
        for (const PoseCandidate& candidate : candidates) {
          ScanRegistration other =
              register_scan(scan, voxelizer_, map_, *search_, candidate.pose, frame_registration_);
          const double other_share = other.result.valid ? other.inlier_share() : 0.0;
          registration.voxelize_ms += other.voxelize_ms;
          registration.register_ms += other.register_ms;
          if (other_share > share && other_share >= search.accept_ratio * typical_share_) {
            other.voxelize_ms = registration.voxelize_ms;
            other.register_ms = registration.register_ms;
            registration = std::move(other);
            share = other_share;
            frame.pose_found = true;
            frame.recovered = true;
          }
        }
      }
      // The voxeliser now holds the last try's grid voxels: re-cut the kept one's grid.
      voxelizer_.voxelize(scan, registration.grid_pose);
    }
    frame.inlier_share = share;
    suspected_break = frame.retried && below_fitting(share);
    if (suspected_break && break_map_) {
      // The scan after a suspected break, which fits the old map no better: if it fits the map
      // restarted from the suspected scan as frames usually fit, the break is confirmed and the
      // old map, which may no longer be where it is drawn, is dropped.
      ScanRegistration fresh = register_scan(scan, voxelizer_, *break_map_, *break_search_,
                                             predicted, frame_registration_);
      const double fresh_share = fresh.result.valid ? fresh.inlier_share() : 0.0;
      fresh.voxelize_ms += registration.voxelize_ms;
      fresh.register_ms += registration.register_ms;
      if (fresh_share >= recovery.trigger_ratio * fitting_share_) {
        map_ = std::move(*break_map_);
        search_ = make_correspondence_search(config_.registration.correspondence, map_);
        registration = std::move(fresh);
        share = fresh_share;
        suspected_break = false;
        frame.map_reset = true;
        frame.inlier_share = share;
      } else {
        // The voxeliser holds the fresh try's grid voxels: re-cut the kept one's grid.
        registration.voxelize_ms = fresh.voxelize_ms;
        registration.register_ms = fresh.register_ms;
        voxelizer_.voxelize(scan, registration.grid_pose);
      }
    }
    break_search_.reset();
    break_map_.reset();
    if (registration.result.valid) {
      typical_share_ = typical_share_ < 0.0 ? share
                                            : (1.0 - recovery.share_smoothing) * typical_share_ +
                                                  recovery.share_smoothing * share;
      // The fitting share, what the reset compares with, is what frames that fit as usual reach:
      // a frame below the recovery's trigger (a break, or a map spoilt by one) does not pull it
      // down, or a run of bad frames would soon look usual and no break would be seen.
      if (fitting_share_ < 0.0 || share >= recovery.trigger_ratio * fitting_share_)
        fitting_share_ = fitting_share_ < 0.0 ? share
                                              : (1.0 - recovery.share_smoothing) * fitting_share_ +
                                                    recovery.share_smoothing * share;
    }
    const RegistrationResult& result = registration.result;
    source_ = registration.source;
    frame.times.voxelize_ms = registration.voxelize_ms;
    frame.times.register_ms = registration.register_ms;
    frame.iterations = result.iterations;
    frame.voxelizations = registration.voxelizations;
    frame.regrid_stopped = registration.regrid_stopped;
    frame.correspondences = result.correspondences;
    if (result.valid) {
      estimate = result.pose;
      frame.registered = true;
      frame.covariance = covariance_from_hessian(result);
    }
  } else {
    const auto start = std::chrono::steady_clock::now();
    source_ = voxelizer_.voxelize(scan, predicted);
    frame.voxelizations = 1;
    frame.times.voxelize_ms = elapsed_ms(start);
  }
  frame.source_distributions = static_cast<int>(source_.size());
  frame.start_registrations = start.speed_registrations;
  frame.times.voxelize_ms += start_search.voxelize_ms;
  frame.times.register_ms += start_search.register_ms;

  // A frame that could not be registered also goes into the map, so that tracking can resume.
  frame.keyframe = frames_ == 0 || !frame.registered || frame.map_reset || is_keyframe(estimate);
  if (frame.keyframe || suspected_break) {
    const auto start = std::chrono::steady_clock::now();
    if (frame.keyframe) {
      map_.add_keyframe(voxelizer_.last_voxels(), estimate);
      search_ = make_correspondence_search(config_.registration.correspondence, map_);
      last_keyframe_ = estimate;
    }
    if (suspected_break) {
      // Kept as usual, and also the start of a map of its own, which the next scan is tried
      // against if it fits the old map no better (RecoveryConfig::reset_ratio).
      break_map_ = std::make_unique<VoxelMap>(config_.voxelizer, config_.map);
      break_map_->add_keyframe(voxelizer_.last_voxels(), estimate);
      break_search_ = make_correspondence_search(config_.registration.correspondence, *break_map_);
    }
    frame.times.map_update_ms = elapsed_ms(start);
  }

  // A pose found by the global search spans the missing frames: the velocity stays the last one.
  // So does a motion no vehicle makes within a frame (PredictionConfig::learn_max_error_m).
  const PredictionConfig& prediction = config_.prediction;
  const Eigen::Isometry3d surprise = predicted.inverse() * estimate;
  const bool implausible =
      frames_ >= 2 && frame.registered &&
      ((prediction.learn_max_error_m > 0.0 &&
        surprise.translation().norm() > prediction.learn_max_error_m) ||
       (prediction.learn_max_error_deg > 0.0 &&
        rotation_angle(surprise.linear()) > prediction.learn_max_error_deg * M_PI / 180.0));
  frame.velocity_kept = frame.pose_found || implausible;
  if (!frame.velocity_kept)
    velocity_ = frames_ == 0 ? Eigen::Isometry3d::Identity() : pose_.inverse() * estimate;
  pose_ = estimate;
  frame.pose = estimate;
  ++frames_;
  seeded_scan_ = false;
  return frame;
}

Keyframe make_keyframe(const Tracker& tracker, const FrameResult& frame, KeyframeKey key,
                       Stamp stamp, const Eigen::Isometry3d& sensor_in_base) {
  const bool moved = !sensor_in_base.matrix().isIdentity(0.0);
  Keyframe keyframe;
  keyframe.key = std::move(key);
  keyframe.stamp = stamp;
  keyframe.odom_pose = moved ? Eigen::Isometry3d(sensor_in_base * frame.pose) : frame.pose;
  keyframe.covariance =
      moved ? transform_left_covariance(frame.covariance, sensor_in_base) : frame.covariance;
  keyframe.voxel_size = tracker.map().voxel_size();
  keyframe.distributions = tracker.last_distributions();
  return keyframe;
}

}  // namespace litamin2
