#include "litamin2/mapping/tile_map.hpp"

#include "litamin2/core/config_error.hpp"

#include <algorithm>
#include <cmath>

namespace litamin2::mapping {

namespace {

Eigen::Isometry3d isometry(const Eigen::Matrix<double, 3, 4>& m) {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.matrix().topRows<3>() = m;
  return pose;
}

Eigen::Matrix<double, 3, 4> top(const Eigen::Isometry3d& pose) {
  return pose.matrix().topRows<3>();
}

/// a^-1 b for rigid 3x4 poses.
Eigen::Matrix<double, 3, 4> relative_pose(const Eigen::Matrix<double, 3, 4>& a,
                                          const Eigen::Matrix<double, 3, 4>& b) {
  return top(isometry(a).inverse(Eigen::Isometry) * isometry(b));
}

Eigen::Matrix<double, 3, 4> compose(const Eigen::Matrix<double, 3, 4>& a,
                                    const Eigen::Matrix<double, 3, 4>& b) {
  return top(isometry(a) * isometry(b));
}

}  // namespace

void validate(const TileMapConfig& c) {
  if (!(c.tile_size > 0.0)) throw ConfigError("tile_size must be positive");
  if (!(c.move_threshold_m >= 0.0)) throw ConfigError("move_threshold_m must be >= 0");
  if (!(c.move_threshold_deg >= 0.0 && c.move_threshold_deg <= 180.0))
    throw ConfigError("move_threshold_deg must be in [0, 180]");
  if (c.segment_keyframes < 0) throw ConfigError("segment_keyframes must be >= 0");
  if (!(c.segment_cache_mb >= 0.0)) throw ConfigError("segment_cache_mb must be >= 0");
}

TileMap::TileMap(const TileMapConfig& config, double voxel_size, Loader loader,
                 std::size_t max_bytes)
    : config_((validate(config), config)), loader_(std::move(loader)), max_bytes_(max_bytes) {
  if (!(voxel_size > 0.0)) throw ConfigError("map voxel size must be positive");
  if (!(config.move_threshold_m < voxel_size))
    throw ConfigError("move_threshold_m must be below the map's voxel size");
  geometry_.tile_size = config.tile_size;
  geometry_.voxels.voxel_size = voxel_size;
  cos_threshold_ = std::cos(config.move_threshold_deg * M_PI / 180.0);
  segment_max_bytes_ = static_cast<std::size_t>(config.segment_cache_mb * 1024.0 * 1024.0);
}

void TileMap::mark(std::uint32_t node) {
  if (queued_.size() <= node) queued_.resize(node + 1, false);
  if (queued_[node]) return;
  queued_[node] = true;
  ++marked_;
  queue_.push_back(node);
}

std::int64_t TileMap::map_anchor(const KeyframeGraph& graph) {
  const StreamGroups& groups = graph.groups();
  if (groups.streams().empty()) return -1;
  return groups.anchor_of(groups.index(groups.first_stream()));
}

bool TileMap::moved(const Fused& f, const Eigen::Isometry3d& pose) const {
  return moved(f.pose, top(pose));
}

bool TileMap::moved(const Pose34& from, const Pose34& m) const {
  if (m == from) return false;
  if (config_.move_threshold_m == 0.0 && config_.move_threshold_deg == 0.0) return true;
  if ((m.col(3) - from.col(3)).norm() > config_.move_threshold_m) return true;
  const Eigen::Matrix3d relative = from.leftCols<3>().transpose() * m.leftCols<3>();
  return (relative.trace() - 1.0) / 2.0 < cos_threshold_;
}

void TileMap::restore(const KeyframeGraph& graph,
                      std::vector<std::optional<Eigen::Isometry3d>> fused,
                      std::vector<TileSummary> index) {
  fused_.assign(graph.size(), Fused{});
  for (std::size_t n = 0; n < fused.size() && n < fused_.size(); ++n) {
    if (!fused[n]) continue;
    fused_[n].pose = fused[n]->matrix().topRows<3>();
    fused_[n].fused = true;
  }
  index_.clear();
  stats_.distributions = 0;
  for (TileSummary& s : index) {
    stats_.distributions += static_cast<std::size_t>(s.distributions);
    const TileKey key = s.key;
    index_.emplace(key, std::move(s));
  }
  fused_anchor_ = map_anchor(graph);
  if (config_.segment_keyframes > 0) {
    // Each segment's frame is its reference's fused pose (the lowest id fused); the relative
    // poses follow from the fused ones; the moments are recomputed when the segment moves.
    for (auto& [key, segment] : segments_) moments_changed(segment);
    segments_.clear();
    segment_lru_.clear();
    stats_.segments = 0;
    segment_bytes_ = 0;
    registered_ = 0;
    register_nodes(graph);
    for (auto& [key, segment] : segments_) {
      std::int64_t reference = -1;
      for (std::uint32_t n : segment.nodes) {
        if (!fused_[n].fused) continue;
        if (reference < 0 ||
            graph.node(n).key.id < graph.node(static_cast<std::uint32_t>(reference)).key.id)
          reference = n;
      }
      if (reference < 0) continue;
      segment.placed = true;
      segment.reference = static_cast<std::uint32_t>(reference);
      segment.frame = fused_[segment.reference].pose;
      for (std::uint32_t n : segment.nodes) {
        if (fused_[n].fused) fused_[n].relative = relative_pose(segment.frame, fused_[n].pose);
      }
      segment.voxels.reset();
      ++stats_.segments;
    }
  }
  const StreamGroups& groups = graph.groups();
  for (std::uint32_t n = 0; n < graph.size(); ++n) {
    const KeyframeNode& node = graph.node(n);
    const bool in_map = fused_anchor_ >= 0 && groups.anchor_of(node.stream) == fused_anchor_;
    const Fused& f = fused_[n];
    if (in_map != f.fused || (f.fused && moved(f, node.pose))) mark(n);
  }
}

std::size_t TileMap::update(const KeyframeGraph& graph, DistributionCache& cache,
                            std::size_t max_keyframes) {
  const std::int64_t anchor = map_anchor(graph);
  if (anchor != fused_anchor_) {
    // The map frame is another group's now: every keyframe changes frame.
    for (std::uint32_t n = 0; n < graph.size(); ++n) mark(n);
    fused_anchor_ = anchor;
  }
  if (fused_.size() < graph.size()) fused_.resize(graph.size());
  const StreamGroups& groups = graph.groups();
  std::size_t done = 0;
  if (config_.segment_keyframes > 0) {
    register_nodes(graph);
    ++generation_;
    while (!queue_.empty() && (max_keyframes == 0 || done < max_keyframes)) {
      const std::uint32_t n = queue_.front();
      queue_.pop_front();
      if (!queued_[n]) continue;  // its segment was reconciled since it was marked
      const SegmentKey key = segment_key(graph.node(n));
      Segment& segment = segments_.at(key);
      // The segment is reconciled whole: its other marks are done too.
      for (std::uint32_t m : segment.nodes) {
        if (m < queued_.size() && queued_[m]) {
          queued_[m] = false;
          --marked_;
        }
      }
      if (segment.generation == generation_) continue;
      segment.generation = generation_;
      // A segment's moments recomputed (evicted) cost its keyframes' fusions too.
      const std::size_t recomputed = recomputed_keyframes_;
      done += reconcile(segment, key, graph, cache, anchor);
      done += recomputed_keyframes_ - recomputed;
      evict_segments(&key);
    }
  }
  while (config_.segment_keyframes == 0 && !queue_.empty() &&
         (max_keyframes == 0 || done < max_keyframes)) {
    const std::uint32_t n = queue_.front();
    queue_.pop_front();
    queued_[n] = false;
    --marked_;
    const KeyframeNode& node = graph.node(n);
    const bool in_map = anchor >= 0 && groups.anchor_of(node.stream) == anchor;
    Fused& f = fused_[n];
    const bool remove = f.fused && (!in_map || moved(f, node.pose));
    const bool add = in_map && (!f.fused || remove);
    if (!remove && !add) continue;
    const Distributions distributions = cache.get(node.key);
    if (remove) {
      fuse(*distributions, isometry(f.pose), -1);
      f.fused = false;
      ++stats_.subtracted;
    }
    if (add) {
      f.pose = node.pose.matrix().topRows<3>();
      f.fused = true;
      fuse(*distributions, isometry(f.pose), +1);
      ++stats_.added;
    }
    changed_node(n);
    ++done;
  }
  // Refresh the summaries of the tiles touched; an empty tile leaves the index (and the
  // store, at take_changes()).
  std::sort(touched_.begin(), touched_.end());
  touched_.erase(std::unique(touched_.begin(), touched_.end()), touched_.end());
  for (const TileKey& key : touched_) {
    Entry& e = tiles_.at(key);
    const auto old = index_.find(key);
    if (old != index_.end()) {
      stats_.distributions -= static_cast<std::size_t>(old->second.distributions);
      index_.erase(old);
    }
    if (!e.tile->empty()) {
      TileSummary s = e.tile->summary(geometry_);
      stats_.distributions += static_cast<std::size_t>(s.distributions);
      index_.emplace(key, std::move(s));
    }
    bytes_ -= e.bytes;
    e.bytes = e.tile->bytes();
    bytes_ += e.bytes;
  }
  updated_.swap(touched_);
  touched_.clear();
  evict();
  return done;
}

void TileMap::changed_node(std::uint32_t n) {
  if (node_changed_.size() <= n) node_changed_.resize(n + 1, false);
  if (!node_changed_[n]) {
    node_changed_[n] = true;
    changed_nodes_.push_back(n);
  }
}

void TileMap::fuse(const std::vector<Distribution>& distributions, const Eigen::Isometry3d& pose,
                   int sign) {
  apply_moments(fused_moments(distributions, pose, geometry_), sign, 1);
}

void TileMap::place(const SegmentVoxels& voxels, const Pose34& frame, int sign,
                    std::int64_t keyframes) {
  apply_moments(placed_moments(voxels, isometry(frame), geometry_), sign, keyframes);
  ++stats_.segment_placements;
}

TileMap::SegmentKey TileMap::segment_key(const KeyframeNode& node) const {
  return {node.stream, node.key.id / static_cast<std::uint64_t>(config_.segment_keyframes)};
}

void TileMap::register_nodes(const KeyframeGraph& graph) {
  for (; registered_ < graph.size(); ++registered_) {
    const auto n = static_cast<std::uint32_t>(registered_);
    segments_[segment_key(graph.node(n))].nodes.push_back(n);
  }
}

SegmentVoxels& TileMap::segment_voxels(Segment& segment, const SegmentKey& key,
                                       const KeyframeGraph& graph, DistributionCache& cache) {
  if (segment.voxels) {
    segment_lru_.splice(segment_lru_.begin(), segment_lru_, segment.lru);
    return *segment.voxels;
  }
  if (spill_ && segment.spilled) {
    segment.voxels = std::make_shared<SegmentVoxels>(spill_->read(segment.spill));
    ++stats_.segment_spill_reads;
  } else {
    segment.voxels = std::make_shared<SegmentVoxels>();
    for (std::uint32_t n : segment.nodes) {
      const Fused& f = fused_[n];
      if (!f.fused) continue;
      ++recomputed_keyframes_;
      stats_.inconsistent += segment.voxels->apply(
          *cache.get(graph.node(n).key), isometry(f.relative), geometry_.voxels.voxel_size, +1);
    }
    ++stats_.segment_recomputes;
  }
  segment_lru_.push_front(key);
  segment.lru = segment_lru_.begin();
  segment.bytes = 0;
  return *segment.voxels;
}

std::size_t TileMap::reconcile(Segment& segment, const SegmentKey& key, const KeyframeGraph& graph,
                               DistributionCache& cache, std::int64_t anchor) {
  const StreamGroups& groups = graph.groups();
  const double voxel = geometry_.voxels.voxel_size;
  auto in_map = [&](std::uint32_t n) {
    return anchor >= 0 && groups.anchor_of(graph.node(n).stream) == anchor;
  };
  std::int64_t reference = -1;
  std::int64_t fused_count = 0;
  for (std::uint32_t n : segment.nodes) {
    if (fused_[n].fused) ++fused_count;
    if (!in_map(n)) continue;
    if (reference < 0 ||
        graph.node(n).key.id < graph.node(static_cast<std::uint32_t>(reference)).key.id)
      reference = n;
  }
  std::size_t done = 0;
  // Out of the map, or a new reference (a late keyframe of lower id): take the segment out.
  if (segment.placed &&
      (reference < 0 || static_cast<std::uint32_t>(reference) != segment.reference)) {
    place(segment_voxels(segment, key, graph, cache), segment.frame, -1, fused_count);
    for (std::uint32_t n : segment.nodes) {
      if (!fused_[n].fused) continue;
      fused_[n].fused = false;
      changed_node(n);
      ++stats_.subtracted;
    }
    segment.placed = false;
    moments_changed(segment);
    if (segment.voxels) {
      segment_lru_.erase(segment.lru);
      segment_bytes_ -= segment.bytes;
      segment.voxels.reset();
      segment.bytes = 0;
    }
    fused_count = 0;
    ++done;
    --stats_.segments;
  }
  if (reference < 0) return done;
  const auto ref = static_cast<std::uint32_t>(reference);

  if (!segment.placed) {
    // Fused once in the frame of its reference's pose.
    segment.placed = true;
    segment.reference = ref;
    segment.frame = top(graph.node(ref).pose);
    moments_changed(segment);
    segment.voxels = std::make_shared<SegmentVoxels>();
    segment_lru_.push_front(key);
    segment.lru = segment_lru_.begin();
    segment.bytes = 0;
    std::int64_t members = 0;
    for (std::uint32_t n : segment.nodes) {
      if (!in_map(n)) continue;
      Fused& f = fused_[n];
      f.pose = top(graph.node(n).pose);
      f.relative = relative_pose(segment.frame, f.pose);
      f.fused = true;
      stats_.inconsistent +=
          segment.voxels->apply(*cache.get(graph.node(n).key), isometry(f.relative), voxel, +1);
      changed_node(n);
      ++stats_.added;
      ++members;
      ++done;
    }
    place(*segment.voxels, segment.frame, +1, members);
    ++stats_.segments;
  } else {
    // The same reference: re-place the frame if the reference moved, and re-fuse within the
    // segment only the keyframes that arrived, left or moved relative to it.
    const Pose34 now = top(graph.node(ref).pose);
    const bool frame_moved = moved(segment.frame, now);
    const Pose34 frame = frame_moved ? now : segment.frame;
    std::vector<std::uint32_t> changed;
    for (std::uint32_t n : segment.nodes) {
      const Fused& f = fused_[n];
      const bool want = in_map(n);
      if (f.fused != want || (want && moved(compose(frame, f.relative), top(graph.node(n).pose))))
        changed.push_back(n);
    }
    if (!frame_moved && changed.empty()) return done;
    SegmentVoxels& voxels = segment_voxels(segment, key, graph, cache);
    if (!changed.empty()) moments_changed(segment);
    place(voxels, segment.frame, -1, fused_count);
    std::int64_t members = fused_count;
    for (std::uint32_t n : changed) {
      Fused& f = fused_[n];
      const Distributions distributions = cache.get(graph.node(n).key);
      if (f.fused) {
        stats_.inconsistent += voxels.apply(*distributions, isometry(f.relative), voxel, -1);
        f.fused = false;
        --members;
        ++stats_.subtracted;
        ++done;
      }
      if (in_map(n)) {
        f.relative = relative_pose(frame, top(graph.node(n).pose));
        f.fused = true;
        stats_.inconsistent += voxels.apply(*distributions, isometry(f.relative), voxel, +1);
        ++members;
        ++stats_.added;
        ++done;
      }
      changed_node(n);
    }
    segment.frame = frame;
    for (std::uint32_t n : segment.nodes) {
      Fused& f = fused_[n];
      if (!f.fused) continue;
      f.pose = compose(frame, f.relative);
      if (frame_moved) changed_node(n);
    }
    place(voxels, segment.frame, +1, members);
    done += 2;
  }
  segment_bytes_ -= segment.bytes;
  segment.bytes = segment.voxels->bytes();
  segment_bytes_ += segment.bytes;
  return done;
}

void TileMap::evict_segments(const SegmentKey* keep) {
  while (segment_bytes_ > segment_max_bytes_ && !segment_lru_.empty()) {
    const SegmentKey key = segment_lru_.back();
    if (keep && key == *keep) break;
    Segment& segment = segments_.at(key);
    if (spill_ && !segment.spilled) {
      segment.spill = spill_->write(*segment.voxels, segment.spill);
      segment.spilled = true;
      ++stats_.segment_spill_writes;
    }
    segment_bytes_ -= segment.bytes;
    segment.bytes = 0;
    segment.voxels.reset();
    segment_lru_.pop_back();
  }
}

void TileMap::moments_changed(Segment& segment) {
  if (spill_) spill_->release(segment.spill);
  segment.spill = {};
  segment.spilled = false;
}

void TileMap::apply_moments(const std::vector<FusedMoment>& moments, int sign,
                            std::int64_t keyframes) {
  // A keyframe touches a few tiles: look each up once.
  std::vector<std::pair<TileKey, MapTile*>> seen;
  for (const FusedMoment& m : moments) {
    MapTile* tile = nullptr;
    for (const auto& [key, t] : seen) {
      if (key == m.tile) tile = t;
    }
    if (!tile) {
      tile = &writable(m.tile);
      tile->count_keyframe(sign * keyframes);
      seen.emplace_back(m.tile, tile);
    }
    if (!tile->apply(m.voxel, m.moments, sign)) ++stats_.inconsistent;
  }
}

TileMap::Entry* TileMap::find(TileKey key) {
  const auto it = tiles_.find(key);
  if (it != tiles_.end()) {
    Entry& e = it->second;
    if (!e.dirty) clean_.splice(clean_.begin(), clean_, e.lru);
    return &e;
  }
  if (!loader_ || !index_.count(key)) return nullptr;
  std::optional<MapTile> loaded = loader_(key);
  if (!loaded) return nullptr;
  ++stats_.loads;
  Entry& e = tiles_[key];
  e.tile = std::make_shared<MapTile>(std::move(*loaded));
  e.bytes = e.tile->bytes();
  bytes_ += e.bytes;
  clean_.push_front(key);
  e.lru = clean_.begin();
  return &e;
}

MapTile& TileMap::writable(TileKey key) {
  Entry* e = find(key);
  if (!e) {
    e = &tiles_[key];
    e->tile = std::make_shared<MapTile>(key);
    e->dirty = true;
    dirty_.insert(key);
  } else if (!e->dirty) {
    clean_.erase(e->lru);
    e->dirty = true;
    dirty_.insert(key);
  }
  // Someone still holds the tile (a take_changes() result): change a copy.
  if (e->tile.use_count() > 1) e->tile = std::make_shared<MapTile>(*e->tile);
  touched_.push_back(key);
  return *e->tile;
}

TileMap::Changes TileMap::take_changes() {
  Changes out;
  for (const TileKey& key : dirty_) {
    const auto it = tiles_.find(key);
    Entry& e = it->second;
    out.tiles.push_back(e.tile);
    if (e.tile->empty()) {
      bytes_ -= e.bytes;
      tiles_.erase(it);
      continue;
    }
    e.dirty = false;
    clean_.push_front(key);
    e.lru = clean_.begin();
  }
  dirty_.clear();
  std::sort(changed_nodes_.begin(), changed_nodes_.end());
  for (std::uint32_t n : changed_nodes_) {
    out.nodes.emplace_back(n, fused_pose(n));
    node_changed_[n] = false;
  }
  changed_nodes_.clear();
  evict();
  return out;
}

std::shared_ptr<const MapTile> TileMap::tile(TileKey key) {
  Entry* e = find(key);
  return e ? e->tile : nullptr;
}

std::optional<Eigen::Isometry3d> TileMap::fused_pose(std::uint32_t node) const {
  if (node >= fused_.size() || !fused_[node].fused) return std::nullopt;
  return isometry(fused_[node].pose);
}

void TileMap::evict() {
  if (!loader_ || max_bytes_ == 0) return;
  while (bytes_ > max_bytes_ && !clean_.empty()) {
    const auto it = tiles_.find(clean_.back());
    bytes_ -= it->second.bytes;
    tiles_.erase(it);
    clean_.pop_back();
  }
}

TileMapStats TileMap::stats() const {
  TileMapStats s = stats_;
  s.tiles = index_.size();
  s.tiles_in_memory = tiles_.size();
  s.bytes_in_memory = bytes_;
  s.segment_bytes = segment_bytes_;
  s.segment_spill_bytes = spill_ ? spill_->file_bytes() : 0;
  return s;
}

}  // namespace litamin2::mapping
