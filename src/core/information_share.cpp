#include "litamin2/core/information_share.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>

namespace litamin2 {

double smallest_information_share(const Matrix6d& part, const Matrix6d& whole) {
  if (!part.allFinite() || !whole.allFinite()) return 0.0;
  const Eigen::LLT<Matrix6d> llt(whole);
  if (llt.info() != Eigen::Success) return 0.0;
  // With whole = L L^T, L^-1 part L^-T has the generalised eigenvalues of (part, whole).
  const Matrix6d left = llt.matrixL().solve(part);
  const Matrix6d scaled = llt.matrixL().solve(left.transpose());
  const Eigen::SelfAdjointEigenSolver<Matrix6d> eig(0.5 * (scaled + scaled.transpose()),
                                                    Eigen::EigenvaluesOnly);
  return eig.eigenvalues()(0);
}

}  // namespace litamin2
