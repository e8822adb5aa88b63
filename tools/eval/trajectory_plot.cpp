#include "trajectory_plot.hpp"

#include <cairo-pdf.h>
#include <cairo-svg.h>
#include <cairo.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <stdexcept>

namespace litamin2::eval_tool {
namespace {

constexpr double kWidth = 900;       // page width (pixels for PNG, points for SVG/PDF)
constexpr double kTitleHeight = 56;  // title and subtitle
constexpr double kMargin = 64;       // left/bottom room for tick labels
constexpr double kRightRoom = 96;    // colour bar and its labels
constexpr double kMaxViewHeight = 900;
constexpr double kErrorPanelHeight = 210;
constexpr double kFontSize = 12;
constexpr const char* kAxisNames = "xyz";

struct Box {
  double x = 0, y = 0, w = 0, h = 0;  // top left and size, page units
};

/// A linear map of one world axis onto one page axis.
struct AxisMap {
  double world_min = 0, world_max = 1, page_min = 0, page_max = 1;
  double operator()(double v) const {
    return page_min + (v - world_min) / (world_max - world_min) * (page_max - page_min);
  }
};

std::string extension_of(const std::string& path) {
  const auto dot = path.find_last_of('.');
  if (dot == std::string::npos) return {};
  std::string ext = path.substr(dot + 1);
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext;
}

/// Colour of a value in [0, 1]: dark blue, blue, green, yellow, red (a perceptually ordered
/// ramp that stays readable on white).
std::array<double, 3> ramp(double t) {
  static const std::array<std::array<double, 3>, 5> stops = {{{0.15, 0.10, 0.55},
                                                              {0.10, 0.45, 0.85},
                                                              {0.15, 0.70, 0.35},
                                                              {0.95, 0.75, 0.10},
                                                              {0.85, 0.10, 0.10}}};
  t = std::clamp(std::isfinite(t) ? t : 1.0, 0.0, 1.0) * (stops.size() - 1);
  const std::size_t i = std::min<std::size_t>(static_cast<std::size_t>(t), stops.size() - 2);
  const double f = t - static_cast<double>(i);
  return {stops[i][0] + f * (stops[i + 1][0] - stops[i][0]),
          stops[i][1] + f * (stops[i + 1][1] - stops[i][1]),
          stops[i][2] + f * (stops[i + 1][2] - stops[i][2])};
}

std::string number(double v, double step) {
  char text[32];
  const int decimals = step >= 1.0 ? 0 : static_cast<int>(std::ceil(-std::log10(step) - 1e-9));
  std::snprintf(text, sizeof text, "%.*f", decimals, std::abs(v) < step * 1e-6 ? 0.0 : v);
  return text;
}

void text_at(cairo_t* cr, double x, double y, const std::string& s, double align_x = 0.0,
             double align_y = 0.0) {
  cairo_text_extents_t e;
  cairo_text_extents(cr, s.c_str(), &e);
  cairo_move_to(cr, x - align_x * e.width - e.x_bearing, y - align_y * e.height - e.y_bearing);
  cairo_show_text(cr, s.c_str());
}

/// Frame, ticks with labels and grid lines of a panel.
void draw_axes(cairo_t* cr, const Box& box, const AxisMap& mx, const AxisMap& my,
               const std::string& x_label, const std::string& y_label) {
  cairo_set_font_size(cr, kFontSize);
  for (int axis = 0; axis < 2; ++axis) {
    const AxisMap& m = axis == 0 ? mx : my;
    const double step = tick_step(m.world_max - m.world_min, 8);
    for (double v = std::ceil(m.world_min / step) * step; v <= m.world_max + step * 1e-9;
         v += step) {
      const double p = m(v);
      cairo_set_source_rgb(cr, 0.88, 0.88, 0.88);
      cairo_set_line_width(cr, 0.8);
      if (axis == 0) {
        cairo_move_to(cr, p, box.y);
        cairo_line_to(cr, p, box.y + box.h);
      } else {
        cairo_move_to(cr, box.x, p);
        cairo_line_to(cr, box.x + box.w, p);
      }
      cairo_stroke(cr);
      cairo_set_source_rgb(cr, 0.2, 0.2, 0.2);
      if (axis == 0) {
        text_at(cr, p, box.y + box.h + 6, number(v, step), 0.5, 0.0);
      } else {
        text_at(cr, box.x - 6, p, number(v, step), 1.0, 0.5);
      }
    }
  }
  cairo_set_source_rgb(cr, 0.0, 0.0, 0.0);
  cairo_set_line_width(cr, 1.0);
  cairo_rectangle(cr, box.x, box.y, box.w, box.h);
  cairo_stroke(cr);
  text_at(cr, box.x + box.w / 2, box.y + box.h + 26, x_label, 0.5, 0.0);
  cairo_save(cr);
  cairo_translate(cr, box.x - 48, box.y + box.h / 2);
  cairo_rotate(cr, -M_PI / 2);
  text_at(cr, 0, 0, y_label, 0.5, 0.5);
  cairo_restore(cr);
}

struct Layout {
  double height = 0;
  Box view, errors, colour_bar;
  AxisMap view_x, view_y;
};

Layout layout(const TrajectoryPlot& plot, const std::array<int, 2>& axes) {
  double lo_u = std::numeric_limits<double>::infinity(), hi_u = -lo_u, lo_v = lo_u, hi_v = -lo_u;
  for (const auto* traj : {&plot.ground_truth, &plot.aligned_estimate}) {
    for (const auto& p : *traj) {
      const Eigen::Vector3d t = p.translation();
      if (!t.allFinite()) continue;
      lo_u = std::min(lo_u, t(axes[0]));
      hi_u = std::max(hi_u, t(axes[0]));
      lo_v = std::min(lo_v, t(axes[1]));
      hi_v = std::max(hi_v, t(axes[1]));
    }
  }
  if (!std::isfinite(lo_u)) lo_u = hi_u = lo_v = hi_v = 0.0;
  // 5 % room around the paths, at least 1 m in each direction.
  const double pad = std::max(1.0, 0.05 * std::max(hi_u - lo_u, hi_v - lo_v));
  lo_u -= pad, hi_u += pad, lo_v -= pad, hi_v += pad;

  Layout l;
  const double view_w = kWidth - kMargin - kRightRoom;
  double scale = view_w / (hi_u - lo_u);  // equal scale on both axes
  double view_h = (hi_v - lo_v) * scale;
  if (view_h > kMaxViewHeight) {  // tall path: the height limits the scale, centre horizontally
    scale = kMaxViewHeight / (hi_v - lo_v);
    view_h = kMaxViewHeight;
    const double half = 0.5 * view_w / scale, mid = 0.5 * (lo_u + hi_u);
    lo_u = mid - half, hi_u = mid + half;
  }
  view_h = std::max(view_h, 120.0);
  const double mid_v = 0.5 * (lo_v + hi_v), half_v = 0.5 * view_h / scale;
  l.view = {kMargin, kTitleHeight, view_w, view_h};
  l.view_x = {lo_u, hi_u, l.view.x, l.view.x + l.view.w};
  l.view_y = {mid_v - half_v, mid_v + half_v, l.view.y + l.view.h, l.view.y};  // v upwards
  l.colour_bar = {l.view.x + l.view.w + 24, l.view.y, 16, std::min(l.view.h, 300.0)};
  l.errors = {kMargin, l.view.y + l.view.h + 64, view_w, kErrorPanelHeight - 64};
  l.height = l.errors.y + l.errors.h + 56;
  return l;
}

void stroke_path(cairo_t* cr, const std::vector<Eigen::Isometry3d>& poses,
                 const std::array<int, 2>& axes, const Layout& l) {
  bool pen_down = false;
  for (const auto& p : poses) {
    const Eigen::Vector3d t = p.translation();
    if (!t.allFinite()) {
      pen_down = false;
      continue;
    }
    const double x = l.view_x(t(axes[0])), y = l.view_y(t(axes[1]));
    if (pen_down) {
      cairo_line_to(cr, x, y);
    } else {
      cairo_move_to(cr, x, y);
      pen_down = true;
    }
  }
  cairo_stroke(cr);
}

void draw(cairo_t* cr, const TrajectoryPlot& plot, const std::array<int, 2>& axes,
          const Layout& l) {
  const auto& gt = plot.ground_truth;
  const auto& est = plot.aligned_estimate;
  std::vector<double> error(gt.size());
  double max_error = 0.0;
  for (std::size_t i = 0; i < gt.size(); ++i) {
    error[i] = (gt[i].translation() - est[i].translation()).norm();
    if (std::isfinite(error[i])) max_error = std::max(max_error, error[i]);
  }
  const double error_scale = max_error > 0.0 ? max_error : 1.0;

  cairo_set_source_rgb(cr, 1, 1, 1);
  cairo_paint(cr);
  cairo_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_BOLD);
  cairo_set_font_size(cr, 15);
  cairo_set_source_rgb(cr, 0, 0, 0);
  text_at(cr, kMargin, 12, plot.title);
  cairo_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
  cairo_set_font_size(cr, kFontSize);
  text_at(cr, kMargin, 33, plot.subtitle);

