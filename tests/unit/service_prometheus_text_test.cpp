#include "litamin2/service/prometheus_text.hpp"

#include <gtest/gtest.h>

#include <limits>
#include <stdexcept>

namespace litamin2::service {
namespace {

using Type = PrometheusText::Type;

TEST(ServicePrometheusText, FamilyHasHelpTypeAndLabelledSamples) {
  PrometheusText out;
  out.family("x_frames_total", Type::kCounter, "frames");
  out.sample({{"stream", "car1"}}, 42);
  out.sample({{"stream", "car2"}, {"reason", "bad_row_step"}}, 3);
  out.family("x_depth", Type::kGauge, "queue depth");
  out.sample({}, 2.5);
  EXPECT_EQ(out.text(),
            "# HELP x_frames_total frames\n"
            "# TYPE x_frames_total counter\n"
            "x_frames_total{stream=\"car1\"} 42\n"
            "x_frames_total{stream=\"car2\",reason=\"bad_row_step\"} 3\n"
            "# HELP x_depth queue depth\n"
            "# TYPE x_depth gauge\n"
            "x_depth 2.5\n");
}

TEST(ServicePrometheusText, HistogramBucketsEndWithInfEqualToCount) {
  Histogram h({0.01, 0.1});
  h.observe(0.005);
  h.observe(0.05);
  h.observe(3.0);
  PrometheusText out;
  out.family("x_latency_seconds", Type::kHistogram, "latency");
  out.histogram({{"stream", "a"}}, h);
  const std::string sum = prometheus_number(0.005 + 0.05 + 3.0);
  EXPECT_EQ(out.text(),
            "# HELP x_latency_seconds latency\n"
            "# TYPE x_latency_seconds histogram\n"
            "x_latency_seconds_bucket{stream=\"a\",le=\"0.01\"} 1\n"
            "x_latency_seconds_bucket{stream=\"a\",le=\"0.1\"} 2\n"
            "x_latency_seconds_bucket{stream=\"a\",le=\"+Inf\"} 3\n"
            "x_latency_seconds_sum{stream=\"a\"} " +
                sum +
                "\n"
                "x_latency_seconds_count{stream=\"a\"} 3\n");
}

TEST(ServicePrometheusText, EscapesLabelValuesAndHelp) {
  PrometheusText out;
  out.family("x", Type::kGauge, "a \\ b\nc");
  out.sample({{"id", "q\"\\\n"}}, 1);
  EXPECT_EQ(out.text(),
            "# HELP x a \\\\ b\\nc\n"
            "# TYPE x gauge\n"
            "x{id=\"q\\\"\\\\\\n\"} 1\n");
}

TEST(ServicePrometheusText, RefusesWhatTheFormatForbids) {
  PrometheusText out;
  EXPECT_THROW(out.family("frames", Type::kCounter, ""), std::invalid_argument);  // no _total
  EXPECT_THROW(out.family("1x", Type::kGauge, ""), std::invalid_argument);
  EXPECT_THROW(out.family("a-b", Type::kGauge, ""), std::invalid_argument);
  EXPECT_THROW(out.sample({}, 1), std::invalid_argument);  // no family yet
  out.family("g", Type::kGauge, "");
  EXPECT_THROW(out.family("g", Type::kGauge, ""), std::invalid_argument);  // twice
  EXPECT_THROW(out.sample({{"bad-label", "v"}}, 1), std::invalid_argument);
  EXPECT_THROW(out.histogram({}, Histogram({1.0})), std::invalid_argument);  // a gauge
  out.family("h", Type::kHistogram, "");
  EXPECT_THROW(out.sample({}, 1), std::invalid_argument);
}

TEST(ServicePrometheusText, NumbersAsTheFormatWritesThem) {
  EXPECT_EQ(prometheus_number(0), "0");
  EXPECT_EQ(prometheus_number(123456789), "123456789");
  EXPECT_EQ(prometheus_number(0.0025), "0.0025");
  EXPECT_EQ(prometheus_number(0.1 + 0.2), "0.30000000000000004");
  EXPECT_EQ(prometheus_number(std::numeric_limits<double>::infinity()), "+Inf");
  EXPECT_EQ(prometheus_number(-std::numeric_limits<double>::infinity()), "-Inf");
  EXPECT_EQ(prometheus_number(std::numeric_limits<double>::quiet_NaN()), "NaN");
}

}  // namespace
}  // namespace litamin2::service
