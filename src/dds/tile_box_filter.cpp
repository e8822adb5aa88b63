#include "litamin2/dds/tile_box_filter.hpp"

#include <fastdds/dds/domain/DomainParticipant.hpp>
#include <fastdds/dds/topic/IContentFilter.hpp>
#include <fastdds/dds/topic/IContentFilterFactory.hpp>

#include <atomic>
#include <charconv>
#include <cstring>
#include <string_view>

namespace litamin2::dds {
namespace {

namespace fdds = eprosima::fastdds::dds;

std::atomic<std::uint64_t> g_evaluations{0};
std::atomic<std::uint64_t> g_passed{0};

/// CDR encapsulation identifiers (first two bytes): plain CDR, big- and little-endian.
constexpr std::uint8_t kCdrBigEndian = 0x00;
constexpr std::uint8_t kCdrLittleEndian = 0x01;
constexpr std::size_t kEncapsulationBytes = 4;

std::int32_t read_int32(const std::uint8_t* p, bool little_endian) {
  std::uint32_t v = 0;
  if (little_endian) {
    v = std::uint32_t(p[0]) | std::uint32_t(p[1]) << 8 | std::uint32_t(p[2]) << 16 |
        std::uint32_t(p[3]) << 24;
  } else {
    v = std::uint32_t(p[3]) | std::uint32_t(p[2]) << 8 | std::uint32_t(p[1]) << 16 |
        std::uint32_t(p[0]) << 24;
  }
  std::int32_t out;
  std::memcpy(&out, &v, sizeof out);
  return out;
}

class TileBoxFilter final : public fdds::IContentFilter {
 public:
  explicit TileBoxFilter(const TileBox& box) : box_(box) {}
  bool evaluate(const SerializedPayload& payload, const FilterSampleInfo&,
                const GUID_t&) const override {
    const auto key = serialized_tile_key(payload.data, payload.length);
    const bool pass = key && box_.contains(key->first, key->second);
    g_evaluations.fetch_add(1, std::memory_order_relaxed);
    if (pass) g_passed.fetch_add(1, std::memory_order_relaxed);
    return pass;
  }
  TileBox box_;
};

class TileBoxFilterFactory final : public fdds::IContentFilterFactory {
 public:
  ReturnCode_t create_content_filter(const char*, const char*, const fdds::TopicDataType*,
                                     const char*, const ParameterSeq& parameters,
                                     fdds::IContentFilter*& filter) override {
    std::vector<std::string> values;
    for (fdds::LoanableCollection::size_type i = 0; i < parameters.length(); ++i)
      values.emplace_back(parameters[i] ? parameters[i] : "");
    const auto box = parse_tile_box(values);
    if (!box) return ReturnCode_t::RETCODE_BAD_PARAMETER;
    if (filter) {
      static_cast<TileBoxFilter*>(filter)->box_ = *box;
    } else {
      filter = new TileBoxFilter(*box);
    }
    return ReturnCode_t::RETCODE_OK;
  }
  ReturnCode_t delete_content_filter(const char*, fdds::IContentFilter* filter) override {
    delete static_cast<TileBoxFilter*>(filter);
    return ReturnCode_t::RETCODE_OK;
  }
};

std::optional<std::int32_t> parse_int32(const std::string& s) {
  std::int32_t v = 0;
  const char* end = s.data() + s.size();
  const auto [ptr, ec] = std::from_chars(s.data(), end, v);
  if (s.empty() || ec != std::errc() || ptr != end) return std::nullopt;
  return v;
}

}  // namespace

std::vector<std::string> tile_box_parameters(const TileBox& box) {
  return {std::to_string(box.ix_min), std::to_string(box.ix_max), std::to_string(box.iy_min),
          std::to_string(box.iy_max)};
}

std::optional<TileBox> parse_tile_box(const std::vector<std::string>& parameters) {
  if (parameters.size() != 4) return std::nullopt;
  std::int32_t v[4];
  for (int i = 0; i < 4; ++i) {
    const auto x = parse_int32(parameters[i]);
    if (!x) return std::nullopt;
    v[i] = *x;
  }
  if (v[0] > v[1] || v[2] > v[3]) return std::nullopt;
  return TileBox{v[0], v[1], v[2], v[3]};
}

std::optional<std::pair<std::int32_t, std::int32_t>> serialized_tile_key(const std::uint8_t* data,
                                                                         std::size_t size) {
  if (!data || size < kEncapsulationBytes + 8 || data[0] != 0x00) return std::nullopt;
  if (data[1] != kCdrBigEndian && data[1] != kCdrLittleEndian) return std::nullopt;
  const bool little = data[1] == kCdrLittleEndian;
  const std::uint8_t* body = data + kEncapsulationBytes;
  return std::make_pair(read_int32(body, little), read_int32(body + 4, little));
}

bool register_tile_box_filter(fdds::DomainParticipant* participant) {
  static TileBoxFilterFactory factory;  // stateless, shared by every participant
  return participant->register_content_filter_factory(kTileBoxFilterClass, &factory) ==
         ReturnCode_t::RETCODE_OK;
}

std::uint64_t tile_box_evaluations() {
  return g_evaluations.load(std::memory_order_relaxed);
}

std::uint64_t tile_box_passed() {
  return g_passed.load(std::memory_order_relaxed);
}

}  // namespace litamin2::dds
