#include "litamin2/core/tracker_config.hpp"

#include <cmath>
#include <sstream>

namespace litamin2 {
namespace {

void require(bool ok, const std::string& key, double value, const std::string& rule) {
  if (ok) return;
  std::ostringstream out;
  out << key << ": " << value << " is invalid (" << rule << ")";
  throw ConfigError(out.str());
}

}  // namespace

void validate(const TrackerConfig& c) {
  const ScanFilterConfig& f = c.filter;
  if (f.ego == EgoFilterMode::kBox) {
    for (int i = 0; i < 3; ++i) {
      require(std::isfinite(f.ego_box_min(i)) && std::isfinite(f.ego_box_max(i)) &&
                  f.ego_box_min(i) < f.ego_box_max(i),
              "filter.ego_box", f.ego_box_max(i) - f.ego_box_min(i),
              "[xmin, ymin, zmin, xmax, ymax, zmax] with each min below its max");
    }
  }
  require(std::isfinite(f.auto_radius) && f.auto_radius > 0.0 && f.auto_radius <= 20.0,
          "filter.auto_radius", f.auto_radius, "metres, above 0 and at most 20");
  require(std::isfinite(f.auto_cell) && f.auto_cell >= 0.05 && f.auto_cell <= f.auto_radius,
          "filter.auto_cell", f.auto_cell, "metres, 0.05 to auto_radius");
  require(f.auto_radius / f.auto_cell <= 64.0, "filter.auto_cell", f.auto_cell,
          "at least auto_radius / 64 (the cell grid is at most 128 cells a side)");
  require(f.auto_scans >= 1 && f.auto_scans <= 1000, "filter.auto_scans", f.auto_scans,
          "1 to 1000");
  require(f.auto_min_share > 0.0 && f.auto_min_share <= 1.0, "filter.auto_min_share",
          f.auto_min_share, "in (0, 1]");
  const VoxelizerConfig& v = c.voxelizer;
  require(std::isfinite(v.voxel_size) && v.voxel_size >= 0.05 && v.voxel_size <= 50.0,
          "voxelizer.voxel_size", v.voxel_size, "metres, 0.05 to 50");
  require(v.min_points >= 3, "voxelizer.min_points", v.min_points, "at least 3");
  require(v.min_range >= 0.0, "voxelizer.min_range", v.min_range, "at least 0");
  require(v.max_range > v.min_range, "voxelizer.max_range", v.max_range, "above min_range");
  require(v.regularizer.min_eigen_ratio > 0.0 && v.regularizer.min_eigen_ratio <= 1.0,
          "voxelizer.regularization.min_eigen_ratio", v.regularizer.min_eigen_ratio, "in (0, 1]");
  require(v.regularizer.shape_min_eigen_ratio > 0.0 && v.regularizer.shape_min_eigen_ratio <= 1.0,
          "voxelizer.regularization.shape_min_eigen_ratio", v.regularizer.shape_min_eigen_ratio,
          "in (0, 1]");
  require(v.regularizer.plane_epsilon > 0.0 && v.regularizer.plane_epsilon <= 1.0,
          "voxelizer.regularization.plane_epsilon", v.regularizer.plane_epsilon, "in (0, 1]");
  require(v.regularizer.min_eigenvalue > 0.0, "voxelizer.regularization.min_eigenvalue",
          v.regularizer.min_eigenvalue, "positive");
  require(c.map.radius > v.voxel_size, "map.radius", c.map.radius, "above the voxel size");
  const RegistrationConfig& r = c.registration;
  require(r.sigma_icp > 0.0, "registration.sigma_icp", r.sigma_icp, "positive");
  require(r.sigma_cov > 0.0, "registration.sigma_cov", r.sigma_cov, "positive");
  require(r.cov_min_points >= 0, "registration.cov_min_points", r.cov_min_points, "at least 0");
  require(r.max_isotropy > 0.0 && r.max_isotropy <= 1.0, "registration.max_isotropy",
          r.max_isotropy, "in (0, 1]; 1 keeps every correspondence");
  require(r.isotropy_min_information >= 0.0 && r.isotropy_min_information <= 1.0,
          "registration.isotropy_min_information", r.isotropy_min_information,
          "in [0, 1]; 0 always gates");
  require(r.isotropy_min_share >= 0.0 && r.isotropy_min_share <= 1.0,
          "registration.isotropy_min_share", r.isotropy_min_share, "in [0, 1]; 0 always gates");
  require(r.line_gate >= 0.0 && r.line_gate < 1.0, "registration.line_gate", r.line_gate,
          "in [0, 1); 0 keeps every line-like correspondence");
  require(r.normal_only_ratio >= 0.0, "registration.normal_only_ratio", r.normal_only_ratio,
          "at least 0; 0 keeps the whole precision");
  require(r.normal_only_iterations >= 1, "registration.normal_only_iterations",
          r.normal_only_iterations, "at least 1");
  require(r.normal_only_start_factor >= 1.0, "registration.normal_only_start_factor",
          r.normal_only_start_factor, "at least 1; 1 starts the refinement once converged");
  require(r.sigma_cov_after_handover >= 0.0, "registration.sigma_cov_after_handover",
          r.sigma_cov_after_handover, "at least 0; 0 is sigma_cov after a handover too");
  require(r.normal_only_thickness >= 0.0, "registration.normal_only_thickness",
          r.normal_only_thickness, "at least 0; 0 weighs every plane alike");
  require(r.lambda >= 0.0, "registration.lambda", r.lambda, "at least 0");
  require(r.max_correspondence_distance >= 0.0, "registration.max_correspondence_distance",
          r.max_correspondence_distance, "at least 0; 0 means one voxel");
  require(r.correspondence != CorrespondenceMethod::kVoxel27 ||
              r.max_correspondence_distance <= v.voxel_size,
          "registration.max_correspondence_distance", r.max_correspondence_distance,
          "voxel27 search is exact only up to one voxel edge; use kdtree for more");
  require(r.max_iterations >= 1 && r.max_iterations <= 1000, "registration.max_iterations",
          r.max_iterations, "1 to 1000");
  require(r.rotation_tolerance > 0.0, "registration.rotation_tolerance", r.rotation_tolerance,
          "positive");
  require(r.translation_tolerance > 0.0, "registration.translation_tolerance",
          r.translation_tolerance, "positive");
  require(r.min_correspondences >= 6, "registration.min_correspondences", r.min_correspondences,
          "at least 6");
  require(r.block_size >= 1, "registration.block_size", r.block_size, "at least 1");
  require(r.regrid_translation > 0.0, "registration.regrid_translation", r.regrid_translation,
          "positive");
  require(r.regrid_rotation_deg > 0.0, "registration.regrid_rotation_deg", r.regrid_rotation_deg,
          "positive");
  require(r.max_regrids >= 0 && r.max_regrids <= 100, "registration.max_regrids", r.max_regrids,
          "0 to 100");
  require(std::isfinite(r.regrid_contraction) && r.regrid_contraction >= 0.0,
          "registration.regrid_contraction", r.regrid_contraction,
          "at least 0; 0: off, bounded by max_regrids only");
  const RecoveryConfig& rec = c.recovery;
  require(rec.trigger_ratio > 0.0 && rec.trigger_ratio <= 1.0, "recovery.trigger_ratio",
          rec.trigger_ratio, "in (0, 1]");
  require(rec.motion_scales.size() <= 16, "recovery.motion_scales",
          static_cast<double>(rec.motion_scales.size()), "at most 16 starts");
  for (double s : rec.motion_scales)
    require(std::isfinite(s) && s >= 0.0 && s <= 10.0, "recovery.motion_scales", s, "each 0 to 10");
  require(rec.ranked_starts >= 0 && rec.ranked_starts <= 16, "recovery.ranked_starts",
          rec.ranked_starts, "0 (every start) to 16");
  require(rec.first_speeds.size() <= 16, "recovery.first_speeds",
          static_cast<double>(rec.first_speeds.size()), "at most 16 starts");
  for (double v : rec.first_speeds)
    require(std::isfinite(v) && std::abs(v) <= 100.0, "recovery.first_speeds", v,
            "each within +-100 m/s");
  require(std::isfinite(rec.first_speeds_max_travel) && rec.first_speeds_max_travel >= 0.0 &&
              rec.first_speeds_max_travel <= 100.0,
          "recovery.first_speeds_max_travel", rec.first_speeds_max_travel, "0 to 100 m");
  require(std::isfinite(rec.min_gain) && rec.min_gain >= 1.0 && rec.min_gain <= 10.0,
          "recovery.min_gain", rec.min_gain, "1 to 10");
  require(rec.share_smoothing > 0.0 && rec.share_smoothing <= 1.0, "recovery.share_smoothing",
          rec.share_smoothing, "in (0, 1]");
  require(std::isfinite(rec.reset_ratio) && rec.reset_ratio >= 0.0 && rec.reset_ratio < 1.0,
          "recovery.reset_ratio", rec.reset_ratio, "0 (off) up to, not including, 1");
  validate(rec.global_search);
  require(c.keyframe.distance >= 0.0, "keyframe.distance", c.keyframe.distance, "at least 0");
  require(c.keyframe.angle_deg >= 0.0, "keyframe.angle_deg", c.keyframe.angle_deg, "at least 0");
  const double ratio = c.prediction.max_interval_ratio;
  require(std::isfinite(ratio) && (ratio == 0.0 || (ratio >= 1.0 && ratio <= 100.0)),
          "prediction.max_interval_ratio", ratio, "0 (off) or 1 to 100");
  require(std::isfinite(c.prediction.learn_max_error_m) && c.prediction.learn_max_error_m >= 0.0,
          "prediction.learn_max_error_m", c.prediction.learn_max_error_m, "0 (off) or more");
  require(std::isfinite(c.prediction.learn_max_error_deg) &&
              c.prediction.learn_max_error_deg >= 0.0 && c.prediction.learn_max_error_deg <= 180.0,
          "prediction.learn_max_error_deg", c.prediction.learn_max_error_deg, "0 (off) to 180");
  validate(c.deskew);
}

}  // namespace litamin2
