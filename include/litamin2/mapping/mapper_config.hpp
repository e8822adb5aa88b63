#pragma once
/// Everything the mapper (place recognition, loop verification, pose graph, global map) is
/// configured by, and its validation (read from YAML by config/mapper_config_yaml.hpp).

#include <string>

namespace litamin2::mapping {

/// How the place search finds its candidates.
enum class PlaceSearch {
  /// The ring-key kd-tree and the spatial grid (ring_key_index.hpp, spatial_grid.hpp):
  /// O(log^2 N) and O(keyframes nearby) per query.
  kIndexed,
  /// Every keyframe, O(N) per query: the same candidates, for comparisons and tests.
  kLinear,
};

/// Place recognition over keyframes (place_descriptor.hpp).
struct PlaceRecognitionConfig {
  /// Rings of the polar descriptor grid.
  int rings = 20;
  /// Sectors of the polar descriptor grid (yaw resolution 360 / sectors degrees).
  int sectors = 60;
  /// Distributions farther than this from the sensor are ignored, metres.
  double max_range = 80.0;
  /// Candidates per query kept from the ring-key search before the full descriptor distance.
  int ring_key_candidates = 10;
  /// Candidates with a descriptor distance above this are rejected (0 = identical, 1 = unrelated).
  double max_descriptor_distance = 0.45;
  /// Keyframes of the same stream closer than this along the trajectory are never loop
  /// candidates (they are neighbours in the odometry chain), metres.
  double min_travel_gap = 50.0;
  /// Besides the descriptor's candidate, the keyframe of the same group of streams nearest
  /// to the query's current pose estimate is verified when it is closer than this, metres
  /// (0 = off): drift is small enough that a revisit is found by position, and the estimate
  /// gives the registration a starting pose.
  double proximity_radius = 30.0;
  /// Cell edge of the proximity search's grid of keyframe positions, metres (> 0). The
  /// search visits cells nearest first and stops when no cell left can hold a nearer
  /// keyframe, so a cell of a few metres keeps the visits to the street around the query.
  double proximity_cell_size = 5.0;
  /// In each cell the proximity search looks at the latest this many keyframes only (0 = all).
  /// A fleet drives its streets again and again: at 10^6 keyframes a 30 m disc holds
  /// thousands, and the nearest of them is no better a loop candidate than the nearest of a
  /// cell's latest few, which the latest optimisations have placed. Bounds the search's cost
  /// at any map size. The linear search (search: linear) looks at every keyframe.
  int proximity_cell_keyframes = 32;
  /// The proximity candidate is the nearest keyframe of a stream that the query's stream has
  /// closed no loop with in the last this many metres of its path, if one is within
  /// proximity_radius; only otherwise the nearest of all (0 = always the nearest of all).
  /// Passes over a place tied only to the pass nearest by estimate (their own layer) stay
  /// metres apart from the passes they never meet; a new partner at each search ties them
  /// (docs/benchmarks.md, "Layers": at 10^5 keyframes the shape error 1.22 -> 0.74 m).
  double proximity_partner_gap = 100.0;
  /// The proximity candidate is verified only when its place descriptor is within this
  /// distance of the query's (match_descriptors, 0..1: a comparison of the two descriptors
  /// before a registration of ~10 ms); 0 = always verified. A keyframe near the pose estimate that
  /// looks unlike the query (another street through a corner, the view blocked) costs a
  /// registration and is then rejected.
  double proximity_max_descriptor_distance = 0.0;
  PlaceSearch search = PlaceSearch::kIndexed;
  /// A stream's keyframes are searched for loops (and their candidates verified) only every
  /// this many metres of its odometry path (0 = every keyframe). A fleet revisiting its
  /// streets finds a candidate at nearly every keyframe; verifying each costs ~10 ms, so a
  /// fleet-scale aggregator samples them, as Cartographer's constraint builder does.
  double search_spacing = 0.0;
  /// After a stream's keyframe finds a verified loop inside its own group of streams, the
  /// stream's place searches look only at other groups' keyframes (the descriptor's
  /// candidate; no proximity candidate) until its path is this much further, metres (0:
  /// search_spacing alone). A fleet on streets it has mapped finds a loop at nearly every
  /// search, and verifying each (~10 ms) and optimising for it is what grows as the
  /// vehicles' maps merge; one loop every loop_spacing metres of a revisit is what holds the
  /// odometry's drift. The searches of other groups go on, so that merges are still found.
  double loop_spacing = 0.0;
  /// Verifications a place search of all keyframes may spend, on average per keyframe added
  /// (0 = no limit): each keyframe adds this to an allowance (up to what 100 keyframes add),
  /// each candidate verified by such a search takes one, and while less than one is left the
  /// searches look only at other groups' keyframes (as within loop_spacing), so merges are
  /// still found. A fleet on streets it has mapped finds a candidate at nearly every search
  /// (~10 ms each); this bounds their cost per keyframe whatever the map's coverage.
  double verification_budget_per_keyframe = 0.0;
  /// A loop between two groups of streams joins them only once this many verified loops
  /// between the same two groups agree on the transform between their frames (1 = the first
  /// loop joins them; merge_confirmation.hpp) ...
  int merge_confirmations = 2;
  /// ... found at places at least this far apart (so that one look-alike place cannot
  /// confirm itself), metres ...
  double merge_min_separation = 50.0;
  /// ... agreeing to within this, metres, plus merge_agreement_per_m per metre of their
  /// separation (the odometry's drift between them) ...
  double merge_agreement_m = 2.0;
  double merge_agreement_per_m = 0.02;
  /// ... and this, degrees.
  double merge_agreement_deg = 3.0;
};

/// Verification of a candidate by LiTAMIN2 registration of the two keyframes' patches
/// (loop_verifier.hpp).
struct LoopVerificationConfig {
  /// Neighbouring keyframes on each side of the candidate merged into its target submap.
  int submap_neighbours = 3;
  /// Registration robust scale; wider than odometry's, as the initial guess is coarse, metres.
  double sigma_icp = 0.5;
  /// RegistrationConfig::max_isotropy of the verifying registration. 1 (every correspondence,
  /// the paper's cost): the odometry's 0.05 leaves too few correspondences to pull a coarse
  /// estimate in between two vehicles' keyframes (MappingMapper test of two vehicles).
  double max_isotropy = 1.0;
  /// Gate of the fitness score: distance along the normal of a query distribution to the
  /// nearest map distribution's surface, metres.
  double fitness_distance = 0.3;
  /// A loop is accepted when at least this fraction of the query's non-horizontal
  /// distributions lies within fitness_distance of the map's surfaces at convergence ...
  double min_fitness = 0.6;
  /// ... and the root mean square of those distances is at most this, metres.
  double max_rmse = 0.2;
  /// Standard deviations the loop edge's information is built from: rotation (degrees) ...
  double rotation_sigma_deg = 0.1;
  /// ... and translation (metres).
  double translation_sigma = 0.05;
};

/// Where the odometry edges' uncertainty comes from.
enum class OdometryCovariance {
  /// Standard deviations proportional to the distance between the keyframes (the
  /// odometry_*_per_m keys), independent per axis.
  kDistance,
  /// The tracker's covariance of the later keyframe, carried to the relative pose
  /// (odometry_covariance.hpp), its standard deviations multiplied by tracker_covariance_scale,
  /// plus independent noise of the tracker_*_sigma_min standard deviations (a floor). Edges whose
  /// keyframe has no covariance (zero: the first frame, a failed registration) or that span a
  /// missing keyframe fall back to Distance.
  kTracker,
};

/// Pose graph optimisation (pose_graph.hpp).
struct PoseGraphConfig {
  OdometryCovariance odometry_covariance = OdometryCovariance::kTracker;
  /// Factor on the tracker's standard deviations (Tracker). The Hessian's covariance
  /// 2 sigma^2 H^-1 is only as right as its assumptions (independent residuals of one variance):
  /// the factor is calibrated so that the normalised errors e^T C^-1 e of consecutive
  /// keyframes' relative poses average 6 (their dimension) on sequences with ground truth other
  /// than the ones evaluated (sim 05 and 07, docs/accuracy.md). With the default icp+cov cost
  /// the Cov term's residuals inflate sigma^2, so the covariance is ~5x too wide: 0.21; with the
  /// ICP term alone it is ~1.55x too narrow: use 1.55.
  double tracker_covariance_scale = 0.21;
  /// Independent noise added to the scaled tracker covariance (Tracker): translation, metres ...
  double tracker_translation_sigma_min = 0.001;
  /// ... and rotation, degrees.
  double tracker_rotation_sigma_min_deg = 0.001;
  /// Odometry edges' standard deviations per metre travelled between keyframes (Distance):
  /// translation (metres per metre) ...
  double odometry_translation_sigma_per_m = 0.01;
  /// ... and rotation (degrees per metre).
  double odometry_rotation_sigma_deg_per_m = 0.01;
  /// Floors of those standard deviations for keyframes close together (Distance).
  double odometry_translation_sigma_min = 0.01;
  double odometry_rotation_sigma_min_deg = 0.01;
  /// Scale of the robust (Cauchy) loss on loop edges, in standard deviations. A loop edge is
  /// first optimised without it (the drift it corrects can be hundreds of standard deviations,
  /// which the loss would ignore), then checked: if the graph cannot accommodate it within
  /// loop_consistency_sigmas, it is dropped; else it keeps the robust loss from then on.
  /// Both are wide (10 and 12) because where passes over one place disagree by metres (a
  /// fleet's early drift), the loops between them are what joins them: at 1 and 3 they were
  /// dropped or given almost no weight, and the passes stayed apart (docs/benchmarks.md, "The
  /// map frame's keyframe held, and what the ATE is made of").
  double loop_loss_scale = 10.0;
  double loop_consistency_sigmas = 12.0;
  /// Standard deviation of a prior that keeps every keyframe level with the frame of its
  /// group's first keyframe (roll and pitch), degrees; 0 = off. For ground vehicles whose
  /// roads tilt less than this from where they started: it bounds the tilt drift that loops
  /// cannot correct on stretches never revisited.
  double level_prior_sigma_deg = 0.0;
  /// The optimisation after new loops (Mapper::optimize) is local: the keyframes of each new
  /// loop's stream since its latest earlier loop (at most this many before the loop's keyframe
  /// and as many after it) are free, their neighbours in the graph fixed
  /// (graph_optimizer.hpp). Its cost follows the drift corrected, not the map's size.
  int local_max_keyframes = 2000;
  /// ... and so is every keyframe within this many odometry edges of either end of a new
  /// loop (along each end's own stream), so that the correction spreads on both sides. Not
  /// through other loops: in a fleet's dense graph their hops would reach most of the map.
  int local_hops = 10;
  /// A new loop's older end whose neighbourhood (local_hops keyframes either side along its
  /// stream) already holds at least this many checked loops is held constant: it is not freed
  /// and no keyframes around it are, so the new loop corrects only its newer end's region. At
  /// a place the fleet has revisited many times that neighbourhood is held by the earlier
  /// loops, and freeing it brought every one of them (and their other ends) into the problem;
  /// the full pass spreads the correction further. 0 = every older end is freed.
  int local_hold_loops = 2;
  /// At most this many keyframes are solved (free) in a local optimisation, where the region
  /// above allows: always the new loops' ends, each new loop's stream stretch (its newer
  /// end's stream from the latest anchored keyframe before it on: the drift it corrects), and
  /// every keyframe between two ends along a stream; of the rest (the ends' local_hops
  /// neighbourhoods) those nearest an end by odometry edges along their streams (breadth
  /// first from every end at once) up to the bound. The rest of the region is held fixed like
  /// its neighbours, and the full pass moves it (see local_widen_for_loops). In a fleet whose
  /// every place has been revisited, each batch brings ~10 new loops whose regions and
  /// earlier loops made solves of ~700 keyframes by 5x10^4 (~60 at the start), ~85 % of
  /// them those stretches: bounding them drops loops, so the default is 0 = no bound
  /// (docs/benchmarks.md, "Bounded local regions").
  int local_max_free_keyframes = 0;
  /// A bounded local solve (local_max_free_keyframes) that cannot fit a new loop within
  /// loop_consistency_sigmas frees the region's whole stretches (runs of a stream) that hold
  /// that loop's ends and is solved again before the loop is dropped; false: the bounded
  /// region decides (one solve; loops that only the larger region fits are dropped).
  bool local_widen_for_loops = true;
  /// The full pass (Mapper::optimize_full, in the aggregator on a background thread) moves
  /// runs of this many consecutive keyframes of a stream as one rigid segment (1 = every
  /// keyframe its own node): its cost and memory are those of a graph this many times
  /// smaller, and the shape within a segment is the local optimisation's.
  int segment_keyframes = 10;
  /// Each full pass cuts the segments one keyframe further along than the pass before (the
  /// shift cycles through the segment's length). With fixed cuts the shape within a segment
  /// is only ever the local optimisations', which fit each new pass to the map as it was: the
  /// first pass over a street, odometry noise included, bends every later one. Shifted cuts
  /// let every odometry edge, in turn, be one the full pass weighs.
  bool full_pass_shift_segments = true;
  /// At most about this many segments in a full pass: beyond segment_keyframes x this many
  /// keyframes the segments grow (in multiples of segment_keyframes) so that the pass stays this
  /// size. The pass's sparse Cholesky factor grows faster than the graph (the loops between
  /// distant places fill it in): at 8.5x10^5 keyframes in segments of 10 it held 3.8 GB
  /// (docs/benchmarks.md, "10^6 keyframes"). 0 = no bound.
  int full_pass_max_segments = 20000;
  /// A full pass leaves a keyframe where it is when it would move it by less than this many
  /// metres and full_pass_min_turn_deg: a settled map's keyframes are not rewritten in the
  /// store, queued for the tiles (which re-fuse only beyond map_tiles.move_threshold_m) or
  /// published again for a millimetre, so applying a pass costs what it changes, not the map's
  /// size (1 cm: below the loops' own error, ~1.3 cm at p50 in the
  /// fleet bench; at 10^5 keyframes it left 31 % of the moves undone at the same ATE,
  /// docs/benchmarks.md "Place search and full pass at any map size"). A keyframe left stays
  /// within the bound of the latest pass's solution: the next pass measures from where it
  /// is. 0 and 0 = every keyframe is moved.
  double full_pass_min_shift = 0.01;
  double full_pass_min_turn_deg = 0.01;
  /// Each stream's odometry yaw drift (a turn per metre of its own; mapping/yaw_drift.hpp) is
  /// estimated from its loop ends within this many metres of path back from its latest one
  /// and taken out of its odometry edges and of the chaining of its new keyframes; 0 = off
  /// (the edges are the odometry as measured). In the fleet bench, whose vehicles turn up to
  /// 0.5 deg per 100 m each, it estimates each vehicle's drift to 0.035 deg per 100 m (median)
  /// at 10^5 keyframes; the map-frame ATE gains less (3.52 -> 3.32 m there: the map is
  /// rotated and tilted about its anchor, with or without drift; docs/benchmarks.md,
  /// "Odometry yaw drift per stream"). On simulated KITTI 00 it estimates -0.009 deg per
  /// 100 m and changes nothing.
  double yaw_drift_window = 2000.0;
  /// An estimate over a span of loop ends shorter than this (metres of path) is not taken:
  /// the previous one stays (0 at first).
  double yaw_drift_min_path = 200.0;
  /// An estimate beyond this (deg per 100 m) is rejected and counted (MapperStats::
  /// yaw_drift_rejected): no LiDAR odometry that tracks drifts so much (KITTI's worst
  /// published methods: ~1 deg per 100 m), so such an estimate comes from a wrong loop.
  double yaw_drift_max_deg_per_100m = 2.0;
  /// A pose graph with at least this many free poses is solved by conjugate gradients on the
  /// normal equations (Ceres' CGNR, Jacobi preconditioner) instead of a sparse Cholesky
  /// factorisation: memory of the order of the graph's edges, none of the factor's fill-in.
  /// Where the loops tie every part of a large map to every other (a fleet on the same streets
  /// for hours) the factor filled 3-4 GB and a full pass took more than 45 min from 4x10^5
  /// keyframes on (docs/benchmarks.md, "10^6 keyframes"). 0 = always the factorisation.
  int iterative_min_free_poses = 5000;
  /// Solver iteration limit.
  int max_iterations = 50;
  /// Solver threads.
  int threads = 1;
};

struct MapperConfig {
  PlaceRecognitionConfig place;
  LoopVerificationConfig verification;
  PoseGraphConfig graph;
  /// Voxel edge of the global map, metres.
  double map_voxel_size = 3.0;
};

/// Throws ConfigError on the first invalid value (the Mapper's constructor calls it).
void validate(const MapperConfig& config);

}  // namespace litamin2::mapping
