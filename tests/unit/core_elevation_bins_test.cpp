#include "litamin2/core/elevation_bins.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>

namespace litamin2 {
namespace {

constexpr double kLow = -45.0, kWidth = 0.05;
constexpr int kBins = 1800;

/// The bin by its definition: the elevation from atan2, in degrees, floored to the bin.
int bin_by_atan2(double z, double horizontal) {
  const double elevation = std::atan2(z, horizontal) * 180.0 / M_PI;
  const int bin = static_cast<int>(std::floor((elevation - kLow) / kWidth));
  return bin >= 0 && bin < kBins ? bin : -1;
}

TEST(ElevationBins, AgreesWithAtan2OnRandomDirections) {
  const ElevationBins bins(kLow, kWidth, kBins);
  ASSERT_EQ(bins.size(), kBins);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> elevation_deg(-50.0, 50.0);
  std::uniform_real_distribution<double> range(0.5, 150.0);
  int compared = 0, outside = 0;
  for (int i = 0; i < 1000000; ++i) {
    const double e = elevation_deg(rng) * M_PI / 180.0;
    const double r = range(rng);
    const double horizontal = r * std::cos(e), z = r * std::sin(e);
    // Directions within rounding of an edge may fall either side: not compared.
    const double from_low = (std::atan2(z, horizontal) * 180.0 / M_PI - kLow) / kWidth;
    if (std::abs(from_low - std::round(from_low)) < 1e-9) continue;
    const int expected = bin_by_atan2(z, horizontal);
    ASSERT_EQ(bins.bin(z, horizontal), expected) << "elevation " << e * 180.0 / M_PI << " deg";
    ++compared;
    if (expected < 0) ++outside;
  }
  EXPECT_GT(compared, 999000);
  EXPECT_GT(outside, 50000);  // the +-45..50 deg directions are outside every bin
}

TEST(ElevationBins, EveryBinsMiddleFallsInIt) {
  const ElevationBins bins(kLow, kWidth, kBins);
  for (int k = 0; k < kBins; ++k) {
    const double e = (kLow + (k + 0.5) * kWidth) * M_PI / 180.0;
    for (double r : {1.0, 20.0, 110.0})
      ASSERT_EQ(bins.bin(r * std::sin(e), r * std::cos(e)), k) << "bin " << k;
  }
}

TEST(ElevationBins, DirectionsWithoutAHorizontalPartAreInNoBin) {
  const ElevationBins bins(kLow, kWidth, kBins);
  EXPECT_EQ(bins.bin(3.0, 0.0), -1);
  EXPECT_EQ(bins.bin(-3.0, 0.0), -1);
  EXPECT_EQ(bins.bin(0.0, -1.0), -1);
  EXPECT_EQ(bins.bin(std::numeric_limits<double>::quiet_NaN(), 1.0), -1);
  EXPECT_EQ(bins.bin(1.0, std::numeric_limits<double>::quiet_NaN()), -1);
  EXPECT_EQ(bins.bin(0.0, 1.0), 900);  // level: the first bin above -45 + 900 * 0.05 = 0 deg
}

TEST(ElevationBins, BinsOutsideTheOpenHalfCircleAreRejected) {
  EXPECT_THROW(ElevationBins(-90.0, 1.0, 10), std::invalid_argument);
  EXPECT_THROW(ElevationBins(80.0, 1.0, 10), std::invalid_argument);
  EXPECT_THROW(ElevationBins(0.0, 0.0, 10), std::invalid_argument);
  EXPECT_THROW(ElevationBins(0.0, 1.0, 0), std::invalid_argument);
  EXPECT_NO_THROW(ElevationBins(-89.0, 1.0, 178));
}

}  // namespace
}  // namespace litamin2
