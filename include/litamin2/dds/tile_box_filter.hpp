#pragma once
/// A DDS content filter of rt/litamin2/map_tiles on the tile key: the tiles with
/// ix in [ix_min, ix_max] and iy in [iy_min, iy_max]. A custom filter class, not Fast DDS's
/// SQL one: that one needs the type's TypeObject, which the project's generated types do not
/// register (fastddsgen runs without -typeobject, idl/CMakeLists.txt). It reads the two key
/// fields off the serialised sample (MapTile.idl's first members, after the CDR encapsulation)
/// and keeps a sample too short or of an unknown encapsulation out.
///
/// A reader's participant registers the factory (register_tile_box_filter) and creates its
/// ContentFilteredTopic with kTileBoxFilterClass and tile_box_parameters; the writer's
/// participant registers it too, so that the writer filters (DDS then sends each reader only
/// its tiles); a writer without it sends every tile and the reader filters.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace eprosima::fastdds::dds {
class DomainParticipant;
}  // namespace eprosima::fastdds::dds

namespace litamin2::dds {

inline constexpr const char* kTileBoxFilterClass = "LITAMIN2_TILE_BOX";
/// The filter expression (informative: the box is in the parameters).
inline constexpr const char* kTileBoxExpression = "ix BETWEEN %0 AND %1 AND iy BETWEEN %2 AND %3";

struct TileBox {
  std::int32_t ix_min = 0, ix_max = 0, iy_min = 0, iy_max = 0;
  bool contains(std::int32_t ix, std::int32_t iy) const {
    return ix >= ix_min && ix <= ix_max && iy >= iy_min && iy <= iy_max;
  }
};

/// The filter's four parameters, decimal: ix_min, ix_max, iy_min, iy_max.
std::vector<std::string> tile_box_parameters(const TileBox& box);
/// The box of four parameters; nullopt unless each is a decimal int32 and min <= max.
std::optional<TileBox> parse_tile_box(const std::vector<std::string>& parameters);
/// The key of a serialised MapTile (CDR, little- or big-endian), nullopt when the payload is
/// shorter than the key or of another encapsulation.
std::optional<std::pair<std::int32_t, std::int32_t>> serialized_tile_key(const std::uint8_t* data,
                                                                         std::size_t size);

/// Registers the filter class on `participant` (once per participant; true on success).
bool register_tile_box_filter(eprosima::fastdds::dds::DomainParticipant* participant);

/// Samples this process's box filters have evaluated (and let through): on a writer's side
/// when the writer filters, on the reader's when it does not.
std::uint64_t tile_box_evaluations();
std::uint64_t tile_box_passed();

}  // namespace litamin2::dds