  // Top view.
  draw_axes(cr, l.view, l.view_x, l.view_y, std::string(1, kAxisNames[axes[0]]) + " [m]",
            std::string(1, kAxisNames[axes[1]]) + " [m]");
  cairo_save(cr);
  cairo_rectangle(cr, l.view.x, l.view.y, l.view.w, l.view.h);
  cairo_clip(cr);
  cairo_set_line_join(cr, CAIRO_LINE_JOIN_ROUND);
  cairo_set_line_cap(cr, CAIRO_LINE_CAP_ROUND);
  cairo_set_source_rgb(cr, 0.1, 0.1, 0.1);
  cairo_set_line_width(cr, 1.5);
  cairo_set_dash(cr, std::array<double, 2>{6.0, 3.0}.data(), 2, 0);
  stroke_path(cr, gt, axes, l);
  cairo_set_dash(cr, nullptr, 0, 0);
  cairo_set_line_width(cr, 2.5);
  for (std::size_t i = 1; i < est.size(); ++i) {  // each step coloured by its error
    const Eigen::Vector3d a = est[i - 1].translation(), b = est[i].translation();
    if (!a.allFinite() || !b.allFinite()) continue;
    const auto c = ramp(0.5 * (error[i - 1] + error[i]) / error_scale);
    cairo_set_source_rgb(cr, c[0], c[1], c[2]);
    cairo_move_to(cr, l.view_x(a(axes[0])), l.view_y(a(axes[1])));
    cairo_line_to(cr, l.view_x(b(axes[0])), l.view_y(b(axes[1])));
    cairo_stroke(cr);
  }
  if (!gt.empty() && gt.front().translation().allFinite()) {
    const Eigen::Vector3d s = gt.front().translation();
    cairo_set_source_rgb(cr, 0.0, 0.6, 0.0);
    cairo_arc(cr, l.view_x(s(axes[0])), l.view_y(s(axes[1])), 5.0, 0, 2 * M_PI);
    cairo_fill(cr);
  }
  cairo_restore(cr);

