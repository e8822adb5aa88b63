// The store's distributions blob against the wire type it mirrors: a blob is, byte for byte, the
// little-endian CDR of litamin2/msg/VoxelDistribution (idl/litamin2/msg/VoxelDistribution.idl)
// serialised one element after another by Fast-CDR. The store keeps its own versioned codec
// (record_codec.hpp, schema.cpp) rather than calling the generated code, so that a change of the
// message cannot silently change the bytes of durable stores; this test is what ties the two
// together: if the IDL changes, it fails, and the store needs a schema version of its own.
#include <gtest/gtest.h>

#include <fastcdr/Cdr.h>
#include <fastcdr/FastBuffer.h>

#include <random>
#include <string>
#include <vector>

#include "litamin2/msg/VoxelDistribution.h"
#include "litamin2/store/record_codec.hpp"

namespace {

using namespace litamin2;

std::vector<Distribution> random_distributions(std::size_t n) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> position(-500.0, 500.0);
  std::uniform_real_distribution<double> spread(-1.0, 1.0);
  std::uniform_int_distribution<int> count(1, 5000);
  std::vector<Distribution> out(n);
  for (Distribution& d : out) {
    d.mean = Eigen::Vector3d(position(rng), position(rng), position(rng));
    Eigen::Matrix3d a;
    for (int i = 0; i < 9; ++i) a.data()[i] = spread(rng);
    d.cov = a * a.transpose() + 0.01 * Eigen::Matrix3d::Identity();
    d.count = count(rng);
  }
  return out;
}

std::vector<litamin2::msg::VoxelDistribution> as_messages(const std::vector<Distribution>& in) {
  std::vector<litamin2::msg::VoxelDistribution> out(in.size());
  for (std::size_t i = 0; i < in.size(); ++i) {
    const Distribution& d = in[i];
    out[i].mean({static_cast<float>(d.mean.x()), static_cast<float>(d.mean.y()),
                 static_cast<float>(d.mean.z())});
    out[i].cov({static_cast<float>(d.cov(0, 0)), static_cast<float>(d.cov(0, 1)),
                static_cast<float>(d.cov(0, 2)), static_cast<float>(d.cov(1, 1)),
                static_cast<float>(d.cov(1, 2)), static_cast<float>(d.cov(2, 2))});
    out[i].count(static_cast<std::uint32_t>(d.count));
  }
  return out;
}

TEST(StoreRecordCodecWireLayout, DistributionsBlobIsTheCdrOfVoxelDistribution) {
  const std::vector<Distribution> distributions = random_distributions(64);
  const std::vector<litamin2::msg::VoxelDistribution> messages = as_messages(distributions);

  std::string cdr_bytes(messages.size() * store::kDistributionBytes + 64, '\0');
  eprosima::fastcdr::FastBuffer buffer(cdr_bytes.data(), cdr_bytes.size());
  eprosima::fastcdr::Cdr cdr(buffer, eprosima::fastcdr::Cdr::LITTLE_ENDIANNESS);
  for (const auto& m : messages) m.serialize(cdr);
  cdr_bytes.resize(cdr.getSerializedDataLength());

  ASSERT_EQ(litamin2::msg::VoxelDistribution::getMaxCdrSerializedSize(0),
            store::kDistributionBytes);
  EXPECT_EQ(store::encode_distributions(distributions), cdr_bytes);
}

TEST(StoreRecordCodecWireLayout, CdrOfVoxelDistributionDecodesAsABlob) {
  const std::vector<litamin2::msg::VoxelDistribution> messages =
      as_messages(random_distributions(16));
  std::string cdr_bytes(messages.size() * store::kDistributionBytes, '\0');
  eprosima::fastcdr::FastBuffer buffer(cdr_bytes.data(), cdr_bytes.size());
  eprosima::fastcdr::Cdr cdr(buffer, eprosima::fastcdr::Cdr::LITTLE_ENDIANNESS);
  for (const auto& m : messages) m.serialize(cdr);

  const std::vector<Distribution> decoded =
      store::decode_distributions(cdr_bytes.data(), cdr_bytes.size(), RegularizerConfig{});
  ASSERT_EQ(decoded.size(), messages.size());
  const RegularizerConfig regularizer;
  for (std::size_t i = 0; i < decoded.size(); ++i) {
    const auto& m = messages[i];
    const auto& c = m.cov();
    Eigen::Matrix3d raw;
    raw << c[0], c[1], c[2], c[1], c[3], c[4], c[2], c[4], c[5];
    Eigen::Matrix3d cov, shape, shape_inv;
    regularize_for_terms(regularizer, raw, cov, shape, shape_inv);
    EXPECT_EQ(decoded[i].mean, Eigen::Vector3d(m.mean()[0], m.mean()[1], m.mean()[2]));
    EXPECT_EQ(decoded[i].cov, cov);
    EXPECT_EQ(decoded[i].shape_cov, shape);
    EXPECT_EQ(decoded[i].count, static_cast<int>(m.count()));
  }
}

}  // namespace
