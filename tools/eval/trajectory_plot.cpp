#include "trajectory_plot.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <sstream>
#include <stdexcept>

#ifdef LITAMIN2_EVAL_HAVE_PNG
#include <png.h>
#endif

namespace litamin2::eval_tool {
namespace {

constexpr int kWidth = 800;  // image width in pixels
constexpr int kMargin = 40;  // border around the plotted area
constexpr int kMaxHeight = 1600;
constexpr const char* kAxisNames = "xyz";

struct Frame {
  std::array<int, 2> axes{0, 2};
  double min_u = 0, min_v = 0, scale = 1;  // metres -> pixels
  int width = kWidth, height = kWidth;

  // Pixel coordinates (origin top left, v axis pointing up in the world).
  std::array<double, 2> pixel(const Eigen::Vector3d& p) const {
    return {kMargin + (p(axes[0]) - min_u) * scale,
            height - kMargin - (p(axes[1]) - min_v) * scale};
  }
};

Frame make_frame(const std::vector<Eigen::Isometry3d>& gt,
                 const std::vector<Eigen::Isometry3d>& est) {
  Frame f;
  f.axes = top_view_axes(gt, est);
  double min_u = std::numeric_limits<double>::infinity(), max_u = -min_u;
  double min_v = min_u, max_v = -min_u;
  for (const auto* traj : {&gt, &est}) {
    for (const auto& p : *traj) {
      const Eigen::Vector3d t = p.translation();
      if (!t.allFinite()) continue;
      min_u = std::min(min_u, t(f.axes[0]));
      max_u = std::max(max_u, t(f.axes[0]));
      min_v = std::min(min_v, t(f.axes[1]));
      max_v = std::max(max_v, t(f.axes[1]));
    }
  }
  if (!std::isfinite(min_u)) min_u = max_u = min_v = max_v = 0.0;
  const double span_u = std::max(max_u - min_u, 1e-6);
  const double span_v = std::max(max_v - min_v, 1e-6);
  const int inner = kWidth - 2 * kMargin;
  f.scale = inner / std::max(span_u, span_v * inner / (kMaxHeight - 2 * kMargin));
  f.min_u = min_u - 0.5 * (inner / f.scale - span_u);  // centre horizontally
  f.min_v = min_v;
  f.width = kWidth;
  f.height = std::max(2 * kMargin + 1, static_cast<int>(std::ceil(span_v * f.scale)) + 2 * kMargin);
  return f;
}

std::string extension_of(const std::string& path) {
  const auto dot = path.find_last_of('.');
  if (dot == std::string::npos || path.find('/', dot) != std::string::npos) return "";
  std::string ext = path.substr(dot + 1);
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return std::tolower(c); });
  return ext;
}

