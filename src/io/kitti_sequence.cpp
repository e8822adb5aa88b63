#include "litamin2/io/kitti_sequence.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <stdexcept>
#include <system_error>

#include "litamin2/io/file_util.hpp"
#include "litamin2/io/io_error.hpp"
#include "litamin2/io/kitti_calib.hpp"
#include "litamin2/io/pcd.hpp"
#include "litamin2/io/trajectory.hpp"

namespace litamin2::io {

namespace fs = std::filesystem;

namespace {

std::string lower_extension(const fs::path& p) {
  std::string ext = p.extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext;
}

/// Regular files of `dir` whose lower-case extension is in `extensions`, sorted by file name.
std::vector<std::string> list_scans(const fs::path& dir,
                                    const std::vector<std::string>& extensions) {
  std::vector<fs::path> files;
  std::error_code ec;
  fs::directory_iterator it(dir, ec);
  if (ec) throw IoError(dir.string(), "cannot list folder: " + ec.message());
  for (; it != fs::directory_iterator(); it.increment(ec)) {
    if (ec) throw IoError(dir.string(), "cannot list folder: " + ec.message());
    std::error_code ec2;
    if (!it->is_regular_file(ec2)) continue;
    const std::string ext = lower_extension(it->path());
    if (std::find(extensions.begin(), extensions.end(), ext) != extensions.end()) {
      files.push_back(it->path());
    }
  }
  std::sort(files.begin(), files.end(), [](const fs::path& a, const fs::path& b) {
    return a.filename().string() < b.filename().string();
  });
  std::vector<std::string> out;
  out.reserve(files.size());
  for (const fs::path& f : files) out.push_back(f.string());
  return out;
}

std::vector<double> read_times(const std::string& path) {
  const std::string text = read_file_bytes(path);
  const auto lines = split_lines(text);
  std::vector<double> times;
  for (std::size_t i = 0; i < lines.size(); ++i) {
    const auto tokens = split_whitespace(lines[i]);
    if (tokens.empty()) continue;
    const auto v = tokens.size() == 1 ? parse_double(tokens[0]) : std::nullopt;
    if (!v || !std::isfinite(*v)) {
      throw IoError(path, "line " + std::to_string(i + 1) + ": expected one finite number");
    }
    times.push_back(*v);
  }
  return times;
}

bool is_file(const fs::path& p) {
  std::error_code ec;
  return fs::is_regular_file(p, ec);
}

}  // namespace

ScanSequence::ScanSequence(const std::string& folder, const KittiBinOptions& bin_options,
                           bool pcd_scans)
    : folder_(folder), bin_options_(bin_options) {
  std::error_code ec;
  const fs::path dir(folder);
  if (!fs::exists(dir, ec)) throw IoError(folder, "folder does not exist");
  if (!fs::is_directory(dir, ec)) throw IoError(folder, "is not a folder");

  is_kitti_ = fs::is_directory(dir / "velodyne", ec);
  if (is_kitti_ && pcd_scans) {
    if (!fs::is_directory(dir / "pcd", ec))
      throw IoError(folder, "has no pcd/ folder of scans (litamin2-sim --sweep-motion writes one)");
    paths_ = list_scans(dir / "pcd", {".pcd"});
    if (paths_.empty()) throw IoError((dir / "pcd").string(), "holds no .pcd scans");
  } else if (is_kitti_) {
    paths_ = list_scans(dir / "velodyne", {".bin"});
    if (paths_.empty()) throw IoError((dir / "velodyne").string(), "holds no .bin scans");
  } else {
    paths_ = list_scans(dir, {".bin", ".pcd"});
    if (paths_.empty()) throw IoError(folder, "holds no .bin or .pcd scans (and no velodyne/)");
  }

  timestamps_.resize(paths_.size());
  for (std::size_t i = 0; i < paths_.size(); ++i) timestamps_[i] = 0.1 * static_cast<double>(i);
  if (!is_kitti_) return;

  const fs::path times = dir / "times.txt";
  if (is_file(times)) {
    std::vector<double> t = read_times(times.string());
    if (t.size() != paths_.size()) {
      throw IoError(times.string(), std::to_string(t.size()) + " timestamps for " +
                                        std::to_string(paths_.size()) + " scans in " +
                                        (pcd_scans ? "pcd/" : "velodyne/"));
    }
    timestamps_ = std::move(t);
  }

  const fs::path calib = dir / "calib.txt";
  if (is_file(calib)) velo_to_cam_ = read_kitti_velo_to_cam(calib.string());

  fs::path poses = dir / "poses.txt";
  if (!is_file(poses)) {
    // <dataset>/sequences/XX -> <dataset>/poses/XX.txt
    const fs::path canonical = fs::weakly_canonical(dir, ec);
    const fs::path seq_dir = ec ? dir : canonical;
    fs::path name = seq_dir.filename();
    if (name.empty()) name = seq_dir.parent_path().filename();
    const fs::path parent =
        seq_dir.filename().empty() ? seq_dir.parent_path().parent_path() : seq_dir.parent_path();
    if (parent.filename() == "sequences") {
      poses = parent.parent_path() / "poses" / (name.string() + ".txt");
    }
  }
  if (is_file(poses)) {
    std::vector<Eigen::Isometry3d> gt = read_kitti_poses(poses.string());
    if (gt.size() != paths_.size()) {
      throw IoError(poses.string(), std::to_string(gt.size()) + " poses for " +
                                        std::to_string(paths_.size()) + " scans in " + folder);
    }
    ground_truth_cam_ = std::move(gt);
  }
}

const std::string& ScanSequence::path(std::size_t i) const {
  if (i >= paths_.size()) {
    throw std::out_of_range("ScanSequence::path(" + std::to_string(i) + "): only " +
                            std::to_string(paths_.size()) + " scans");
  }
  return paths_[i];
}

double ScanSequence::timestamp(std::size_t i) const {
  if (i >= timestamps_.size()) {
    throw std::out_of_range("ScanSequence::timestamp(" + std::to_string(i) + "): only " +
                            std::to_string(timestamps_.size()) + " scans");
  }
  return timestamps_[i];
}

PointCloud ScanSequence::load(std::size_t i) const {
  const std::string& p = path(i);
  if (lower_extension(fs::path(p)) == ".pcd") return read_pcd(p);
  return read_kitti_bin(p, bin_options_);
}

std::optional<std::vector<Eigen::Isometry3d>> ScanSequence::ground_truth_velo() const {
  if (!ground_truth_cam_ || !velo_to_cam_) return std::nullopt;
  return cam_to_velo_trajectory(*ground_truth_cam_, *velo_to_cam_);
}

}  // namespace litamin2::io
