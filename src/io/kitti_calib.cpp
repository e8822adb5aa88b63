#include "litamin2/io/kitti_calib.hpp"

#include <cmath>
#include <filesystem>
#include <stdexcept>
#include <string_view>

#include "litamin2/core/value_checks.hpp"
#include "litamin2/io/file_util.hpp"
#include "litamin2/io/io_error.hpp"

namespace litamin2::io {

namespace {

struct Entry {
  std::string key;
  std::vector<std::string_view> values;
  std::size_t line_no = 0;
};

std::vector<double> numbers(const std::string& path, const Entry& e, std::size_t expected) {
  const std::string where = "line " + std::to_string(e.line_no) + " (" + e.key + "): ";
  if (e.values.size() != expected) {
    throw IoError(path, where + std::to_string(e.values.size()) + " values, expected " +
                            std::to_string(expected));
  }
  std::vector<double> out;
  for (std::string_view token : e.values) {
    const auto v = parse_double(token);
    if (!v || !std::isfinite(*v)) {
      throw IoError(path, where + "'" + std::string(token) + "' is not a finite number");
    }
    out.push_back(*v);
  }
  return out;
}

Eigen::Isometry3d from_row_major(const std::string& path, const std::string& what,
                                 const std::vector<double>& rotation9,
                                 const std::vector<double>& translation3) {
  Eigen::Isometry3d tr = Eigen::Isometry3d::Identity();
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) tr.linear()(r, c) = rotation9[static_cast<std::size_t>(r * 3 + c)];
    tr.translation()(r) = translation3[static_cast<std::size_t>(r)];
  }
  if (const auto why = checks::rotation_error(tr.linear()))
    throw IoError(path, what + ": rotation part " + *why);
  if (const auto why = checks::position_error(tr.translation()))
    throw IoError(path, what + ": translation " + *why);
  return tr;
}

Eigen::Isometry3d from_3x4(const std::string& path, const Entry& e) {
  const std::vector<double> v = numbers(path, e, 12);
  return from_row_major(path, "line " + std::to_string(e.line_no) + " (" + e.key + ")",
                        {v[0], v[1], v[2], v[4], v[5], v[6], v[8], v[9], v[10]},
                        {v[3], v[7], v[11]});
}

/// Parses "<first>" or "<first>-<last>" table keys.
std::optional<std::pair<int, int>> parse_range(std::string_view key) {
  const std::size_t dash = key.find('-');
  const auto first = parse_unsigned(key.substr(0, dash));
  if (!first || *first > 1000000) return std::nullopt;
  if (dash == std::string_view::npos) return std::pair<int, int>(int(*first), int(*first));
  const auto last = parse_unsigned(key.substr(dash + 1));
  if (!last || *last > 1000000) return std::nullopt;
  return std::pair<int, int>(int(*first), int(*last));
}

}  // namespace

Eigen::Isometry3d read_kitti_velo_to_cam(const std::string& path, std::optional<int> sequence) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) {
    return read_kitti_velo_to_cam((std::filesystem::path(path) / "calib.txt").string(), sequence);
  }
  const std::string text = read_file_bytes(path);
  const auto lines = split_lines(text);
  std::vector<Entry> entries;
  for (std::size_t i = 0; i < lines.size(); ++i) {
    std::string_view line = lines[i];
    const auto tokens = split_whitespace(line);
    if (tokens.empty() || tokens[0].front() == '#') continue;
    const std::size_t colon = line.find(':');
    if (colon == std::string_view::npos) {
      throw IoError(path, "line " + std::to_string(i + 1) + ": expected 'key: values'");
    }
    const auto key_tokens = split_whitespace(line.substr(0, colon));
    if (key_tokens.size() != 1) {
      throw IoError(path, "line " + std::to_string(i + 1) + ": malformed key");
    }
    entries.push_back(
        Entry{std::string(key_tokens[0]), split_whitespace(line.substr(colon + 1)), i + 1});
  }
  auto find = [&](const std::string& key) -> const Entry* {
    for (const Entry& e : entries) {
      if (e.key == key) return &e;
    }
    return nullptr;
  };

  if (const Entry* e = find("Tr")) return from_3x4(path, *e);
  if (const Entry* e = find("Tr_velo_to_cam")) return from_3x4(path, *e);
  const Entry* r = find("R");
  const Entry* t = find("T");
  if (r && t) {
    return from_row_major(path, "R/T entries", numbers(path, *r, 9), numbers(path, *t, 3));
  }

  bool is_table = false;
  for (const Entry& e : entries) is_table = is_table || parse_range(e.key).has_value();
  if (!is_table) {
    throw IoError(path, "no 'Tr:', 'Tr_velo_to_cam:', 'R:'+'T:' or per-sequence table entry");
  }
  if (!sequence) {
    throw IoError(path,
                  "is a per-sequence calibration table; a sequence number is required to "
                  "choose a row");
  }
  for (const Entry& e : entries) {
    const auto range = parse_range(e.key);
    if (range && range->first <= *sequence && *sequence <= range->second) {
      return from_3x4(path, e);
    }
  }
  throw IoError(path, "no row for sequence " + std::to_string(*sequence));
}

int kitti_sequence_number(const std::string& name) {
  std::string s = name;
  while (!s.empty() && (s.back() == '/' || s.back() == '\\')) s.pop_back();
  const std::size_t slash = s.find_last_of("/\\");
  if (slash != std::string::npos) s = s.substr(slash + 1);
  const auto value = parse_unsigned(s);
  if (!value || *value > 1000000) {
    throw std::invalid_argument("'" + name + "' is not a KITTI sequence number");
  }
  return static_cast<int>(*value);
}

Eigen::Isometry3d cam_pose_to_velo(const Eigen::Isometry3d& pose_cam,
                                   const Eigen::Isometry3d& velo_to_cam) {
  return velo_to_cam.inverse() * pose_cam * velo_to_cam;
}

Eigen::Isometry3d velo_pose_to_cam(const Eigen::Isometry3d& pose_velo,
                                   const Eigen::Isometry3d& velo_to_cam) {
  return velo_to_cam * pose_velo * velo_to_cam.inverse();
}

std::vector<Eigen::Isometry3d> cam_to_velo_trajectory(const std::vector<Eigen::Isometry3d>& cam,
                                                      const Eigen::Isometry3d& velo_to_cam) {
  std::vector<Eigen::Isometry3d> out;
  out.reserve(cam.size());
  if (cam.empty()) return out;
  const Eigen::Isometry3d first_inv = cam.front().inverse();
  for (const Eigen::Isometry3d& p : cam)
    out.push_back(cam_pose_to_velo(first_inv * p, velo_to_cam));
  return out;
}

std::vector<Eigen::Isometry3d> velo_to_cam_trajectory(const std::vector<Eigen::Isometry3d>& velo,
                                                      const Eigen::Isometry3d& velo_to_cam) {
  std::vector<Eigen::Isometry3d> out;
  out.reserve(velo.size());
  if (velo.empty()) return out;
  const Eigen::Isometry3d first_inv = velo.front().inverse();
  for (const Eigen::Isometry3d& p : velo) {
    out.push_back(velo_pose_to_cam(first_inv * p, velo_to_cam));
  }
  return out;
}

}  // namespace litamin2::io