  // Legend, top left inside the view.
  const double lx = l.view.x + 10, ly = l.view.y + 10;
  cairo_set_source_rgba(cr, 1, 1, 1, 0.85);
  cairo_rectangle(cr, lx, ly, 250, 62);
  cairo_fill(cr);
  cairo_set_line_width(cr, 1.5);
  cairo_set_source_rgb(cr, 0.1, 0.1, 0.1);
  cairo_set_dash(cr, std::array<double, 2>{6.0, 3.0}.data(), 2, 0);
  cairo_move_to(cr, lx + 8, ly + 12);
  cairo_line_to(cr, lx + 38, ly + 12);
  cairo_stroke(cr);
  cairo_set_dash(cr, nullptr, 0, 0);
  text_at(cr, lx + 46, ly + 12, "ground truth", 0.0, 0.5);
  cairo_set_line_width(cr, 2.5);
  for (int k = 0; k < 6; ++k) {
    const auto c = ramp(k / 5.0);
    cairo_set_source_rgb(cr, c[0], c[1], c[2]);
    cairo_move_to(cr, lx + 8 + 5 * k, ly + 31);
    cairo_line_to(cr, lx + 13 + 5 * k, ly + 31);
    cairo_stroke(cr);
  }
  cairo_set_source_rgb(cr, 0.1, 0.1, 0.1);
  text_at(cr, lx + 46, ly + 31, "estimate (aligned), colour = error", 0.0, 0.5);
  cairo_set_source_rgb(cr, 0.0, 0.6, 0.0);
  cairo_arc(cr, lx + 23, ly + 50, 4.0, 0, 2 * M_PI);
  cairo_fill(cr);
  cairo_set_source_rgb(cr, 0.1, 0.1, 0.1);
  text_at(cr, lx + 46, ly + 50, "start", 0.0, 0.5);

  // Colour bar of the position error.
  const Box& bar = l.colour_bar;
  for (int k = 0; k < 100; ++k) {
    const auto c = ramp(1.0 - k / 99.0);
    cairo_set_source_rgb(cr, c[0], c[1], c[2]);
    cairo_rectangle(cr, bar.x, bar.y + bar.h * k / 100.0, bar.w, bar.h / 100.0 + 0.5);
    cairo_fill(cr);
  }
  cairo_set_source_rgb(cr, 0, 0, 0);
  cairo_set_line_width(cr, 1.0);
  cairo_rectangle(cr, bar.x, bar.y, bar.w, bar.h);
  cairo_stroke(cr);
  const double bar_step = tick_step(error_scale, 5);
  for (double v = 0.0; v <= error_scale + bar_step * 1e-9; v += bar_step) {
    text_at(cr, bar.x + bar.w + 4, bar.y + bar.h * (1.0 - v / error_scale), number(v, bar_step),
            0.0, 0.5);
  }
  text_at(cr, bar.x, bar.y + bar.h + 8, "error [m]");