void write_svg(const std::string& path, const std::vector<Eigen::Isometry3d>& gt,
               const std::vector<Eigen::Isometry3d>& est) {
  const Frame f = make_frame(gt, est);
  std::ostringstream svg;
  svg.precision(6);
  svg << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
      << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << f.width << "\" height=\""
      << f.height << "\" viewBox=\"0 0 " << f.width << ' ' << f.height << "\">\n"
      << "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
  const auto polyline = [&](const std::vector<Eigen::Isometry3d>& traj, const char* colour) {
    svg << "<polyline fill=\"none\" stroke=\"" << colour
        << "\" stroke-width=\"1.5\" stroke-linejoin=\"round\" points=\"";
    for (const auto& p : traj) {
      if (!p.translation().allFinite()) continue;
      const auto px = f.pixel(p.translation());
      svg << px[0] << ',' << px[1] << ' ';
    }
    svg << "\"/>\n";
  };
  polyline(gt, "black");
  polyline(est, "red");
  if (!gt.empty()) {
    const auto start = f.pixel(gt.front().translation());
    svg << "<circle cx=\"" << start[0] << "\" cy=\"" << start[1]
        << "\" r=\"4\" fill=\"none\" stroke=\"green\" stroke-width=\"1.5\"/>\n";
  }
  // Legend, axis names and a scale bar of a round length.
  const double bar_m = std::pow(10.0, std::floor(std::log10(200.0 / f.scale)));
  svg << "<g font-family=\"sans-serif\" font-size=\"13\">\n"
      << "<line x1=\"10\" y1=\"14\" x2=\"30\" y2=\"14\" stroke=\"black\" stroke-width=\"2\"/>"
      << "<text x=\"35\" y=\"18\">ground truth</text>\n"
      << "<line x1=\"130\" y1=\"14\" x2=\"150\" y2=\"14\" stroke=\"red\" stroke-width=\"2\"/>"
      << "<text x=\"155\" y=\"18\">estimate</text>\n"
      << "<circle cx=\"240\" cy=\"14\" r=\"4\" fill=\"none\" stroke=\"green\"/>"
      << "<text x=\"248\" y=\"18\">start</text>\n"
      << "<text x=\"" << f.width - 200 << "\" y=\"18\">top view: " << kAxisNames[f.axes[0]]
      << " right, " << kAxisNames[f.axes[1]] << " up</text>\n"
      << "<line x1=\"" << kMargin << "\" y1=\"" << f.height - 12 << "\" x2=\""
      << kMargin + bar_m * f.scale << "\" y2=\"" << f.height - 12
      << "\" stroke=\"black\" stroke-width=\"2\"/>"
      << "<text x=\"" << kMargin + bar_m * f.scale + 6 << "\" y=\"" << f.height - 8 << "\">"
      << bar_m << " m</text>\n"
      << "</g>\n</svg>\n";
  std::ofstream out(path, std::ios::binary);
  out << svg.str();
  if (!out.good()) throw std::runtime_error(path + ": cannot write SVG file");
}

#ifdef LITAMIN2_EVAL_HAVE_PNG
struct Image {
  int width, height;
  std::vector<unsigned char> rgb;
  Image(int w, int h) : width(w), height(h), rgb(static_cast<std::size_t>(w) * h * 3, 255) {}

  void dot(int x, int y, const std::array<unsigned char, 3>& c, int radius) {
    for (int dy = -radius; dy <= radius; ++dy) {
      for (int dx = -radius; dx <= radius; ++dx) {
        const int px = x + dx, py = y + dy;
        if (px < 0 || py < 0 || px >= width || py >= height) continue;
        std::copy(c.begin(), c.end(),
                  rgb.begin() + (static_cast<std::size_t>(py) * width + px) * 3);
      }
    }
  }

  // Bresenham line with a square pen of the given radius.
  void line(double x0d, double y0d, double x1d, double y1d, const std::array<unsigned char, 3>& c,
            int radius) {
    int x0 = static_cast<int>(std::lround(x0d)), y0 = static_cast<int>(std::lround(y0d));
    const int x1 = static_cast<int>(std::lround(x1d)), y1 = static_cast<int>(std::lround(y1d));
    const int dx = std::abs(x1 - x0), sx = x0 < x1 ? 1 : -1;
    const int dy = -std::abs(y1 - y0), sy = y0 < y1 ? 1 : -1;
    int err = dx + dy;
    while (true) {
      dot(x0, y0, c, radius);
      if (x0 == x1 && y0 == y1) break;
      const int e2 = 2 * err;
      if (e2 >= dy) {
        err += dy;
        x0 += sx;
      }
      if (e2 <= dx) {
        err += dx;
        y0 += sy;
      }
    }
  }
};

