#pragma once
/// Parameters of LiTAMIN2 registration (paper Sec. III), defaults as in the paper.

#include "litamin2/core/correspondence_search.hpp"

namespace litamin2 {

/// Which terms the cost has: the ICP term alone (Eq. 3), or ICP plus the Cov term (Eq. 4).
enum class CostMode { kIcp, kIcpCov };

/// How Newton's method treats the Cov term's second derivative 2 df df^T + 2 f d2f.
enum class CovHessian {
  /// The exact Hessian; if the total is not positive definite, the f d2f part is dropped for
  /// that iteration.
  kFull,
  /// Only the always positive semi-definite 2 df df^T (Gauss-Newton).
  kGaussNewton,
};

/// The Cov term's energy: the paper's Eq. 4 squares the bracket f, its Table 1 does not.
/// sigma_cov = 3 is defined on Eq. 4's form.
enum class CovEnergy {
  /// E_cov = f^2 (Eq. 4).
  kSquared,
  /// E_cov = f (Table 1); f >= 0 since it is twice a symmetric KL divergence.
  kLinear,
};

struct RegistrationConfig {
  /// Terms of the cost.
  CostMode mode = CostMode::kIcpCov;
  /// Robust-weight scale of the ICP term. The paper uses 0.5; 0.1 measured 2-3x less drift on
  /// simulated sequences and closer agreement on the real KITTI pair (docs/accuracy.md). Below
  /// 0.05 icp+cov diverges: the Cov term (sigma_cov fixed) then outweighs the ICP term.
  double sigma_icp = 0.1;
  /// Robust-weight scale of the Cov term (paper: 3). With Table 1's linear energy, 3 weights
  /// every shape disagreement f < 9 nearly fully, and the Cov term's pull on the rotation then
  /// outweighs the ICP term's: the ICP term alone drifted 0.90x as much over 16 simulated runs.
  /// 0.3 weights the typical f ~ 0.8 of a well-populated voxel at the true pose by ~0.1 (Eq.
  /// 5's w = sigma^2 / (f + sigma^2)) and more disagreeing ones less: 0.88x the drift of 3 over
  /// those runs, 0.90x over 10 with deskew (docs/accuracy.md, "The Cov term's weight").
  double sigma_cov = 0.3;
  /// sigma_cov for the first scan of a stream taken over from another daemon (a TrackerSeed):
  /// its start is the stream's last pose carried over the gap at its last twist, metres and
  /// degrees off, where the Cov term's pull towards the map's shapes, whatever the
  /// translation, widens the basin. 0: sigma_cov. With 0.3 a stream taken over after a 2.1 s
  /// gap ended 1.09 m ATE off, with 3 0.04 m (tests/integration/multihost.sh, failover). Frames
  /// dropped in the simulated street world (a prediction over 2-12 intervals) measured better
  /// with sigma_cov: 16 runs 0.91x with 3 after such gaps against 0.88x without.
  double sigma_cov_after_handover = 3.0;
  /// Added to the combined covariance before inversion (paper: 1e-6).
  double lambda = 1e-6;
  /// The Cov term is applied only to correspondences whose source and map distributions both
  /// hold at least this many points (0: all, as in the paper). A covariance from a few points
  /// of one scan is a poor shape estimate: at the true pose, simulated scans' voxels with fewer
  /// than 20 points disagree with their map voxel by f = 11.6 on average (2.7 for 20-99
  /// points, 0.8 from 100), and that disagreement is torque noise. 50 measured best of 0/20/50
  /// (docs/accuracy.md, "Why icp+cov drifts").
  int cov_min_points = 50;
  /// Correspondences whose combined covariance Cq + R Cp R^T (Eq. 3) is round, smallest over
  /// largest eigenvalue above this, are left out of both terms (1: none, as in the paper). The
  /// mean of a round (non-planar: trees, clutter) voxel depends on where it was seen from, and
  /// the map's voxels ahead of the vehicle were seen from farther away, those behind from
  /// closer, than the scan sees them: their vertical offsets, of opposite sign ahead and behind,
  /// give every registration the same pitch error, which the Frobenius-normalised precision of
  /// a round distribution weights in every direction. A plane's precision weights only its
  /// normal, along which the offset is small. If fewer than min_correspondences pass, or fewer
  /// than isotropy_min_share of the matched ones, the scan is registered with all. 0.05 measured
  /// 3x less drift than 1 on simulated sequences and is the smallest tried that keeps the real
  /// KITTI pair test (docs/accuracy.md, "Pitch bias"). The vlp16 preset sets 1: on 16 beams
  /// the round voxels hold the horizontal constraints (docs/accuracy.md, "Line-like
  /// correspondences").
  double max_isotropy = 0.05;
  /// The isotropy gate is applied only while it keeps at least this share of the matched
  /// correspondences (0: always). On simulated HDL-64 scans and the real KITTI pair it keeps
  /// 56-60 %; on the real VLP-16 drive 13 %, which leaves too few walls to fix the horizontal
  /// pose (docs/accuracy.md, "Sparse sensors"). Set by the sparse sensors' presets.
  double isotropy_min_share = 0.0;
  /// The isotropy gate is applied only while the correspondences it keeps hold at least this
  /// share of the information of all of them in every direction of the pose (0: always): the
  /// smallest generalised eigenvalue of (H_gated, H_gated + H_round) at a registration's first
  /// iteration, H_round the ICP term's Hessian (Eq. 3, 5) of the correspondences the gate
  /// leaves out. On a highway the planes (road, barriers) hold little along the road and the
  /// round voxels (vegetation, posts) hold it: harder simulated 01 HDL-64 3.14 -> 1.85 %
  /// (seeds 2, 3: 0.56x, 0.61x; with deskew 0.40-0.56x), urban street 0.84-1.03x (with deskew
  /// 0.96-1.17x), the default world's urban sequences unchanged, its highway without sweep
  /// motion 1.5-1.7x worse (a round voxel's mean moves with the viewpoint). 0.2 changed
  /// little; 0.4 and 0.5 cost the default world up to 1.5x (docs/accuracy.md, "The isotropy
  /// gate on a highway").
  double isotropy_min_information = 0.3;
  /// Correspondences whose combined covariance Cq + R Cp R^T (Eq. 3) is a line, middle over
  /// largest eigenvalue below this, are left out of both terms (0: none, as in the paper); for
  /// two equal arcs at an angle a that ratio is (1 - cos a) / (1 + cos a), 0.1 at 35 deg. A
  /// 16-beam ring crosses a 3 m voxel as one arc; where the map voxel is also one ring's arc
  /// (a map of few scans: at the start, after a stop) the two arcs are parallel lines, and
  /// Eq. 3's precision then weights both directions across the line. One of them is along the
  /// surface (radially on the road, vertically on a wall), where the arc's position is set by
  /// the sensor's pose and beam, not by the world: the arcs coincide at zero motion and pull
  /// the scan back to the previous scan's pose. If fewer than min_correspondences pass, the
  /// scan is registered with all (as for the isotropy gate). The vlp16 preset sets 0.1
  /// (docs/accuracy.md, "Line-like correspondences").
  double line_gate = 0.0;
  /// Where a correspondence's combined precision C_qp (Eq. 3) is a plane's, its two weaker
  /// eigenvalues together below this times the strongest, the ICP term's gradient keeps only
  /// the strongest direction, the normal: the offset along the plane is left out (0: off, as in
  /// the paper). Within a plane, where a voxel's mean lies is set by where the scan's rings cut
  /// the voxel, and they cut it differently from each viewpoint (a wall's points stop at the top
  /// ring, higher on a far wall than on a near one). Eq. 3's normalised precision still weights
  /// that offset, by the in-plane over the normal variance, and it tilts every registration the
  /// same way: on the simulated HDL-64 sequences half of a -0.0007 deg pitch bias a frame, most
  /// of the KITTI rotation drift. Applied only as a refinement (normal_only_iterations), with
  /// the energy, its robust weight and the Hessian of the whole precision
  /// (docs/accuracy.md, "In-plane offsets").
  double normal_only_ratio = 1.0;
  /// Weighted Newton steps with the normal-only gradient (normal_only_ratio), taken once the
  /// registration has nearly converged with the whole precision (normal_only_start_factor)
  /// within the re-grid tolerances of its start. Each costs one iteration. Started after full
  /// convergence (normal_only_start_factor 1), 2 measured about 2 more Newton iterations a frame
  /// and most of the gain of iterating to convergence, which took 6 more (docs/accuracy.md,
  /// "In-plane offsets"); started at 10x the tolerances, 0.9 (builtin VLP-16 loop) to 1.6
  /// (HDL-64 loop) more than without the refinement.
  int normal_only_iterations = 2;
  /// The refinement (normal_only_iterations) starts once a Newton step with the whole precision
  /// is below this many times rotation_tolerance and translation_tolerance (1: converged).
  /// Its steps finish the convergence: at 10 (1e-4 rad, 1 mm) the builtin VLP-16 loop took
  /// 4.75 Newton iterations a frame instead of 5.68, at the same drift on 26 simulated runs
  /// and as many real-drive pairs off. Larger factors were faster but lost more: at 30 the
  /// real drive's breaks went worse, at 100 the degenerate start of 08 HDL-64 with deskew was
  /// lost (docs/accuracy.md, "Starting the refinement before convergence").
  double normal_only_start_factor = 10.0;
  /// In that refinement each plane-like correspondence's gradient and Hessian are weighted by
  /// tau^2 / (tau^2 + t^2), t^2 the combined covariance Cq + R Cp R^T along its normal, tau this
  /// (metres; 0: off, every plane alike). Eq. 3's normalised precision weighs a rough or curved
  /// plane (grass, a kerb, an undulating road within a 3 m voxel) along its normal as much as a
  /// crisp one, and there the mean's place along the normal depends on where the rings cut the
  /// voxel. Off by default: 0.1 measured 0.93x the drift over 26 simulated runs (default-world
  /// HDL-64 0.51-0.76x, 07 below KISS-ICP), but the street world without deskew 1.05-1.07x,
  /// the real drive 7 pairs off instead of 5, and a scan registered wrongly after a synthetic
  /// turning break then fits just above the global search's trigger (0.241 against 0.239), so
  /// the search does not run (docs/accuracy.md, "The refinement weighted by plane thickness").
  double normal_only_thickness = 0.0;
  /// Newton's step on the robust ICP cost includes the derivative of the robust weight (Eq. 5),
  /// not only the weight: the cost that w(E) = sigma^2 / (E + sigma^2) is the derivative of,
  /// rho(E) = sigma^2 ln(1 + E / sigma^2), has the Hessian w H + w'(E) g g^T per correspondence
  /// (g, H: Eq. 3's gradient and Gauss-Newton Hessian; w' = -w^2 / sigma^2). Where E > sigma^2
  /// rho is not convex along the residual; there the factor is capped so that the
  /// correspondence's curvature along its residual is zero, never negative
  /// (robust_weight_curvature). That step is taken only near the optimum: once the weighted
  /// step is within the re-grid tolerances (regrid_translation, regrid_rotation_deg), where
  /// that Hessian is positive definite and the step at most 3 times the weighted one in
  /// rotation and translation; else the weighted step. Far from the optimum, where many
  /// correspondences are past sigma, the path (and so the basin it ends in) is the paper's.
  /// With the weight held fixed (false, the paper's iteratively reweighted step) the iteration
  /// converges only linearly on sparse scans (the builtin VLP-16 loop: 5.7 iterations a frame,
  /// 3.8 with this; docs/accuracy.md, "The robust weight's curvature in Newton's step"). The
  /// gradient, and so the pose it converges to, is the same either way. The odometry covariance
  /// stays the weighted Gauss-Newton Hessian's. The motion within the sweep (SweepMotionConfig) is
  /// estimated with the weighted step.
  bool robust_newton = true;
  /// Form of the Cov term's energy.
  CovEnergy cov_energy = CovEnergy::kLinear;
  /// Treatment of the Cov term's Hessian.
  CovHessian cov_hessian = CovHessian::kFull;
  /// How the nearest map distribution is found.
  CorrespondenceMethod correspondence = CorrespondenceMethod::kKdTree;
  /// Correspondences farther than this are ignored, metres; 0 means one voxel edge.
  double max_correspondence_distance = 0.0;
  /// Newton iteration limit.
  int max_iterations = 30;
  /// Converged when the rotation update is below this, radians ...
  double rotation_tolerance = 1e-5;
  /// ... and the translation update below this, metres.
  double translation_tolerance = 1e-4;
  /// Registration fails with fewer correspondences.
  int min_correspondences = 20;
  /// The scan is voxelised in the map's grid at the pose estimate (see Voxelizer::voxelize);
  /// when registration moves the pose farther than these tolerances from the pose the grid
  /// was cut at, the scan is voxelised again at the new pose and registered again.
  double regrid_translation = 0.02;
  /// ... rotation tolerance of the regrid test, degrees.
  double regrid_rotation_deg = 0.1;
  /// At most this many re-voxelisations per scan.
  int max_regrids = 10;
  /// The re-grid loop is a fixed-point iteration (grid pose -> registered pose); after the first
  /// re-grid, a further re-voxelisation is made only while the correction (in units of the
  /// regrid tolerances) shrank to at most this fraction of the previous pass's. When it did
  /// not, the loop stops at the previous pass's pose, the one the last grid was cut at: on
  /// sparse scans each re-cut changes the distributions and the loop otherwise walks away from
  /// a good pose (docs/accuracy.md, "Sparse sensors"). 0 (default): off, only max_regrids
  /// bounds it. Off by default because it also stops registrations from large errors that
  /// converge without shrinking at every pass (10 deg from the start: corrections 28, 5.9, 6.4,
  /// 20.7, 3.0, 11.5, 67.7, 0.5 regrid tolerances, core_registration_test), and on the real
  /// VLP-16 drive 0.5 cut voxelisations from 8.9 to 3.3 a frame without making the track
  /// better (docs/accuracy.md, "Robust odometry on sparse sensors").
  double regrid_contraction = 0.0;
  /// Source distributions per parallel block. Fixed, so that the ordered reduction gives the
  /// same bits whatever the thread count.
  int block_size = 64;
};

}  // namespace litamin2
