#include "litamin2/service/metrics_config.hpp"

#include <gtest/gtest.h>

namespace litamin2::service {
namespace {

TEST(ServiceMetricsConfig, ParsesHostAndPort) {
  std::string why;
  auto a = parse_listen_address("127.0.0.1:9464", &why);
  ASSERT_TRUE(a) << why;
  EXPECT_EQ(a->host, "127.0.0.1");
  EXPECT_EQ(a->port, 9464);
  a = parse_listen_address("[::1]:1", &why);
  ASSERT_TRUE(a) << why;
  EXPECT_EQ(a->host, "::1");
  EXPECT_EQ(a->port, 1);
  a = parse_listen_address("metrics-host.local:65535", &why);
  ASSERT_TRUE(a) << why;
  EXPECT_EQ(a->port, 65535);
}

TEST(ServiceMetricsConfig, RejectsWhatIsNotHostPort) {
  for (const char* bad :
       {"9464", "127.0.0.1", "127.0.0.1:", ":9464", "127.0.0.1:0", "127.0.0.1:65536",
        "127.0.0.1:99999999", "127.0.0.1:94a4", "127.0.0.1:-1", "host name:80", "[::1]9464",
        "[]:80", "[zz]:80", "http://127.0.0.1:9464"}) {
    std::string why;
    EXPECT_FALSE(parse_listen_address(bad, &why)) << bad;
    EXPECT_FALSE(why.empty()) << bad;
  }
}

TEST(ServiceMetricsConfig, EmptyIsOffAndValid) {
  MetricsConfig config;
  EXPECT_FALSE(config.enabled());
  EXPECT_FALSE(metrics_config_error(config));
  config.listen = "127.0.0.1:70000";
  ASSERT_TRUE(metrics_config_error(config));
  EXPECT_NE(metrics_config_error(config)->find("metrics.listen"), std::string::npos);
}

}  // namespace
}  // namespace litamin2::service
