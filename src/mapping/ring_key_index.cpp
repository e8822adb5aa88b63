#include "litamin2/mapping/ring_key_index.hpp"

#include <nanoflann.hpp>

#include <algorithm>
#include <limits>

namespace litamin2::mapping {
namespace {

/// nanoflann's view of the ring keys: node i's key is keys[i * dims .. (i + 1) * dims).
struct RingKeys {
  std::size_t dims = 0;
  std::vector<float> keys;

  std::size_t kdtree_get_point_count() const { return dims ? keys.size() / dims : 0; }
  float kdtree_get_pt(std::size_t i, std::size_t d) const { return keys[i * dims + d]; }
  template <class Box>
  bool kdtree_get_bbox(Box&) const {
    return false;
  }
};

using Metric = nanoflann::L2_Simple_Adaptor<float, RingKeys, double>;
using Tree = nanoflann::KDTreeSingleIndexDynamicAdaptor<Metric, RingKeys, -1, std::uint32_t>;

/// Keeps the k best eligible nodes by (exact distance, before). The distance nanoflann passes
/// (float differences) is only used to prune; worstDist() is widened so that rounding can
/// never prune a node the exact comparison would keep.
class EligibleKnn {
 public:
  using DistanceType = double;
  using IndexType = std::uint32_t;

  EligibleKnn(std::size_t k, const RingKeys& keys, const std::vector<float>& query,
              const std::function<bool(std::uint32_t)>& eligible,
              const std::function<bool(std::uint32_t, std::uint32_t)>& before)
      : k_(k), keys_(keys), query_(query), eligible_(eligible), before_(before) {}

  void init() { items_.clear(); }
  std::size_t size() const { return items_.size(); }
  bool full() const { return items_.size() >= k_; }

  bool addPoint(double, std::uint32_t node) {
    if (!eligible_(node)) return true;
    const std::pair<double, std::uint32_t> item{exact(node), node};
    auto better = [&](const auto& a, const auto& b) {
      return a.first < b.first || (a.first == b.first && before_(a.second, b.second));
    };
    if (full() && !better(item, items_.back())) return true;
    items_.insert(std::upper_bound(items_.begin(), items_.end(), item, better), item);
    if (items_.size() > k_) items_.pop_back();
    return true;
  }

  double worstDist() const {
    if (!full()) return std::numeric_limits<double>::infinity();
    return items_.back().first * (1.0 + 1e-6) + 1e-9;
  }

  std::vector<std::uint32_t> nodes() const {
    std::vector<std::uint32_t> out;
    out.reserve(items_.size());
    for (const auto& item : items_) out.push_back(item.second);
    return out;
  }

  double exact(std::uint32_t node) const {
    double sum = 0.0;
    for (std::size_t d = 0; d < keys_.dims; ++d) {
      const double diff = double(query_[d]) - keys_.kdtree_get_pt(node, d);
      sum += diff * diff;
    }
    return sum;
  }

 private:
  std::size_t k_;
  const RingKeys& keys_;
  const std::vector<float>& query_;
  const std::function<bool(std::uint32_t)>& eligible_;
  const std::function<bool(std::uint32_t, std::uint32_t)>& before_;
  std::vector<std::pair<double, std::uint32_t>> items_;
};

}  // namespace

struct RingKeyIndex::Impl {
  explicit Impl(int dimensions)
      : keys{static_cast<std::size_t>(dimensions), {}},
        tree(dimensions, keys, nanoflann::KDTreeSingleIndexAdaptorParams(16)) {}
  RingKeys keys;
  Tree tree;
};

RingKeyIndex::RingKeyIndex(int dimensions) : impl_(std::make_unique<Impl>(dimensions)) {}
RingKeyIndex::~RingKeyIndex() = default;
RingKeyIndex::RingKeyIndex(RingKeyIndex&&) noexcept = default;
RingKeyIndex& RingKeyIndex::operator=(RingKeyIndex&&) noexcept = default;

void RingKeyIndex::add(const std::vector<float>& ring_key) {
  RingKeys& keys = impl_->keys;
  const auto node = static_cast<std::uint32_t>(size());
  for (std::size_t d = 0; d < keys.dims; ++d)
    keys.keys.push_back(d < ring_key.size() ? ring_key[d] : 0.0f);
  impl_->tree.addPoints(node, node);
}

std::size_t RingKeyIndex::size() const {
  return impl_->keys.kdtree_get_point_count();
}

std::vector<std::uint32_t> RingKeyIndex::nearest(
    const std::vector<float>& ring_key, std::size_t k,
    const std::function<bool(std::uint32_t)>& eligible,
    const std::function<bool(std::uint32_t, std::uint32_t)>& before) const {
  if (k == 0 || size() == 0) return {};
  std::vector<float> query(impl_->keys.dims, 0.0f);
  std::copy_n(ring_key.begin(), std::min(ring_key.size(), query.size()), query.begin());
  EligibleKnn result(k, impl_->keys, query, eligible, before);
  impl_->tree.findNeighbors(result, query.data(), nanoflann::SearchParams());
  return result.nodes();
}

double RingKeyIndex::distance(const std::vector<float>& ring_key, std::uint32_t node) const {
  double sum = 0.0;
  for (std::size_t d = 0; d < impl_->keys.dims; ++d) {
    const double diff =
        double(d < ring_key.size() ? ring_key[d] : 0.0f) - impl_->keys.kdtree_get_pt(node, d);
    sum += diff * diff;
  }
  return sum;
}

}  // namespace litamin2::mapping
