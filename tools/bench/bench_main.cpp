// litamin2-bench: time of each LiTAMIN2 stage and of whole frames on KITTI-size scans.
//
// Scans: the two real KITTI scans of ../shared/data (124k points each) for the stages, and a
// sequence folder given with LITAMIN2_BENCH_SEQUENCE (e.g. a simulated one) for whole frames.
// Usage: litamin2-bench [--benchmark_filter=REGEX] ; results and commands in docs/benchmarks.md.

#include "common/cli.hpp"
#include "litamin2/core/correspondence_search.hpp"
#include "litamin2/core/scan_registration.hpp"
#include "litamin2/core/sensor_preset.hpp"
#include "litamin2/core/tracker.hpp"
#include "litamin2/io/kitti_bin.hpp"
#include "litamin2/io/kitti_sequence.hpp"
#include "litamin2/mapping/pose_graph.hpp"
#include "litamin2/version.hpp"

#include <benchmark/benchmark.h>
#include <tbb/task_arena.h>

#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <string>

namespace {

using namespace litamin2;

constexpr const char* kProg = "litamin2-bench";

struct Pair {
  PointCloud target, source;
};

const Pair& real_pair() {
  static const Pair pair = [] {
    const std::string dir = LITAMIN2_SHARED_DATA_DIR "/kitti/seq00_frames_xyz/";
    if (!std::filesystem::exists(dir + "000000.bin")) {
      std::exit(tools::runtime_error(kProg, "shared KITTI scans not found in " + dir));
    }
    return Pair{io::read_kitti_bin(dir + "000000.bin"), io::read_kitti_bin(dir + "000001.bin")};
  }();
  return pair;
}

/// Runs `body` in an arena of state.range(0) threads.
template <class Body>
void in_arena(benchmark::State& state, Body&& body) {
  tbb::task_arena arena(static_cast<int>(state.range(0)));
  arena.execute([&] { body(); });
}

/// Voxelisation of a real scan; argument: threads.
void BM_Voxelize(benchmark::State& state) {
  Voxelizer voxelizer(VoxelizerConfig{});
  in_arena(state, [&] {
    for (auto _ : state) benchmark::DoNotOptimize(voxelizer.voxelize(real_pair().source));
  });
  state.SetItemsProcessed(state.iterations() * real_pair().source.size());
}
BENCHMARK(BM_Voxelize)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond);

void BM_MapInsert(benchmark::State& state) {
  for (auto _ : state) {
    VoxelMap map(VoxelizerConfig{}, VoxelMapConfig{});
    map.insert(real_pair().target, Eigen::Isometry3d::Identity());
    benchmark::DoNotOptimize(map.distributions().data());
  }
}
BENCHMARK(BM_MapInsert)->Unit(benchmark::kMillisecond);

void BM_Correspondences(benchmark::State& state) {
  VoxelMap map(VoxelizerConfig{}, VoxelMapConfig{});
  map.insert(real_pair().target, Eigen::Isometry3d::Identity());
  const auto source = Voxelizer(VoxelizerConfig{}).voxelize(real_pair().source);
  const auto search =
      make_correspondence_search(static_cast<CorrespondenceMethod>(state.range(0)), map);
  const double max_sq = 9.0;
  for (auto _ : state) {
    int found = 0;
    for (const Distribution& d : source) found += search->nearest(d.mean, max_sq) >= 0;
    benchmark::DoNotOptimize(found);
  }
  state.SetLabel(state.range(0) == 0 ? "voxel27" : "kdtree");
  state.SetItemsProcessed(state.iterations() * source.size());
}
BENCHMARK(BM_Correspondences)->Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond);

/// Building the correspondence search over a map of ~2,300 distributions (the real KITTI
/// target inserted five times, 30 m apart), as the tracker does at every keyframe: arg method.
void BM_SearchBuild(benchmark::State& state) {
  VoxelMap map(VoxelizerConfig{}, VoxelMapConfig{});
  for (int k = 0; k < 5; ++k) {
    map.insert(real_pair().target, Eigen::Isometry3d(Eigen::Translation3d(30.0 * k, 0.0, 0.0)));
  }
  for (auto _ : state) {
    const auto search =
        make_correspondence_search(static_cast<CorrespondenceMethod>(state.range(0)), map);
    benchmark::DoNotOptimize(search.get());
  }
  state.SetLabel(std::to_string(map.distributions().size()) + " means, " +
                 (state.range(0) == 0 ? "voxel27" : "kdtree"));
}
BENCHMARK(BM_SearchBuild)->Arg(1)->Unit(benchmark::kMicrosecond);

