// kiss_icp_runner: KISS-ICP's C++ pipeline on a KITTI-style folder of scans, for side-by-side
// benchmarks with litamin2 (scripts/peers/side-by-side.sh). Benchmark-only: built outside
// litamin2's build by scripts/peers/build-kiss-icp.sh against a KISS-ICP source folder.
//
// Input: SCANS/velodyne/*.bin (float32 x y z intensity), or with --deskew SCANS/pcd/*.pcd with
// a per-point time field `t` (what litamin2-sim --sweep-motion writes; DATA binary, x y z as
// F4, t as F4 or F8). Output: OUT/poses_kitti_velo.txt (one 3x4 row per scan, the sensor's
// pose in the first scan's sensor frame) and, when SCANS/calib.txt has a Tr line,
// OUT/poses_kitti_cam.txt (the camera-0 convention of KITTI's ground truth: Tr P Tr^-1).
// OUT/stats.json holds frames, wall seconds and frames/s.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "kiss_icp/pipeline/KissICP.hpp"

namespace fs = std::filesystem;

namespace {

struct Options {
  fs::path scans, output;
  bool deskew = false;
  int threads = 1;
  double voxel_size = 1.0;  // KISS-ICP's default: max_range / 100
  double max_range = 100.0;
  double min_range = 0.0;
  bool quiet = false;
};

[[noreturn]] void usage(int code) {
  std::fprintf(code == 0 ? stdout : stderr,
               "Usage: kiss_icp_runner [options] -o OUT SCANS\n"
               "Runs KISS-ICP (benchmark-only peer) over SCANS/velodyne/*.bin, or with --deskew\n"
               "over SCANS/pcd/*.pcd with a per-point time field t, and writes\n"
               "OUT/poses_kitti_velo.txt, OUT/poses_kitti_cam.txt (when SCANS/calib.txt has Tr)\n"
               "and OUT/stats.json.\n\n"
               "Options:\n"
               "  -o, --output DIR    output folder (created)\n"
               "  --deskew            read pcd/ scans with per-point times and deskew\n"
               "  --threads N         KISS-ICP's max_num_threads (default 1; 0 = all cores)\n"
               "  --voxel-size M      (default 1.0, KISS-ICP's max_range / 100)\n"
               "  --max-range M       (default 100)\n"
               "  --min-range M       (default 0)\n"
               "  -q, --quiet         no progress on stderr\n"
               "  -h, --help          this text\n");
  std::exit(code);
}

double to_double(const std::string& what, const char* text) {
  char* end = nullptr;
  const double v = std::strtod(text, &end);
  if (end == text || *end != '\0') throw std::invalid_argument(what + ": not a number: " + text);
  return v;
}

Options parse(int argc, char** argv) {
  Options o;
  std::vector<std::string> positional;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto value = [&]() -> const char* {
      if (i + 1 >= argc) throw std::invalid_argument(a + " needs a value");
      return argv[++i];
    };
    if (a == "-h" || a == "--help") usage(0);
    if (a == "-o" || a == "--output")
      o.output = value();
    else if (a == "--deskew")
      o.deskew = true;
    else if (a == "--threads")
      o.threads = static_cast<int>(to_double(a, value()));
    else if (a == "--voxel-size")
      o.voxel_size = to_double(a, value());
    else if (a == "--max-range")
      o.max_range = to_double(a, value());
    else if (a == "--min-range")
      o.min_range = to_double(a, value());
    else if (a == "-q" || a == "--quiet")
      o.quiet = true;
    else if (!a.empty() && a[0] == '-')
      throw std::invalid_argument("unknown option " + a);
    else
      positional.push_back(a);
  }
  if (positional.size() != 1 || o.output.empty()) usage(2);
  o.scans = positional[0];
  if (!(o.voxel_size > 0.0) || !(o.max_range > o.min_range) || o.min_range < 0.0 || o.threads < 0)
    throw std::invalid_argument("invalid --voxel-size, --max-range, --min-range or --threads");
  return o;
}

