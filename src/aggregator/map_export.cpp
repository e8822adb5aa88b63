#include "litamin2/aggregator/map_export.hpp"

#include "litamin2/io/io_error.hpp"
#include "litamin2/io/pcd.hpp"
#include "litamin2/io/ply.hpp"
#include "litamin2/io/trajectory.hpp"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <system_error>

namespace litamin2::aggregator {

namespace {

/// The least eigenvector of a distribution's covariance (its surface normal), with nz >= 0.
Eigen::Vector3d normal_of(const Eigen::Matrix3d& cov) {
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(cov);
  Eigen::Vector3d n = eigen.eigenvectors().col(0);
  if (n.z() < 0.0) n = -n;
  return n;
}

}  // namespace

std::optional<MapFormat> map_format(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (ext == ".ply") return MapFormat::kPly;
  if (ext == ".pcd") return MapFormat::kPcd;
  return std::nullopt;
}

void write_map_pcd(const std::string& path, const std::vector<Distribution>& map) {
  PointCloud cloud;
  cloud.points.reserve(map.size());
  static const char* names[] = {"c00", "c01", "c02", "c11", "c12", "c22", "nx", "ny", "nz"};
  std::vector<io::PcdField> fields;
  for (const char* name : names) fields.push_back({name, 'F', 4, {}});
  fields.push_back({"count", 'U', 4, {}});
  for (io::PcdField& f : fields) f.values.reserve(map.size());
  for (const Distribution& d : map) {
    cloud.points.push_back(d.mean.cast<float>());
    const Eigen::Matrix3d& c = d.cov;
    const Eigen::Vector3d n = normal_of(c);
    const double row[] = {c(0, 0), c(0, 1), c(0, 2), c(1, 1), c(1, 2),
                          c(2, 2), n.x(),   n.y(),   n.z(),   static_cast<double>(d.count)};
    for (std::size_t i = 0; i < fields.size(); ++i) fields[i].values.push_back(row[i]);
  }
  io::write_pcd_binary(path, cloud, fields);
}

void write_map_ply(const std::string& path, const std::vector<Distribution>& map) {
  static const std::vector<std::string> names = {"x",   "y",   "z",  "c00", "c01", "c02",  "c11",
                                                 "c12", "c22", "nx", "ny",  "nz",  "count"};
  std::vector<float> values;
  values.reserve(map.size() * names.size());
  for (const Distribution& d : map) {
    const Eigen::Vector3d n = normal_of(d.cov);
    const Eigen::Matrix3d& c = d.cov;
    const double row[] = {d.mean.x(),
                          d.mean.y(),
                          d.mean.z(),
                          c(0, 0),
                          c(0, 1),
                          c(0, 2),
                          c(1, 1),
                          c(1, 2),
                          c(2, 2),
                          n.x(),
                          n.y(),
                          n.z(),
                          static_cast<double>(d.count)};
    for (double v : row) values.push_back(static_cast<float>(v));
  }
  io::write_ply_vertices(path, names, values);
}

std::string stream_file_stem(const std::string& stream) {
  std::string out;
  for (char c : stream) {
    if (c == '/')
      out += "__";
    else
      out += c;
  }
  return out;
}

std::vector<std::string> write_trajectories(const std::string& dir, const StreamPoses& poses) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) throw io::IoError(dir, "cannot create the directory: " + ec.message());
  std::vector<Eigen::Isometry3d> kitti;
  std::vector<io::TimedPose> tum;
  for (const StreamPoses::Entry& e : poses.keyframes) {
    kitti.push_back(e.pose);
    tum.push_back({e.stamp.seconds(), e.pose});
  }
  const std::string stem = (std::filesystem::path(dir) / stream_file_stem(poses.stream)).string();
  io::write_kitti_poses(stem + "_kitti.txt", kitti);
  io::write_tum(stem + "_tum.txt", tum);
  return {stem + "_kitti.txt", stem + "_tum.txt"};
}

std::vector<Distribution> map_in_box(mapping::TileMap& tiles,
                                     const std::optional<ExportOptions::Box>& box,
                                     std::size_t* tiles_read) {
  mapping::TileKey lo{std::numeric_limits<std::int32_t>::min(),
                      std::numeric_limits<std::int32_t>::min()};
  mapping::TileKey hi{std::numeric_limits<std::int32_t>::max(),
                      std::numeric_limits<std::int32_t>::max()};
  if (box) tiles.geometry().tile_range(box->min_x, box->min_y, box->max_x, box->max_y, lo, hi);
  std::vector<mapping::TileKey> keys;
  for (const auto& [key, summary] : tiles.index()) {
    if (key.ix >= lo.ix && key.ix <= hi.ix && key.iy >= lo.iy && key.iy <= hi.iy)
      keys.push_back(key);
  }
  std::vector<Distribution> out;
  for (const mapping::TileKey& key : keys) {
    for (Distribution& d : tiles.tile(key)->distributions(tiles.geometry())) {
      if (box && (d.mean.x() < box->min_x || d.mean.x() > box->max_x || d.mean.y() < box->min_y ||
                  d.mean.y() > box->max_y))
        continue;
      out.push_back(std::move(d));
    }
  }
  if (tiles_read) *tiles_read = keys.size();
  return out;
}

ExportResult export_store(const ExportOptions& options) {
  const std::optional<MapFormat> format = options.map_file.empty()
                                              ? std::optional<MapFormat>(MapFormat::kPly)
                                              : map_format(options.map_file);
  if (!format)
    throw std::invalid_argument("--map " + options.map_file +
                                ": unsupported map format (use a .ply or .pcd file name)");
  CoreOptions core_options;
  core_options.recovery =
      options.replay ? CoreOptions::Recovery::kReplay : CoreOptions::Recovery::kTables;
  core_options.tiles = options.tiles;
  AggregatorCore core(options.store, store::OpenMode::kReadOnly, options.mapper, {},
                      options.progress, core_options);
  const mapping::Mapper& mapper = core.mapper();
  ExportResult result;
  result.keyframes = mapper.stats().keyframes;
  result.streams = mapper.stats().streams;
  result.loops = mapper.loops().size();
  if (!options.map_file.empty()) {
    // The keyframes the aggregator had not fused into the tiles yet (all, replayed), in memory.
    core.update_map(0);
    const std::vector<Distribution> map = map_in_box(core.tiles(), options.box, &result.tiles);
    result.voxels = map.size();
    if (*format == MapFormat::kPcd)
      write_map_pcd(options.map_file, map);
    else
      write_map_ply(options.map_file, map);
    result.files.push_back(options.map_file);
  }
  if (!options.trajectories_dir.empty()) {
    // frames.txt: which frame each stream's trajectory is in (the map frame once a loop has
    // joined it to the map's anchor stream, else its own group's anchor's odometry frame).
    std::ostringstream frames;
    frames << "# stream anchor_stream in_map_frame keyframes\n";
    for (const StreamPoses& s : all_stream_poses(mapper)) {
      for (std::string& f : write_trajectories(options.trajectories_dir, s))
        result.files.push_back(std::move(f));
      frames << s.stream << ' ' << s.anchor << ' ' << (s.in_map_frame ? 1 : 0) << ' '
             << s.keyframes.size() << '\n';
    }
    const std::string path =
        (std::filesystem::path(options.trajectories_dir) / "frames.txt").string();
    std::ofstream(path) << frames.str();
    result.files.push_back(path);
  }
  return result;
}

}  // namespace litamin2::aggregator
