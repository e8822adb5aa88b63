// ROS_DOMAIN_ID as ROS 2 reads it: unset or empty is "no value", anything but 0..232 an error.

#include "litamin2/service/transport_config.hpp"

#include <gtest/gtest.h>

using namespace litamin2::service;

TEST(RosDomainId, ValidValues) {
  std::string error;
  EXPECT_EQ(parse_ros_domain_id("0", &error), 0);
  EXPECT_EQ(parse_ros_domain_id("42", &error), 42);
  EXPECT_EQ(parse_ros_domain_id("232", &error), 232);
  EXPECT_EQ(parse_ros_domain_id("007", &error), 7);
  EXPECT_TRUE(error.empty());
}

TEST(RosDomainId, UnsetOrEmptyIsNoValueAndNoError) {
  std::string error;
  EXPECT_FALSE(parse_ros_domain_id(nullptr, &error));
  EXPECT_FALSE(parse_ros_domain_id("", &error));
  EXPECT_TRUE(error.empty());
}

TEST(RosDomainId, InvalidValuesAreErrors) {
  for (const char* bad :
       {"233", "1000", "-1", "+1", " 1", "1 ", "1.0", "abc", "0x1", "4294967297"}) {
    std::string error;
    EXPECT_FALSE(parse_ros_domain_id(bad, &error)) << bad;
    EXPECT_EQ(error, std::string("ROS_DOMAIN_ID: '") + bad +
                         "' is not a DDS domain id (a whole number in 0..232)")
        << bad;
  }
  EXPECT_STREQ(to_string(DomainSource::kEnvironment), "ROS_DOMAIN_ID");
}