  // Position error over time (or pose index).
  const bool by_time = plot.times.size() == gt.size() && !gt.empty();
  const double t0 = by_time ? plot.times.front() : 0.0;
  const double t1 = by_time ? plot.times.back() : static_cast<double>(gt.size() - 1);
  const AxisMap ex{t0, t1 > t0 ? t1 : t0 + 1.0, l.errors.x, l.errors.x + l.errors.w};
  const AxisMap ey{0.0, error_scale * 1.1, l.errors.y + l.errors.h, l.errors.y};
  draw_axes(cr, l.errors, ex, ey, by_time ? "time [s]" : "pose", "error [m]");
  cairo_set_source_rgb(cr, 0.1, 0.35, 0.75);
  cairo_set_line_width(cr, 1.5);
  bool pen_down = false;
  for (std::size_t i = 0; i < gt.size(); ++i) {
    if (!std::isfinite(error[i])) {
      pen_down = false;
      continue;
    }
    const double x = ex(by_time ? plot.times[i] : static_cast<double>(i)), y = ey(error[i]);
    if (pen_down) {
      cairo_line_to(cr, x, y);
    } else {
      cairo_move_to(cr, x, y);
      pen_down = true;
    }
  }
  cairo_stroke(cr);
}

struct SurfaceDeleter {
  void operator()(cairo_surface_t* s) const { cairo_surface_destroy(s); }
};
struct ContextDeleter {
  void operator()(cairo_t* c) const { cairo_destroy(c); }
};

}  // namespace

double tick_step(double span, int max_ticks) {
  if (!std::isfinite(span) || span <= 0.0 || max_ticks < 1) return 1.0;
  const double raw = span / max_ticks;
  const double power = std::pow(10.0, std::floor(std::log10(raw)));
  for (const double m : {1.0, 2.0, 5.0, 10.0}) {
    if (m * power >= raw * (1.0 - 1e-12)) return m * power;
  }
  return 10.0 * power;
}

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
  return ext == "png" || ext == "svg" || ext == "pdf" ? ext : "";
}

void write_trajectory_plot(const std::string& path, const TrajectoryPlot& plot) {
  const std::string format = plot_format(path);
  if (format.empty())
    throw std::runtime_error(path + ": unknown plot format (use a .png, .svg or .pdf file name)");
  if (plot.ground_truth.size() != plot.aligned_estimate.size())
    throw std::runtime_error(path + ": ground truth and estimate differ in length");
  if (!plot.times.empty() && plot.times.size() != plot.ground_truth.size())
    throw std::runtime_error(path + ": times and poses differ in length");
  const auto axes = top_view_axes(plot.ground_truth, plot.aligned_estimate);
  const Layout l = layout(plot, axes);

  std::unique_ptr<cairo_surface_t, SurfaceDeleter> surface;
  if (format == "png") {
    surface.reset(cairo_image_surface_create(CAIRO_FORMAT_RGB24, static_cast<int>(kWidth),
                                             static_cast<int>(std::ceil(l.height))));
  } else if (format == "svg") {
    surface.reset(cairo_svg_surface_create(path.c_str(), kWidth, l.height));
  } else {
    surface.reset(cairo_pdf_surface_create(path.c_str(), kWidth, l.height));
  }
  if (cairo_surface_status(surface.get()) != CAIRO_STATUS_SUCCESS)
    throw std::runtime_error(path + ": cannot create the " + format + " file: " +
                             cairo_status_to_string(cairo_surface_status(surface.get())));
  {
    std::unique_ptr<cairo_t, ContextDeleter> cr(cairo_create(surface.get()));
    draw(cr.get(), plot, axes, l);
    if (cairo_status(cr.get()) != CAIRO_STATUS_SUCCESS)
      throw std::runtime_error(
          path + ": drawing failed: " + cairo_status_to_string(cairo_status(cr.get())));
  }
  cairo_status_t status = CAIRO_STATUS_SUCCESS;
  if (format == "png") {
    status = cairo_surface_write_to_png(surface.get(), path.c_str());
  } else {
    cairo_surface_finish(surface.get());
    status = cairo_surface_status(surface.get());
  }
  if (status != CAIRO_STATUS_SUCCESS)
    throw std::runtime_error(path + ": cannot write the " + format +
                             " file: " + cairo_status_to_string(status));
}

}  // namespace litamin2::eval_tool