std::vector<fs::path> files_with_extension(const fs::path& dir, const std::string& ext) {
  if (!fs::is_directory(dir)) throw std::runtime_error(dir.string() + ": not a folder");
  std::vector<fs::path> files;
  for (const auto& entry : fs::directory_iterator(dir))
    if (entry.is_regular_file() && entry.path().extension() == ext) files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  if (files.empty()) throw std::runtime_error(dir.string() + ": no " + ext + " files");
  return files;
}

std::vector<Eigen::Vector3d> read_bin(const fs::path& path) {
  const auto bytes = static_cast<std::size_t>(fs::file_size(path));
  if (bytes % (4 * sizeof(float)) != 0)
    throw std::runtime_error(path.string() + ": size is not a multiple of 16 bytes");
  std::vector<float> raw(bytes / sizeof(float));
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error(path.string() + ": cannot open");
  in.read(reinterpret_cast<char*>(raw.data()), static_cast<std::streamsize>(bytes));
  if (!in) throw std::runtime_error(path.string() + ": short read");
  std::vector<Eigen::Vector3d> points;
  points.reserve(raw.size() / 4);
  for (std::size_t i = 0; i + 3 < raw.size(); i += 4)
    points.emplace_back(raw[i], raw[i + 1], raw[i + 2]);
  return points;
}

// A PCD with DATA binary and x, y, z (F4) and t (F4 or F8) among its fields.
void read_pcd(const fs::path& path, std::vector<Eigen::Vector3d>& points,
              std::vector<double>& times) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error(path.string() + ": cannot open");
  std::vector<std::string> fields;
  std::vector<int> sizes, counts;
  std::vector<char> types;
  std::size_t n_points = 0;
  std::string line;
  bool binary = false;
  while (std::getline(in, line)) {
    std::istringstream ls(line);
    std::string key;
    ls >> key;
    if (key == "FIELDS") {
      for (std::string f; ls >> f;) fields.push_back(f);
    } else if (key == "SIZE") {
      for (int s; ls >> s;) sizes.push_back(s);
    } else if (key == "TYPE") {
      for (char t; ls >> t;) types.push_back(t);
    } else if (key == "COUNT") {
      for (int c; ls >> c;) counts.push_back(c);
    } else if (key == "POINTS") {
      ls >> n_points;
    } else if (key == "DATA") {
      std::string kind;
      ls >> kind;
      binary = kind == "binary";
      break;
    }
  }
  if (!binary) throw std::runtime_error(path.string() + ": only DATA binary is read");
  if (counts.empty()) counts.assign(fields.size(), 1);
  if (sizes.size() != fields.size() || types.size() != fields.size() ||
      counts.size() != fields.size())
    throw std::runtime_error(path.string() + ": FIELDS, SIZE, TYPE and COUNT differ in length");
  std::size_t stride = 0;
  int ox = -1, oy = -1, oz = -1, ot = -1, tsize = 0;
  for (std::size_t i = 0; i < fields.size(); ++i) {
    const int offset = static_cast<int>(stride);
    if (fields[i] == "x") ox = offset;
    if (fields[i] == "y") oy = offset;
    if (fields[i] == "z") oz = offset;
    if (fields[i] == "t" && types[i] == 'F') ot = offset, tsize = sizes[i];
    stride += static_cast<std::size_t>(sizes[i]) * static_cast<std::size_t>(counts[i]);
  }
  if (ox < 0 || oy < 0 || oz < 0 || ot < 0)
    throw std::runtime_error(path.string() + ": needs fields x, y, z and a float t");
  std::vector<char> data(stride * n_points);
  in.read(data.data(), static_cast<std::streamsize>(data.size()));
  if (!in) throw std::runtime_error(path.string() + ": point data shorter than POINTS says");
  points.clear();
  times.clear();
  points.reserve(n_points);
  times.reserve(n_points);
  for (std::size_t i = 0; i < n_points; ++i) {
    const char* p = data.data() + i * stride;
    float x, y, z;
    std::memcpy(&x, p + ox, 4);
    std::memcpy(&y, p + oy, 4);
    std::memcpy(&z, p + oz, 4);
    double t;
    if (tsize == 8) {
      std::memcpy(&t, p + ot, 8);
    } else {
      float tf;
      std::memcpy(&tf, p + ot, 4);
      t = tf;
    }
    points.emplace_back(x, y, z);
    times.push_back(t);
  }
}

