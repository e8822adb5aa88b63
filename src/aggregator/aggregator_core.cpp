#include "litamin2/aggregator/aggregator_core.hpp"

#include "litamin2/core/stopwatch.hpp"

#include <algorithm>

namespace litamin2::aggregator {

const RegularizerConfig& AggregatorCore::regularizer() {
  static const RegularizerConfig config{};
  return config;
}

AggregatorCore::AggregatorCore(const std::string& store_path, store::OpenMode mode,
                               const mapping::MapperConfig& mapper_config,
                               const store::StoreOptions& store_options, const Progress& progress)
    : store_(store::KeyframeStore::open(store_path, mode, store_options)), mapper_(mapper_config) {
  std::vector<Keyframe> keyframes = store_.load_keyframes(regularizer());
  const std::size_t total = keyframes.size();
  for (std::size_t i = 0; i < total; ++i) {
    mapper_.add_keyframe(std::move(keyframes[i]));
    if (progress && ((i + 1) % 100 == 0 || i + 1 == total)) progress(i + 1, total);
  }
  recovered_ = total;
  if (mapper_.optimize().ran && mode != store::OpenMode::kReadOnly) save_graph();
}

IngestResult AggregatorCore::ingest(std::vector<Keyframe>& batch) {
  IngestResult result;
  double t = thread_cpu_seconds();
  // Canonical order, and one keyframe per key (the first received wins).
  std::stable_sort(batch.begin(), batch.end(), canonical_before);
  std::vector<std::size_t> fresh;
  std::vector<const Keyframe*> to_store;
  std::set<KeyframeKey> seen;
  for (std::size_t i = 0; i < batch.size(); ++i) {
    if (mapper_.contains(batch[i].key) || !seen.insert(batch[i].key).second) {
      ++result.duplicates;
      continue;
    }
    fresh.push_back(i);
    to_store.push_back(&batch[i]);
  }
  duplicates_ += result.duplicates;
  double now = thread_cpu_seconds();
  cpu_.sort_s += now - t;
  t = now;
  if (fresh.empty()) {
    batch.clear();
    return result;
  }

  // Durable first: a keyframe the mapper knows is always in the store.
  const auto t0 = std::chrono::steady_clock::now();
  store_.insert_keyframes(to_store);
  result.store_ms = elapsed_ms(t0);
  const auto t1 = std::chrono::steady_clock::now();
  now = thread_cpu_seconds();
  cpu_.store_s += now - t;
  t = now;

  std::vector<mapping::LoopEdge> loops;
  for (std::size_t i : fresh) {
    Keyframe keyframe = std::move(batch[i]);
    for (Distribution& d : keyframe.distributions) {
      const Eigen::Matrix3d raw = d.cov;
      regularize_for_terms(regularizer(), raw, d.cov, d.shape_cov, d.shape_cov_inv);
    }
    now = thread_cpu_seconds();
    cpu_.regularize_s += now - t;
    t = now;
    result.streams.insert(keyframe.key.stream);
    result.keys.push_back(keyframe.key);
    if (mapper_.add_keyframe(std::move(keyframe), &loops) == mapping::AddStatus::kAdded)
      ++result.added;
    now = thread_cpu_seconds();
    cpu_.add_keyframe_s += now - t;
    t = now;
  }
  result.new_loops = loops.size();
  result.optimization = mapper_.optimize();
  now = thread_cpu_seconds();
  cpu_.optimize_s += now - t;
  t = now;
  if (result.optimization.ran || !loops.empty()) save_graph();
  cpu_.save_graph_s += thread_cpu_seconds() - t;
  result.mapper_ms = elapsed_ms(t1);
  batch.clear();
  return result;
}

void AggregatorCore::save_graph() {
  store_.replace_loop_edges(mapper_.loops());
  store_.replace_corrected_poses(mapper_.poses());
}

}  // namespace litamin2::aggregator
