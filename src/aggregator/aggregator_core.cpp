#include "litamin2/aggregator/aggregator_core.hpp"

#include "litamin2/core/stopwatch.hpp"
#include "litamin2/store/record_codec.hpp"

#include <algorithm>

namespace litamin2::aggregator {
namespace {

std::unique_ptr<mapping::DistributionCache> make_cache(const store::KeyframeStore& store,
                                                       std::size_t bytes) {
  return std::make_unique<mapping::DistributionCache>(
      [&store](const KeyframeKey& key) {
        return store.load_distributions(key, AggregatorCore::regularizer());
      },
      bytes);
}

}  // namespace

const RegularizerConfig& AggregatorCore::regularizer() {
  static const RegularizerConfig config{};
  return config;
}

AggregatorCore::AggregatorCore(const std::string& store_path, store::OpenMode mode,
                               const mapping::MapperConfig& mapper_config,
                               const store::StoreOptions& store_options, const Progress& progress,
                               const CoreOptions& options)
    : store_(store::KeyframeStore::open(store_path, mode, store_options)),
      read_only_(mode == store::OpenMode::kReadOnly),
      mapper_(mapper_config, make_cache(store_, options.distribution_cache_bytes)),
      tiles_(
          options.tiles, mapper_config.map_voxel_size,
          [this](mapping::TileKey key) { return store_.load_tile(key, tiles_.geometry()); },
          options.tile_cache_bytes) {
  // Evicted segment moments are spilled next to the store (a scratch file, unlinked at once:
  // segment_spill.hpp), not recomputed from the keyframes each time a full pass moves them.
  // Read-only, nothing is written beside the store.
  if (!read_only_ && options.spill_segments)
    tiles_.spill_segments_to(std::make_unique<mapping::SegmentSpill>(store_path + "-segments"));
  if (options.recovery == CoreOptions::Recovery::kReplay) {
    replay(progress);
  } else {
    recover_from_tables(progress);
  }
}

void AggregatorCore::replay(const Progress& progress) {
  std::vector<Keyframe> keyframes = store_.load_keyframes(regularizer());
  const std::size_t total = keyframes.size();
  for (std::size_t i = 0; i < total; ++i) {
    mapper_.add_keyframe(std::move(keyframes[i]));
    if (progress && ((i + 1) % 100 == 0 || i + 1 == total)) progress(i + 1, total);
  }
  recovered_ = total;
  mapper_.optimize_full();
  // The tiles are made again from the replayed graph: every keyframe of the map is to fuse.
  tiles_.restore(mapper_.graph(), {}, {});
  if (!read_only_) {
    store::KeyframeStore::Batch batch(store_);
    store_.replace_loop_edges(mapper_.loops());
    store_.replace_pending_merges(mapper_.pending_merges());
    saved_pending_merges_ = mapper_.pending_merges_version();
    store_.replace_corrected_poses(mapper_.poses());
    store_.clear_map();
    mapper_.take_changed();
    batch.commit();
  }
}

void AggregatorCore::keep_descriptor_cells_in_store() {
  mapper_.keep_descriptor_cells_outside(
      [this](const KeyframeKey& key) { return store_.load_descriptor(key); });
}

void AggregatorCore::recover_from_tables(const Progress& progress) {
  // Every descriptor is in the store: the graph keeps the ring keys, a search reads the cells
  // of the keyframes it shortlists back (Mapper::keep_descriptor_cells_outside).
  store::KeyframeStore::GraphRecords records = store_.load_graph(/*descriptor_cells=*/false);
  const std::size_t total = records.nodes.size();
  // A store of schema version 1 has neither descriptors nor every corrected pose: replay it
  // once (then it has both).
  const bool complete = std::all_of(records.nodes.begin(), records.nodes.end(),
                                    [](const auto& n) { return n.has_descriptor && n.has_pose; });
  if (!complete) {
    records = {};
    replay(progress);
    if (!read_only_) {
      store::KeyframeStore::Batch batch(store_);
      std::vector<std::pair<KeyframeKey, mapping::PlaceDescriptor>> made;
      for (const auto& [key, n] : mapper_.graph().by_key())
        made.emplace_back(key, mapper_.graph().node(n).descriptor);
      std::vector<std::pair<KeyframeKey, const mapping::PlaceDescriptor*>> refs;
      for (const auto& [key, d] : made) refs.emplace_back(key, &d);
      store_.store_descriptors(refs);
      batch.commit();
      keep_descriptor_cells_in_store();
    }
    return;
  }
  std::vector<mapping::KeyframeNode> nodes;
  std::vector<std::pair<KeyframeKey, Eigen::Isometry3d>> map_poses;
  nodes.reserve(total);
  for (auto& r : records.nodes) {
    if (r.map_pose) map_poses.emplace_back(r.node.key, *r.map_pose);
    nodes.push_back(std::move(r.node));
  }
  records.nodes.clear();
  records.nodes.shrink_to_fit();
  mapper_.restore(std::move(nodes), records.loops, records.pending_merges);
  keep_descriptor_cells_in_store();
  saved_pending_merges_ = mapper_.pending_merges_version();
  mapper_.take_changed();
  // The tiles as committed, and the keyframes not fused at their current pose yet.
  const mapping::KeyframeGraph& graph = mapper_.graph();
  std::vector<std::optional<Eigen::Isometry3d>> fused(graph.size());
  for (const auto& [key, pose] : map_poses) {
    const std::int64_t n = graph.find(key);
    if (n >= 0) fused[static_cast<std::size_t>(n)] = pose;
  }
  tiles_.restore(graph, std::move(fused), store_.load_tile_index());
  recovered_ = total;
  if (progress) progress(total, total);
}

IngestResult AggregatorCore::ingest(std::vector<Keyframe>& batch) {
  IngestResult result;
  double t = thread_cpu_seconds();
  // Canonical order, and one keyframe per key (the first received wins).
  std::stable_sort(batch.begin(), batch.end(), canonical_before);
  std::vector<std::size_t> fresh;
  std::set<KeyframeKey> seen;
  for (std::size_t i = 0; i < batch.size(); ++i) {
    if (mapper_.contains(batch[i].key) || !seen.insert(batch[i].key).second) {
      ++result.duplicates;
      continue;
    }
    fresh.push_back(i);
  }
  duplicates_ += result.duplicates;
  double now = thread_cpu_seconds();
  cpu_.sort_s += now - t;
  t = now;
  if (fresh.empty()) {
    batch.clear();
    return result;
  }

  // What the store gives back on a re-read, exactly: the distributions through its encoding,
  // with the covariance regularisation it applies on load (the store keeps the received
  // ones). A live mapper and one that reads evicted keyframes back see the same numbers.
  std::vector<mapping::PlaceDescriptor> descriptors;
  std::vector<std::vector<Distribution>> decoded;
  descriptors.reserve(fresh.size());
  decoded.reserve(fresh.size());
  for (std::size_t i : fresh) {
    const std::string encoded = store::encode_distributions(batch[i].distributions);
    decoded.push_back(store::decode_distributions(encoded.data(), encoded.size(), regularizer()));
    descriptors.push_back(mapper_.describe(decoded.back()));
  }
  now = thread_cpu_seconds();
  cpu_.regularize_s += now - t;
  t = now;

  const auto t0 = std::chrono::steady_clock::now();
  store::KeyframeStore::Batch transaction(store_);
  std::vector<const Keyframe*> to_store;
  std::vector<const mapping::PlaceDescriptor*> described;
  for (std::size_t k = 0; k < fresh.size(); ++k) {
    to_store.push_back(&batch[fresh[k]]);
    described.push_back(&descriptors[k]);
  }
  store_.insert_keyframes(to_store, described);
  now = thread_cpu_seconds();
  cpu_.store_s += now - t;
  t = now;

  const auto t1 = std::chrono::steady_clock::now();
  const std::size_t loops_before = mapper_.loops().size();
  std::vector<mapping::LoopEdge> loops;
  for (std::size_t k = 0; k < fresh.size(); ++k) {
    Keyframe keyframe = std::move(batch[fresh[k]]);
    keyframe.distributions = std::move(decoded[k]);
    result.streams.insert(keyframe.key.stream);
    result.keys.push_back(keyframe.key);
    if (mapper_.add_keyframe(std::move(keyframe), &loops, &descriptors[k]) ==
        mapping::AddStatus::kAdded)
      ++result.added;
  }
  now = thread_cpu_seconds();
  cpu_.add_keyframe_s += now - t;
  t = now;
  result.new_loops = loops.size();
  result.optimization = mapper_.optimize();
  now = thread_cpu_seconds();
  cpu_.optimize_s += now - t;
  t = now;
  save_changes(loops_before);
  transaction.commit();
  cpu_.save_graph_s += thread_cpu_seconds() - t;
  result.store_ms = elapsed_ms(t0) - elapsed_ms(t1);
  result.mapper_ms = elapsed_ms(t1);
  batch.clear();
  return result;
}

std::size_t AggregatorCore::apply_full_pass(const mapping::FullPassProblem& problem) {
  const double t = thread_cpu_seconds();
  mapper_.apply_full_pass(problem);
  store::KeyframeStore::Batch transaction(store_);
  const std::size_t loops = mapper_.loops().size();
  const std::size_t moved = mapper_.graph().size();
  save_changes(loops);
  transaction.commit();
  cpu_.full_pass_apply_s += thread_cpu_seconds() - t;
  return moved;
}

MapUpdate AggregatorCore::update_map(std::size_t max_keyframes, bool persist) {
  MapUpdate out;
  double t = thread_cpu_seconds();
  out.keyframes = tiles_.update(mapper_.graph(), mapper_.cache(), max_keyframes);
  double now = thread_cpu_seconds();
  cpu_.map_fuse_s += now - t;
  t = now;
  // Read-only, the changed tiles stay in memory (the store's would be stale).
  if (read_only_) return out;
  out.tiles = tiles_.updated_tiles();
  if (!persist || (!tiles_.has_changes() && out.keyframes == 0)) return out;
  const mapping::TileMap::Changes changes = tiles_.take_changes();
  const mapping::KeyframeGraph& graph = mapper_.graph();
  std::vector<std::pair<KeyframeKey, std::optional<Eigen::Isometry3d>>> poses;
  poses.reserve(changes.nodes.size());
  for (const auto& [n, pose] : changes.nodes) poses.emplace_back(graph.node(n).key, pose);
  store::KeyframeStore::Batch transaction(store_);
  store_.upsert_tiles(changes.tiles, tiles_.geometry());
  store_.set_map_poses(poses);
  transaction.commit();
  cpu_.map_store_s += thread_cpu_seconds() - t;
  return out;
}

std::vector<std::uint32_t> AggregatorCore::take_moved() {
  std::vector<std::uint32_t> out;
  out.swap(moved_);
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

void AggregatorCore::save_changes(std::size_t first_new) {
  const std::vector<mapping::LoopEdge>& all = mapper_.loops();
  if (first_new < all.size()) {
    store_.insert_loop_edges(std::vector<mapping::LoopEdge>(
        all.begin() + static_cast<std::ptrdiff_t>(first_new), all.end()));
  }
  const mapping::KeyframeGraph& graph = mapper_.graph();
  const mapping::StreamGroups& groups = graph.groups();
  std::vector<store::CorrectedPose> poses;
  for (std::uint32_t n : mapper_.take_changed()) {
    const mapping::KeyframeNode& node = graph.node(n);
    poses.push_back({node.key, node.pose, groups.at(groups.anchor_of(node.stream)).name});
    tiles_.mark(n);
    moved_.push_back(n);
  }
  store_.upsert_corrected_poses(poses);
  // The loops waiting for a merge's confirmation, when they changed (rarely: only loops
  // between groups change them), in the same transaction.
  if (mapper_.pending_merges_version() != saved_pending_merges_) {
    store_.replace_pending_merges(mapper_.pending_merges());
    saved_pending_merges_ = mapper_.pending_merges_version();
  }
}

}  // namespace litamin2::aggregator
