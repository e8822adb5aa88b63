#pragma once
/// The rank-one update M += alpha g g^T of a 6x6 matrix's upper triangle, as
/// `M.selfadjointView<Eigen::Upper>().rankUpdate(g, alpha)` does it (column i, rows 0..i, each
/// entry plus (alpha g_i) g_r) but written out: Eigen's runs as a call through its BLAS-like
/// layer with run-time sizes, ~4x the operations for a 6-vector. Registration adds one per
/// correspondence and Newton iteration (the robust weight's curvature, robust_weight.hpp).

#include "litamin2/core/so3.hpp"

namespace litamin2 {

inline void add_upper_rank_one(Matrix6d& m, const Eigen::Matrix<double, 6, 1>& g, double alpha) {
  for (int i = 0; i < 6; ++i) {
    const double scaled = alpha * g(i);
    for (int r = 0; r <= i; ++r) m(r, i) += scaled * g(r);
  }
}

}  // namespace litamin2
