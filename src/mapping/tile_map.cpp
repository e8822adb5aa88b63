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

}  // namespace

void validate(const TileMapConfig& c) {
  if (!(c.tile_size > 0.0)) throw ConfigError("tile_size must be positive");
  if (!(c.move_threshold_m >= 0.0)) throw ConfigError("move_threshold_m must be >= 0");
  if (!(c.move_threshold_deg >= 0.0 && c.move_threshold_deg <= 180.0))
    throw ConfigError("move_threshold_deg must be in [0, 180]");
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
}

void TileMap::mark(std::uint32_t node) {
  if (queued_.size() <= node) queued_.resize(node + 1, false);
  if (queued_[node]) return;
  queued_[node] = true;
  queue_.push_back(node);
}

std::int64_t TileMap::map_anchor(const KeyframeGraph& graph) {
  const StreamGroups& groups = graph.groups();
  if (groups.streams().empty()) return -1;
  return groups.anchor_of(groups.index(groups.first_stream()));
}

bool TileMap::moved(const Fused& f, const Eigen::Isometry3d& pose) const {
  const Eigen::Matrix<double, 3, 4> m = pose.matrix().topRows<3>();
  if (m == f.pose) return false;
  if (config_.move_threshold_m == 0.0 && config_.move_threshold_deg == 0.0) return true;
  if ((m.col(3) - f.pose.col(3)).norm() > config_.move_threshold_m) return true;
  const Eigen::Matrix3d relative = f.pose.leftCols<3>().transpose() * m.leftCols<3>();
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
  while (!queue_.empty() && (max_keyframes == 0 || done < max_keyframes)) {
    const std::uint32_t n = queue_.front();
    queue_.pop_front();
    queued_[n] = false;
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
    if (node_changed_.size() <= n) node_changed_.resize(n + 1, false);
    if (!node_changed_[n]) {
      node_changed_[n] = true;
      changed_nodes_.push_back(n);
    }
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
  touched_.clear();
  evict();
  return done;
}

void TileMap::fuse(const std::vector<Distribution>& distributions, const Eigen::Isometry3d& pose,
                   int sign) {
  const std::vector<FusedMoment> moments = fused_moments(distributions, pose, geometry_);
  // A keyframe touches a few tiles: look each up once.
  std::vector<std::pair<TileKey, MapTile*>> seen;
  for (const FusedMoment& m : moments) {
    MapTile* tile = nullptr;
    for (const auto& [key, t] : seen) {
      if (key == m.tile) tile = t;
    }
    if (!tile) {
      tile = &writable(m.tile);
      tile->count_keyframe(sign);
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
  return s;
}

}  // namespace litamin2::mapping