void write_png(const std::string& path, const std::vector<Eigen::Isometry3d>& gt,
               const std::vector<Eigen::Isometry3d>& est) {
  const Frame f = make_frame(gt, est);
  Image img(f.width, f.height);
  const auto draw = [&](const std::vector<Eigen::Isometry3d>& traj,
                        const std::array<unsigned char, 3>& c) {
    for (std::size_t i = 1; i < traj.size(); ++i) {
      if (!traj[i - 1].translation().allFinite() || !traj[i].translation().allFinite()) continue;
      const auto a = f.pixel(traj[i - 1].translation());
      const auto b = f.pixel(traj[i].translation());
      img.line(a[0], a[1], b[0], b[1], c, 1);
    }
  };
  draw(gt, {0, 0, 0});
  draw(est, {220, 0, 0});
  if (!gt.empty()) {
    const auto s = f.pixel(gt.front().translation());
    img.dot(static_cast<int>(std::lround(s[0])), static_cast<int>(std::lround(s[1])), {0, 160, 0},
            4);
  }
  // Legend without text: black bar = ground truth, red bar = estimate (top left).
  img.line(10, 10, 40, 10, {0, 0, 0}, 1);
  img.line(10, 20, 40, 20, {220, 0, 0}, 1);
  // Scale bar of a round length (10^k m) at the bottom left.
  const double bar_m = std::pow(10.0, std::floor(std::log10(200.0 / f.scale)));
  img.line(kMargin, f.height - 12, kMargin + bar_m * f.scale, f.height - 12, {0, 0, 0}, 1);

  FILE* fp = std::fopen(path.c_str(), "wb");
  if (!fp) throw std::runtime_error(path + ": cannot open PNG file for writing");
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  png_infop info = png ? png_create_info_struct(png) : nullptr;
  if (!png || !info || setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, &info);
    std::fclose(fp);
    throw std::runtime_error(path + ": libpng failed to write the image");
  }
  png_init_io(png, fp);
  png_set_IHDR(png, info, static_cast<png_uint_32>(img.width), static_cast<png_uint_32>(img.height),
               8, PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT,
               PNG_FILTER_TYPE_DEFAULT);
  png_write_info(png, info);
  for (int y = 0; y < img.height; ++y) {
    png_write_row(png, img.rgb.data() + static_cast<std::size_t>(y) * img.width * 3);
  }
  png_write_end(png, nullptr);
  png_destroy_write_struct(&png, &info);
  if (std::fclose(fp) != 0) throw std::runtime_error(path + ": cannot write PNG file");
}
#endif

}  // namespace

std::array<int, 2> top_view_axes(const std::vector<Eigen::Isometry3d>& gt,
                                 const std::vector<Eigen::Isometry3d>& est) {
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector3d hi = -lo;
  for (const auto* traj : {&gt, &est}) {
    for (const auto& p : *traj) {
      if (!p.translation().allFinite()) continue;
      lo = lo.cwiseMin(p.translation());
      hi = hi.cwiseMax(p.translation());
    }
  }
  if (!lo.allFinite()) return {0, 2};  // nothing to plot: KITTI default
  const Eigen::Vector3d extent = hi - lo;
  // Drop the axis with the smallest extent (ties: prefer dropping y, the KITTI camera's
  // vertical axis, then z, then x).
  int drop = 1;
  for (const int a : {2, 0}) {
    if (extent(a) < extent(drop)) drop = a;
  }
  std::array<int, 2> axes{};
  int k = 0;
  for (int a = 0; a < 3; ++a) {
    if (a != drop) axes[k++] = a;
  }
  return axes;
}

std::string plot_format(const std::string& path) {
  const std::string ext = extension_of(path);
#ifdef LITAMIN2_EVAL_HAVE_PNG
  if (ext == "png") return ext;
#endif
  return ext == "svg" ? ext : "";
}

void write_trajectory_plot(const std::string& path, const std::vector<Eigen::Isometry3d>& gt,
                           const std::vector<Eigen::Isometry3d>& est) {
  const std::string ext = extension_of(path);
  if (ext == "svg") return write_svg(path, gt, est);
  if (ext == "png") {
#ifdef LITAMIN2_EVAL_HAVE_PNG
    return write_png(path, gt, est);
#else
    throw std::runtime_error(path + ": PNG output not available (built without libpng); use .svg");
#endif
  }
  throw std::runtime_error(path + ": unknown plot format (use a .svg or .png file name)");
}

}  // namespace litamin2::eval_tool