/// One cost evaluation (correspondences + terms + reduction): args mode, threads.
void BM_CostEvaluation(benchmark::State& state) {
  VoxelMap map(VoxelizerConfig{}, VoxelMapConfig{});
  map.insert(real_pair().target, Eigen::Isometry3d::Identity());
  const auto source = Voxelizer(VoxelizerConfig{}).voxelize(real_pair().source);
  const auto search = make_correspondence_search(CorrespondenceMethod::kVoxel27, map);
  RegistrationConfig config;
  config.mode = state.range(1) ? CostMode::kIcpCov : CostMode::kIcp;
  in_arena(state, [&] {
    for (auto _ : state) {
      benchmark::DoNotOptimize(
          evaluate_cost(source, map, *search, Eigen::Isometry3d::Identity(), config));
    }
  });
  state.SetLabel(state.range(1) ? "icp+cov" : "icp");
}
BENCHMARK(BM_CostEvaluation)
    ->Args({1, 0})
    ->Args({1, 1})
    ->Args({2, 0})
    ->Args({2, 1})
    ->Unit(benchmark::kMicrosecond);

/// The sensor recognition of `sensor: auto` on a real scan (every point's elevation binned).
void BM_SensorSignature(benchmark::State& state) {
  for (auto _ : state) benchmark::DoNotOptimize(measure_signature(real_pair().source));
  state.SetItemsProcessed(state.iterations() * real_pair().source.size());
}
BENCHMARK(BM_SensorSignature)->Unit(benchmark::kMillisecond);

/// The first 100 scans of the sequence folder LITAMIN2_BENCH_SEQUENCE, loaded once; null (and
/// the benchmark skipped with a message) when the variable is not set.
const std::vector<PointCloud>* sequence_scans(benchmark::State& state) {
  const char* folder = std::getenv("LITAMIN2_BENCH_SEQUENCE");
  if (!folder) {
    state.SkipWithError("set LITAMIN2_BENCH_SEQUENCE to a sequence folder (e.g. simulated)");
    return nullptr;
  }
  static const std::vector<PointCloud> scans = [folder] {
    std::vector<PointCloud> loaded;
    const io::ScanSequence sequence(folder);
    const std::size_t n = std::min<std::size_t>(sequence.size(), 100);
    for (std::size_t i = 0; i < n; ++i) loaded.push_back(sequence.load(i));
    return loaded;
  }();
  return &scans;
}

/// Voxelisation of the sequence's first N scans (argument), one after another, single
/// thread. With N = 1 the scan stays in the cache like BM_Voxelize's real scan, which makes the
/// two comparable; N = 100 streams the scans from memory as whole frames do.
void BM_VoxelizeSequence(benchmark::State& state) {
  const std::vector<PointCloud>* loaded = sequence_scans(state);
  if (!loaded) return;
  const std::size_t n = std::min<std::size_t>(loaded->size(), state.range(0));
  const PointCloud* first = loaded->data();
  const PointCloud* last = first + n;
  Voxelizer voxelizer(VoxelizerConfig{});
  std::size_t points = 0;
  for (const PointCloud* scan = first; scan != last; ++scan) points += scan->size();
  tbb::task_arena arena(1);
  arena.execute([&] {
    for (auto _ : state) {
      for (const PointCloud* scan = first; scan != last; ++scan)
        benchmark::DoNotOptimize(voxelizer.voxelize(*scan));
    }
  });
  state.SetItemsProcessed(state.iterations() * points);
  state.counters["points_per_scan"] = static_cast<double>(points) / n;
  state.counters["time_per_scan"] =
      benchmark::Counter(static_cast<double>(n), benchmark::Counter::kIsIterationInvariantRate |
                                                     benchmark::Counter::kInvert);
}
BENCHMARK(BM_VoxelizeSequence)->Arg(1)->Arg(100)->Unit(benchmark::kMillisecond);

/// A stream's start (LITAMIN2_BENCH_SEQUENCE): a new tracker with the shipped defaults
/// (`sensor: auto`) takes the sequence's first two scans, untimed, one thread: the sensor
/// recognition, the first map, and the second scan's start search (recovery.first_speeds).
/// Every stream of a daemon pays this once; a daemon started under a fleet pays it for all of
/// them within one scan period.
void BM_StreamStart(benchmark::State& state) {
  const std::vector<PointCloud>* sequence = sequence_scans(state);
  if (!sequence) return;
  if (sequence->size() < 2) {
    state.SkipWithError("the sequence has fewer than two scans");
    return;
  }
  tbb::task_arena arena(1);
  arena.execute([&] {
    for (auto _ : state) {
      Tracker tracker(TrackerConfig{});
      benchmark::DoNotOptimize(tracker.process((*sequence)[0]));
      benchmark::DoNotOptimize(tracker.process((*sequence)[1]));
    }
  });
  state.SetLabel("ms = a new stream's first two scans");
}
BENCHMARK(BM_StreamStart)->Unit(benchmark::kMillisecond)->MinTime(2.0);

