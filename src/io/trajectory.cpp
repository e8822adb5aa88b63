#include "litamin2/io/trajectory.hpp"

#include <cmath>
#include <cstdio>
#include <string_view>

#include "litamin2/core/value_checks.hpp"
#include "litamin2/io/file_util.hpp"
#include "litamin2/io/io_error.hpp"

namespace litamin2::io {

namespace {

std::string line_prefix(std::size_t line_no) {
  return "line " + std::to_string(line_no) + ": ";
}

/// Parses all tokens of a line as doubles, throwing IoError on a non-number.
std::vector<double> parse_numbers(const std::string& path, std::size_t line_no,
                                  const std::vector<std::string_view>& tokens) {
  std::vector<double> values;
  values.reserve(tokens.size());
  for (std::string_view token : tokens) {
    const auto v = parse_double(token);
    if (!v) {
      throw IoError(path, line_prefix(line_no) + "'" + std::string(token) + "' is not a number");
    }
    values.push_back(*v);
  }
  return values;
}

void append_formatted(std::string& out, const char* format, double value) {
  char buf[64];
  const int n = std::snprintf(buf, sizeof(buf), format, value);
  out.append(buf, static_cast<std::size_t>(n));
}

}  // namespace

std::vector<Eigen::Isometry3d> read_kitti_poses(const std::string& path) {
  const std::string text = read_file_bytes(path);
  const auto lines = split_lines(text);
  std::vector<Eigen::Isometry3d> poses;
  poses.reserve(lines.size());
  std::size_t first_blank = 0;  // 1-based line number of a blank line seen, 0 if none
  for (std::size_t i = 0; i < lines.size(); ++i) {
    const std::size_t line_no = i + 1;
    const auto tokens = split_whitespace(lines[i]);
    if (tokens.empty()) {
      if (first_blank == 0) first_blank = line_no;
      continue;
    }
    if (first_blank != 0) {
      throw IoError(path, line_prefix(first_blank) +
                              "blank line inside the file (frames would be misnumbered)");
    }
    if (tokens.size() != 12) {
      throw IoError(path, line_prefix(line_no) + std::to_string(tokens.size()) +
                              " values, expected 12 (row-major 3x4 pose)");
    }
    const std::vector<double> v = parse_numbers(path, line_no, tokens);
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 4; ++c) pose.matrix()(r, c) = v[static_cast<std::size_t>(r * 4 + c)];
    }
    if (!pose.matrix().allFinite()) {
      throw IoError(path, line_prefix(line_no) + "pose contains NaN or Inf");
    }
    if (const auto why = checks::rotation_error(pose.linear()))
      throw IoError(path, line_prefix(line_no) + "rotation " + *why);
    if (const auto why = checks::position_error(pose.translation()))
      throw IoError(path, line_prefix(line_no) + "translation " + *why);
    poses.push_back(pose);
  }
  if (poses.empty()) throw IoError(path, "empty file: no poses");
  return poses;
}

void write_kitti_poses(const std::string& path, const std::vector<Eigen::Isometry3d>& poses) {
  std::string out;
  out.reserve(poses.size() * 12 * 24);
  for (const Eigen::Isometry3d& pose : poses) {
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 4; ++c) {
        if (r + c > 0) out += ' ';
        append_formatted(out, "%.16e", pose.matrix()(r, c));
      }
    }
    out += '\n';
  }
  write_file_bytes(path, out.data(), out.size());
}

std::vector<TimedPose> read_tum(const std::string& path) {
  const std::string text = read_file_bytes(path);
  const auto lines = split_lines(text);
  std::vector<TimedPose> poses;
  poses.reserve(lines.size());
  for (std::size_t i = 0; i < lines.size(); ++i) {
    const std::size_t line_no = i + 1;
    const auto tokens = split_whitespace(lines[i]);
    if (tokens.empty() || tokens[0].front() == '#') continue;
    if (tokens.size() != 8) {
      throw IoError(path, line_prefix(line_no) + std::to_string(tokens.size()) +
                              " values, expected 8 (t x y z qx qy qz qw)");
    }
    const std::vector<double> v = parse_numbers(path, line_no, tokens);
    if (!std::isfinite(v[0])) throw IoError(path, line_prefix(line_no) + "non-finite time");
    if (const auto why = checks::position_error(Eigen::Vector3d(v[1], v[2], v[3])))
      throw IoError(path, line_prefix(line_no) + "translation " + *why);
    if (const auto why = checks::unit_quaternion_error(v[7], v[4], v[5], v[6]))
      throw IoError(path, line_prefix(line_no) + "quaternion " + *why);
    Eigen::Quaterniond q(v[7], v[4], v[5], v[6]);
    q.normalize();  // removes the rounding of the file's digits only
    TimedPose tp;
    tp.time = v[0];
    tp.pose.linear() = q.toRotationMatrix();
    tp.pose.translation() = Eigen::Vector3d(v[1], v[2], v[3]);
    poses.push_back(tp);
  }
  if (poses.empty()) throw IoError(path, "no poses (empty or comments only)");
  return poses;
}

void write_tum(const std::string& path, const std::vector<TimedPose>& poses) {
  std::string out;
  out.reserve(poses.size() * 8 * 24);
  for (const TimedPose& tp : poses) {
    Eigen::Quaterniond q(tp.pose.linear());
    q.normalize();
    if (q.w() < 0) q.coeffs() = -q.coeffs();
    const Eigen::Vector3d t = tp.pose.translation();
    append_formatted(out, "%.17g", tp.time);
    for (double value : {t.x(), t.y(), t.z(), q.x(), q.y(), q.z(), q.w()}) {
      out += ' ';
      append_formatted(out, "%.16e", value);
    }
    out += '\n';
  }
  write_file_bytes(path, out.data(), out.size());
}

}  // namespace litamin2::io