// Tr (velodyne to camera 0) from a KITTI calib.txt, if it has one.
std::optional<Eigen::Isometry3d> read_tr(const fs::path& calib) {
  std::ifstream in(calib);
  for (std::string line; std::getline(in, line);) {
    std::istringstream ls(line);
    std::string key;
    ls >> key;
    if (key != "Tr:") continue;
    Eigen::Matrix4d m = Eigen::Matrix4d::Identity();
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 4; ++c)
        if (!(ls >> m(r, c))) throw std::runtime_error(calib.string() + ": short Tr line");
    Eigen::Isometry3d tr;
    tr.matrix() = m;
    return tr;
  }
  return std::nullopt;
}

void write_poses(const fs::path& path, const std::vector<Eigen::Isometry3d>& poses) {
  std::ofstream out(path);
  out.precision(9);
  for (const auto& pose : poses) {
    const Eigen::Matrix4d& m = pose.matrix();
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 4; ++c) out << m(r, c) << (r == 2 && c == 3 ? '\n' : ' ');
  }
  if (!out) throw std::runtime_error(path.string() + ": write failed");
}

}  // namespace

int main(int argc, char** argv) try {
  const Options o = parse(argc, argv);
  const auto files = o.deskew ? files_with_extension(o.scans / "pcd", ".pcd")
                              : files_with_extension(o.scans / "velodyne", ".bin");
  fs::create_directories(o.output);
  kiss_icp::pipeline::KISSConfig config;
  config.voxel_size = o.voxel_size;
  config.max_range = o.max_range;
  config.min_range = o.min_range;
  config.max_num_threads = o.threads;
  config.deskew = o.deskew;
  kiss_icp::pipeline::KissICP pipeline(config);

  std::vector<Eigen::Isometry3d> poses;
  poses.reserve(files.size());
  std::vector<Eigen::Vector3d> points;
  std::vector<double> times;
  double registration_s = 0.0;
  for (std::size_t i = 0; i < files.size(); ++i) {
    if (o.deskew) {
      read_pcd(files[i], points, times);
    } else {
      points = read_bin(files[i]);
      times.clear();
    }
    const auto start = std::chrono::steady_clock::now();
    pipeline.RegisterFrame(points, times);
    registration_s +=
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    Eigen::Isometry3d pose;
    pose.matrix() = pipeline.pose().matrix();
    poses.push_back(pose);
    if (!o.quiet && (i + 1) % 100 == 0)
      std::fprintf(stderr, "kiss_icp_runner: %zu / %zu scans\n", i + 1, files.size());
  }
  write_poses(o.output / "poses_kitti_velo.txt", poses);
  if (const auto tr = read_tr(o.scans / "calib.txt")) {
    std::vector<Eigen::Isometry3d> cam;
    cam.reserve(poses.size());
    for (const auto& p : poses) cam.push_back(*tr * p * tr->inverse());
    write_poses(o.output / "poses_kitti_cam.txt", cam);
  }
  std::ofstream stats(o.output / "stats.json");
  stats << "{\"frames\": " << files.size() << ", \"registration_s\": " << registration_s
        << ", \"frames_per_second\": " << static_cast<double>(files.size()) / registration_s
        << ", \"deskew\": " << (o.deskew ? "true" : "false") << ", \"threads\": " << o.threads
        << "}\n";
  return 0;
} catch (const std::exception& e) {
  std::fprintf(stderr, "kiss_icp_runner: %s\n", e.what());
  return 1;
}