/// Whole frames of a sequence (LITAMIN2_BENCH_SEQUENCE), preloaded: args threads, mode.
void BM_TrackerFrames(benchmark::State& state) {
  const std::vector<PointCloud>* sequence = sequence_scans(state);
  if (!sequence) return;
  const std::vector<PointCloud>& scans = *sequence;
  TrackerConfig config;
  config.registration.mode = state.range(1) ? CostMode::kIcpCov : CostMode::kIcp;
  in_arena(state, [&] {
    for (auto _ : state) {
      Tracker tracker(config);
      for (const PointCloud& scan : scans) benchmark::DoNotOptimize(tracker.process(scan));
    }
  });
  state.SetItemsProcessed(state.iterations() * scans.size());
  state.SetLabel(state.range(1) ? "icp+cov, frames/s = items_per_second"
                                : "icp, frames/s = items_per_second");
}
BENCHMARK(BM_TrackerFrames)
    ->Args({1, 0})
    ->Args({1, 1})
    ->Args({2, 0})
    ->Args({2, 1})
    ->Unit(benchmark::kMillisecond)
    ->MinTime(2.0);

}  // namespace

/// Pose-graph optimisation time as the graph grows (issue 5): a drive of N keyframes 2 m apart
/// around 400 m blocks, odometry with a small heading drift, and a loop edge wherever the drive
/// passes a block corner it passed before (every 200 keyframes).
void BM_PoseGraph(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  std::vector<Eigen::Isometry3d> truth;
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  for (int i = 0; i < n; ++i) {
    truth.push_back(pose);
    Eigen::Isometry3d step = Eigen::Isometry3d::Identity();
    step.translation().x() = 2.0;
    if (i % 50 == 49)
      step.linear() = Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ()).matrix();
    pose = pose * step;
  }
  std::vector<mapping::PoseGraphEdge> edges;
  std::vector<Eigen::Isometry3d> initial = {truth[0]};
  Eigen::Isometry3d drift = Eigen::Isometry3d::Identity();
  drift.linear() = Eigen::AngleAxisd(1e-4, Eigen::Vector3d::UnitZ()).matrix();
  for (int i = 1; i < n; ++i) {
    mapping::PoseGraphEdge e;
    e.from = i - 1;
    e.to = i;
    e.relative = truth[i - 1].inverse() * truth[i] * drift;
    e.sigma << 0.02, 0.02, 0.02, 3e-4, 3e-4, 3e-4;
    edges.push_back(e);
    initial.push_back(initial.back() * e.relative);
  }
  for (int i = 200; i < n; i += 200) {
    mapping::PoseGraphEdge e;
    e.from = i - 200;
    e.to = i;
    e.relative = truth[i - 200].inverse() * truth[i];
    e.sigma << 0.1, 0.1, 0.1, 0.009, 0.009, 0.009;
    edges.push_back(e);
  }
  std::vector<bool> fixed(static_cast<std::size_t>(n), false);
  fixed[0] = true;
  for (auto _ : state) {
    std::vector<Eigen::Isometry3d> poses = initial;
    const auto result =
        mapping::optimize_pose_graph(poses, fixed, edges, mapping::PoseGraphConfig{});
    benchmark::DoNotOptimize(result);
    state.counters["iterations"] = result.iterations;
  }
}
BENCHMARK(BM_PoseGraph)->Arg(1000)->Arg(3000)->Arg(10000)->Unit(benchmark::kMillisecond);

namespace {

const char* kHelp =
    "litamin2-bench: time of each LiTAMIN2 stage and of whole frames on KITTI-size scans.\n"
    "Usage: litamin2-bench [OPTIONS]\n"
    "\n"
    "Options:\n"
    "  -h, --help               print this help and Google Benchmark's options, and exit.\n"
    "  -V, --version            print the version and exit.\n"
    "  --benchmark_...          Google Benchmark's options (below), e.g.\n"
    "                           --benchmark_filter=REGEX, --benchmark_repetitions=N.\n"
    "\n"
    "Environment:\n"
    "  LITAMIN2_BENCH_SEQUENCE  a sequence folder (KITTI layout: velodyne/*.bin, e.g. from\n"
    "                           litamin2-sim) for the whole-frame benchmarks (TrackerFrames,\n"
    "                           VoxelizeSequence); without it they are skipped with a message.\n"
    "  LITAMIN2_KEYING=sse2     force the baseline voxel keying (comparisons with AVX2).\n"
    "The stage benchmarks read the two real KITTI scans of ../shared/data.\n"
    "Commands, machine and results: docs/benchmarks.md.\n"
    "\n"
    "Exit status: 0 done, 1 the shared scans are missing, 2 usage error.\n"
    "\n"
    "Google Benchmark's options:\n\n";

}  // namespace

int main(int argc, char** argv) {
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--help" || arg == "-h") std::cout << kHelp << std::flush;
    if (arg == "--version" || arg == "-V") {
      std::cout << "litamin2-bench " << litamin2::version() << "\n";
      return 0;
    }
  }
  benchmark::Initialize(&argc, argv);  // prints its own usage and exits on --help
  // What Google Benchmark did not take (its own report would be one line per argument, named
  // after argv[0]'s full path).
  if (argc > 1) {
    std::string rest;
    for (int i = 1; i < argc; ++i) rest += (i > 1 ? " " : "") + std::string(argv[i]);
    return tools::usage_error(kProg, "unrecognized option(s): " + rest);
  }
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
