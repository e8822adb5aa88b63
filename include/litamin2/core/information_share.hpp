#pragma once
/// How much of one system's information another holds, direction by direction.

#include "litamin2/core/so3.hpp"

namespace litamin2 {

/// The smallest generalised eigenvalue of (part, whole), two symmetric 6x6 information
/// matrices (Gauss-Newton Hessians of the pose): min over directions v of
/// v^T part v / v^T whole v, the least share of `whole`'s information that `part` holds in any
/// direction. 0 where `whole` is not positive definite or either is not finite.
double smallest_information_share(const Matrix6d& part, const Matrix6d& whole);

}  // namespace litamin2
