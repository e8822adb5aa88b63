#include "litamin2/service/prometheus_text.hpp"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>

namespace litamin2::service {

namespace {

bool valid_name(const std::string& name, bool allow_colon) {
  if (name.empty()) return false;
  for (std::size_t i = 0; i < name.size(); ++i) {
    const char c = name[i];
    const bool letter =
        (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '_' || (allow_colon && c == ':');
    const bool digit = c >= '0' && c <= '9';
    if (!letter && !(digit && i > 0)) return false;
  }
  return true;
}

std::string escape_label_value(const std::string& value) {
  std::string out;
  out.reserve(value.size());
  for (char c : value) {
    if (c == '\\')
      out += "\\\\";
    else if (c == '"')
      out += "\\\"";
    else if (c == '\n')
      out += "\\n";
    else
      out += c;
  }
  return out;
}

std::string escape_help(const std::string& help) {
  std::string out;
  for (char c : help) {
    if (c == '\\')
      out += "\\\\";
    else if (c == '\n')
      out += "\\n";
    else
      out += c;
  }
  return out;
}

const char* type_name(PrometheusText::Type type) {
  switch (type) {
    case PrometheusText::Type::kCounter:
      return "counter";
    case PrometheusText::Type::kGauge:
      return "gauge";
    case PrometheusText::Type::kHistogram:
      return "histogram";
  }
  return "untyped";
}

}  // namespace

std::string prometheus_number(double value) {
  if (std::isnan(value)) return "NaN";
  if (std::isinf(value)) return value > 0 ? "+Inf" : "-Inf";
  char buf[64];
  if (value == std::floor(value) && std::fabs(value) < 1e15)
    std::snprintf(buf, sizeof buf, "%.0f", value);
  else {
    // The shortest of 15 or 17 significant digits that reads back as the same double.
    std::snprintf(buf, sizeof buf, "%.15g", value);
    if (std::strtod(buf, nullptr) != value) std::snprintf(buf, sizeof buf, "%.17g", value);
  }
  return buf;
}

void PrometheusText::family(const std::string& name, Type type, const std::string& help) {
  if (!valid_name(name, true)) throw std::invalid_argument("invalid metric name '" + name + "'");
  if (type == Type::kCounter &&
      (name.size() < 6 || name.compare(name.size() - 6, 6, "_total") != 0))
    throw std::invalid_argument("counter '" + name + "' does not end in _total");
  if (!names_.insert(name).second)
    throw std::invalid_argument("metric family '" + name + "' written twice");
  current_ = name;
  type_ = type;
  text_ += "# HELP " + name + " " + escape_help(help) + "\n";
  text_ += "# TYPE " + name + " " + type_name(type) + "\n";
}

void PrometheusText::line(const std::string& suffix, const Labels& labels,
                          const std::string& value) {
  text_ += current_ + suffix;
  if (!labels.empty()) {
    text_ += '{';
    for (std::size_t i = 0; i < labels.size(); ++i) {
      if (!valid_name(labels[i].first, false))
        throw std::invalid_argument("invalid label name '" + labels[i].first + "'");
      if (i > 0) text_ += ',';
      text_ += labels[i].first + "=\"" + escape_label_value(labels[i].second) + "\"";
    }
    text_ += '}';
  }
  text_ += ' ' + value + '\n';
}

void PrometheusText::sample(const Labels& labels, double value) {
  if (current_.empty() || type_ == Type::kHistogram)
    throw std::invalid_argument("sample() needs a counter or gauge family");
  line("", labels, prometheus_number(value));
}

void PrometheusText::histogram(const Labels& labels, const Histogram& h) {
  if (current_.empty() || type_ != Type::kHistogram)
    throw std::invalid_argument("histogram() needs a histogram family");
  const std::vector<std::uint64_t> counts = h.cumulative_counts();
  for (std::size_t i = 0; i < counts.size(); ++i) {
    Labels with_le = labels;
    with_le.emplace_back("le", prometheus_number(h.upper_bounds()[i]));
    line("_bucket", with_le, prometheus_number(static_cast<double>(counts[i])));
  }
  Labels inf = labels;
  inf.emplace_back("le", "+Inf");
  line("_bucket", inf, prometheus_number(static_cast<double>(h.count())));
  line("_sum", labels, prometheus_number(h.sum()));
  line("_count", labels, prometheus_number(static_cast<double>(h.count())));
}

}  // namespace litamin2::service
