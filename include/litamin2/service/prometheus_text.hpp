#pragma once
/// Writes the Prometheus text exposition format 0.0.4: per metric family one `# HELP` and one
/// `# TYPE` line, then its samples `name{label="value",...} number`. Counter names must end in
/// `_total`; a histogram writes `_bucket{le=...}` (cumulative, ending with le="+Inf" equal to
/// `_count`), `_sum` and `_count`. Names and label names are checked ([a-zA-Z_:][a-zA-Z0-9_:]*,
/// std::invalid_argument otherwise), label values escaped (\\, \", \n).

#include "litamin2/service/histogram.hpp"

#include <cstdint>
#include <set>
#include <string>
#include <utility>
#include <vector>

namespace litamin2::service {

/// The Content-Type of the format.
inline constexpr const char* kPrometheusContentType = "text/plain; version=0.0.4; charset=utf-8";

class PrometheusText {
 public:
  using Labels = std::vector<std::pair<std::string, std::string>>;
  enum class Type { kCounter, kGauge, kHistogram };

  /// Starts a family (each name once: std::invalid_argument on a repeat or a counter name
  /// without _total). Samples written after it belong to it.
  void family(const std::string& name, Type type, const std::string& help);
  /// A counter or gauge sample of the current family.
  void sample(const Labels& labels, double value);
  /// The current family's histogram for `labels` (the family must be a histogram).
  void histogram(const Labels& labels, const Histogram& h);

  const std::string& text() const { return text_; }

 private:
  void line(const std::string& suffix, const Labels& labels, const std::string& value);

  std::string text_;
  std::string current_;
  Type type_ = Type::kGauge;
  std::set<std::string> names_;
};

/// A sample value as the format writes it: integers without a fraction, NaN, +Inf, -Inf.
std::string prometheus_number(double value);

}  // namespace litamin2::service
