/// Topic names and stream ids.

#include <gtest/gtest.h>

#include "litamin2/service/topic_names.hpp"

namespace litamin2::service {
namespace {

TEST(TopicNames, Topics) {
  EXPECT_EQ(points_topic("car1"), "rt/car1/points");
  EXPECT_EQ(odom_topic("car1"), "rt/car1/odom");
  EXPECT_EQ(points_topic("fleet/car_2"), "rt/fleet/car_2/points");
  EXPECT_EQ(map_patches_topic(), "rt/litamin2/map_patches");
  EXPECT_EQ(status_topic(), "rt/litamin2/status");
}

TEST(TopicNames, ValidStreamIds) {
  for (const char* id : {"car1", "a", "_x", "Car_1", "fleet/car1", "a/b/c", "velodyne_top"}) {
    EXPECT_TRUE(is_valid_stream_id(id)) << id << ": " << stream_id_error(id).value_or("");
  }
  EXPECT_TRUE(is_valid_stream_id(std::string(245, 'a')));
}

TEST(TopicNames, InvalidStreamIds) {
  for (const char* id : {"", "/car1", "car1/", "a//b", "1car", "a/1b", "car-1", "car 1", "car.1",
                         "a__b", "~car", "{ns}", "car*", "caé"}) {
    const auto error = stream_id_error(id);
    EXPECT_TRUE(error.has_value()) << "'" << id << "' accepted";
    if (error) {
      EXPECT_FALSE(error->empty());
    }
  }
  EXPECT_FALSE(is_valid_stream_id(std::string(246, 'a')));
  EXPECT_NE(stream_id_error("1car")->find("digit"), std::string::npos);
}

TEST(TopicNames, PatternMatch) {
  const auto pattern = TopicPattern::parse("rt/*/points");
  ASSERT_TRUE(pattern);
  EXPECT_EQ(pattern->match("rt/car1/points").value_or("-"), "car1");
  EXPECT_EQ(pattern->match("rt/fleet/car1/points").value_or("-"), "fleet/car1");
  EXPECT_FALSE(pattern->match("rt//points"));
  EXPECT_FALSE(pattern->match("rt/points"));
  EXPECT_FALSE(pattern->match("rt/car1/odom"));
  EXPECT_FALSE(pattern->match("rt/car1/points/x"));
  EXPECT_FALSE(pattern->match("rq/car1/points"));
  EXPECT_FALSE(pattern->match("rt/1car/points"));  // not a valid stream id
  EXPECT_FALSE(pattern->match("rt/car-1/points"));
  EXPECT_FALSE(pattern->match("rt/a b/points"));
  EXPECT_FALSE(pattern->match("xrt/car1/points"));
  EXPECT_FALSE(pattern->match(""));
  EXPECT_EQ(pattern->topic_for("car7"), "rt/car7/points");
  EXPECT_EQ(pattern->str(), "rt/*/points");

  const auto lidar = TopicPattern::parse("rt/sensors/*");
  ASSERT_TRUE(lidar);
  EXPECT_EQ(lidar->match("rt/sensors/front").value_or("-"), "front");
  EXPECT_EQ(stream_from_topic("lidar_*", "lidar_front").value_or("-"), "front");
  EXPECT_EQ(stream_from_topic("rt/*/points", "rt/car9/points").value_or("-"), "car9");
  EXPECT_FALSE(stream_from_topic("rt/points", "rt/points"));
}

TEST(TopicNames, BadPatterns) {
  std::string error;
  EXPECT_FALSE(TopicPattern::parse("rt/car/points", &error));
  EXPECT_NE(error.find("no '*'"), std::string::npos);
  EXPECT_FALSE(TopicPattern::parse("rt/*/*", &error));
  EXPECT_NE(error.find("more than one"), std::string::npos);
  EXPECT_FALSE(TopicPattern::parse(std::string(300, 'a') + "*", &error));
  EXPECT_FALSE(TopicPattern::parse("rt/*/po ints", &error));
  EXPECT_NE(error.find("not a valid topic pattern"), std::string::npos);
  EXPECT_FALSE(TopicPattern::parse("rt/*/points?", &error));
}

TEST(TopicNames, TopicNameErrors) {
  EXPECT_FALSE(topic_name_error("rt/litamin2/map_patches"));
  EXPECT_FALSE(topic_name_error("odom"));
  EXPECT_NE(topic_name_error("")->find("empty"), std::string::npos);
  for (const char* bad : {"rt/a b", "rt/*/odom", "rt/odom?", "rt/tab\there", "rt/new\nline"})
    EXPECT_NE(topic_name_error(bad)->find("not a valid topic name"), std::string::npos) << bad;
  EXPECT_TRUE(topic_name_error(std::string(kMaxTopicLength + 1, 'a')));
  EXPECT_FALSE(topic_name_error(std::string(kMaxTopicLength, 'a')));
}

}  // namespace
}  // namespace litamin2::service
