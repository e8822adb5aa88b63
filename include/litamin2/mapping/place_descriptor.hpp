#pragma once
/// Place recognition descriptor of a keyframe, in the spirit of Scan Context (Kim and Kim,
/// IROS 2018) but computed from the keyframe's distributions instead of its points: a polar
/// grid of rings (range) by sectors (azimuth) around the sensor, each cell holding the largest
/// height of the distribution means that fall in it. A yaw of the sensor shifts the grid's
/// columns, so comparing under every column shift is yaw invariant and gives the yaw.

#include "litamin2/core/distribution.hpp"
#include "litamin2/core/keyframe.hpp"
#include "litamin2/mapping/mapper_config.hpp"

#include <cstdint>
#include <functional>
#include <vector>

namespace litamin2::mapping {

/// A keyframe's descriptor as the store keeps it in its nodes table (and the mapper in memory,
/// unless Mapper::keep_descriptor_cells_outside: then its ring key only): 1 byte per cell,
/// 1.2 kB a keyframe. The sector keys and column norms that the comparison needs are derived from
/// the cells when two descriptors are compared (match_descriptors).
struct PlaceDescriptor {
  int rings = 0;
  int sectors = 0;
  /// rings x sectors, row-major by ring; 0 marks an empty cell, else (height + offset) in
  /// steps of kDescriptorHeightStep, at least 1 (an occupied cell is never 0), at most 255.
  std::vector<std::uint8_t> cells;
  /// Per ring, the fraction of occupied sectors: invariant to yaw, used to shortlist (the
  /// ring-key index, ring_key_index.hpp).
  std::vector<float> ring_key;
};

/// Reads a keyframe's place descriptor, cells included, back from where its owner keeps it
/// (the aggregator's store), for graphs whose nodes hold their ring keys only
/// (Mapper::keep_descriptor_cells_outside).
using DescriptorLoader = std::function<PlaceDescriptor(const KeyframeKey&)>;

/// Frees the descriptor's cells (their memory too), keeping its ring key.
inline void release_cells(PlaceDescriptor& descriptor) {
  std::vector<std::uint8_t>().swap(descriptor.cells);
}

/// Column shifts on each side of the sector keys' best alignment that the full comparison
/// tries.
constexpr int kDescriptorShiftSearch = 3;

/// Heights are measured from this far below the sensor, so that every occupied cell (ground
/// included, about 1.7 m below a car's roof sensor) has a positive value.
constexpr double kDescriptorHeightOffset = 3.0;

/// Quantisation of a cell's height, metres: cells hold up to 25.5 m (22.5 m above the sensor).
constexpr double kDescriptorHeightStep = 0.1;

PlaceDescriptor make_place_descriptor(const std::vector<Distribution>& distributions,
                                      const PlaceRecognitionConfig& config);

struct DescriptorMatch {
  /// Mean cosine distance of the columns occupied in both (0 same place, 1 unrelated).
  double distance = 1.0;
  /// Yaw of the query's sensor in the candidate's sensor frame, radians (from the best
  /// column shift; resolution 2 pi / sectors).
  double yaw = 0.0;
};

/// Compares two descriptors of the same grid: the column shift is found by aligning the sector
/// keys, then the full comparison tries that shift and kDescriptorShiftSearch on each side
/// (Scan Context's fast alignment).
DescriptorMatch match_descriptors(const PlaceDescriptor& query, const PlaceDescriptor& candidate);

/// Squared Euclidean distance of the ring keys.
double ring_key_distance(const PlaceDescriptor& a, const PlaceDescriptor& b);

}  // namespace litamin2::mapping
