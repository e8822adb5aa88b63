// Derivatives of the LiTAMIN2 cost terms against central finite differences, at random poses
// and covariances including nearly flat ones: a wrong sign or a missing term fails here.

#include "litamin2/core/cov_term.hpp"
#include "litamin2/core/covariance_regularizer.hpp"
#include "litamin2/core/icp_term.hpp"
#include "litamin2/core/rank_one_update.hpp"
#include "litamin2/core/robust_weight.hpp"
#include "litamin2/core/so3.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace litamin2 {
namespace {

using Vector6d = Eigen::Matrix<double, 6, 1>;

struct Random {
  std::mt19937 engine{12345};
  double uniform(double a, double b) {
    return std::uniform_real_distribution<double>(a, b)(engine);
  }
  Eigen::Vector3d vector(double scale) {
    return Eigen::Vector3d(uniform(-scale, scale), uniform(-scale, scale), uniform(-scale, scale));
  }
  Eigen::Matrix3d rotation() { return so3_exp(vector(M_PI)); }
  /// Covariance with eigenvalues spread by `flatness` (1e-4 = a wall), regularised as the
  /// voxeliser does.
  Eigen::Matrix3d covariance(double flatness, Eigen::Matrix3d* inverse) {
    const Eigen::Matrix3d basis = rotation();
    const Eigen::Vector3d values(uniform(0.2, 1.0), uniform(0.2, 1.0),
                                 flatness * uniform(0.5, 1.0));
    Eigen::Matrix3d cov = basis * values.asDiagonal() * basis.transpose();
    Eigen::Matrix3d inv;
    regularize_covariance(RegularizerConfig{}, cov, inv);
    *inverse = inv;
    return cov;
  }
};

double cov_f(const Eigen::Matrix3d& rotation, const Eigen::Matrix3d& cp,
             const Eigen::Matrix3d& cp_inv, const Eigen::Matrix3d& cq,
             const Eigen::Matrix3d& cq_inv) {
  const Eigen::Matrix3d m = rotation * cp_inv * rotation.transpose();
  const Eigen::Matrix3d n = rotation * cp * rotation.transpose();
  return (m * cq).trace() + (cq_inv * n).trace() - 6.0;
}

class CovTermTest : public ::testing::TestWithParam<double> {};

TEST_P(CovTermTest, GradientAndHessianMatchFiniteDifferences) {
  Random rnd;
  const double flatness = GetParam();
  for (int trial = 0; trial < 50; ++trial) {
    Eigen::Matrix3d cp_inv, cq_inv;
    const Eigen::Matrix3d cp = rnd.covariance(flatness, &cp_inv);
    const Eigen::Matrix3d cq = rnd.covariance(flatness, &cq_inv);
    const Eigen::Matrix3d r0 = rnd.rotation();
    auto f = [&](const Eigen::Vector3d& phi) {
      return cov_f(so3_exp(phi) * r0, cp, cp_inv, cq, cq_inv);
    };
    const CovShape shape =
        evaluate_cov_shape(r0 * cp_inv * r0.transpose(), r0 * cp * r0.transpose(), cq, cq_inv);
    const double scale = std::max(1.0, std::abs(shape.f));
    EXPECT_NEAR(shape.f, f(Eigen::Vector3d::Zero()), 1e-9 * scale);

    const double h = 1e-5;
    for (int i = 0; i < 3; ++i) {
      const Eigen::Vector3d e = Eigen::Vector3d::Unit(i) * h;
      const double numeric = (f(e) - f(-e)) / (2 * h);
      EXPECT_NEAR(shape.gradient(i), numeric, 1e-5 * scale) << "gradient " << i;
    }
    const double h2 = 1e-4;
    for (int i = 0; i < 3; ++i) {
      for (int j = 0; j < 3; ++j) {
        const Eigen::Vector3d a = Eigen::Vector3d::Unit(i) * h2;
        const Eigen::Vector3d b = Eigen::Vector3d::Unit(j) * h2;
        const double numeric = (f(a + b) - f(a - b) - f(-a + b) + f(-a - b)) / (4 * h2 * h2);
        EXPECT_NEAR(shape.hessian(i, j), numeric, 1e-4 * scale) << "hessian " << i << j;
      }
    }
    EXPECT_TRUE(shape.hessian.isApprox(shape.hessian.transpose(), 1e-12));
  }
}

INSTANTIATE_TEST_SUITE_P(RoundAndFlat, CovTermTest, ::testing::Values(1.0, 0.05, 1e-4));

TEST(CovTerm, ZeroForIdenticalShapesAndTranslationFree) {
  Random rnd;
  Eigen::Matrix3d cov_inv;
  const Eigen::Matrix3d cov = rnd.covariance(0.1, &cov_inv);
  const CovShape shape = evaluate_cov_shape(cov_inv, cov, cov, cov_inv);
  EXPECT_NEAR(shape.f, 0.0, 1e-9);
  EXPECT_LT(shape.gradient.norm(), 1e-8);
  // Rotating a flat source away from the target increases f (symmetric KL is >= 0).
  const Eigen::Matrix3d r = so3_exp(Eigen::Vector3d(0.3, 0.0, 0.0));
  const CovShape rotated =
      evaluate_cov_shape(r * cov_inv * r.transpose(), r * cov * r.transpose(), cov, cov_inv);
  EXPECT_GT(rotated.f, 0.0);
}

/// A source mean p at a random pose and the precision of Eq. 3 from two nearly flat covariances.
struct IcpCase {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  Eigen::Vector3d p;
  Eigen::Matrix3d precision;
};

IcpCase random_icp_case(Random& rnd) {
  IcpCase c;
  c.pose.linear() = rnd.rotation();
  c.pose.translation() = rnd.vector(20.0);
  c.p = rnd.vector(30.0);
  Eigen::Matrix3d cp_inv, cq_inv;
  const Eigen::Matrix3d cp = rnd.covariance(1e-3, &cp_inv);
  const Eigen::Matrix3d cq = rnd.covariance(1e-3, &cq_inv);
  c.precision = combined_precision(cq, c.pose.linear() * cp * c.pose.linear().transpose(), 1e-6);
  return c;
}

TEST(IcpTerm, GradientMatchesFiniteDifferencesAndHessianIsGaussNewton) {
  Random rnd;
  for (int trial = 0; trial < 50; ++trial) {
    const IcpCase icp_case = random_icp_case(rnd);
    const Eigen::Isometry3d& pose = icp_case.pose;
    const Eigen::Vector3d& p = icp_case.p;
    const Eigen::Matrix3d& precision = icp_case.precision;
    EXPECT_NEAR(precision.norm(), 1.0, 1e-12);
    const Eigen::Vector3d q = pose * p + rnd.vector(0.5);

    auto energy = [&](const Vector6d& xi) {
      const Eigen::Vector3d r = q - apply_left_update(xi, pose) * p;
      return r.dot(precision * r);
    };
    const IcpTerm term = evaluate_icp_term(q, pose * p, precision);
    EXPECT_NEAR(term.energy, energy(Vector6d::Zero()), 1e-9);
    const double h = 1e-6;
    for (int i = 0; i < 6; ++i) {
      const Vector6d e = Vector6d::Unit(i) * h;
      const double numeric = (energy(e) - energy(-e)) / (2 * h);
      EXPECT_NEAR(term.gradient(i), numeric, 1e-5 * std::max(1.0, std::abs(numeric)))
          << "gradient " << i;
    }

    // At a zero residual the Gauss-Newton Hessian is the exact one.
    const Eigen::Vector3d q0 = pose * p;
    auto energy0 = [&](const Vector6d& xi) {
      const Eigen::Vector3d r = q0 - apply_left_update(xi, pose) * p;
      return r.dot(precision * r);
    };
    const IcpTerm at_zero = evaluate_icp_term(q0, q0, precision);
    const double h2 = 1e-4;
    for (int i = 0; i < 6; ++i) {
      for (int j = 0; j < 6; ++j) {
        const Vector6d a = Vector6d::Unit(i) * h2;
        const Vector6d b = Vector6d::Unit(j) * h2;
        const double numeric =
            (energy0(a + b) - energy0(a - b) - energy0(-a + b) + energy0(-a - b)) / (4 * h2 * h2);
        EXPECT_NEAR(at_zero.hessian(i, j), numeric, 1e-4 * std::max(1.0, std::abs(numeric)))
            << "hessian " << i << j;
      }
    }
  }
}

/// Exact equality where the compiler may not fuse a multiply and an add (no FMA in the target:
/// the portable build), where the written-out forms and Eigen's are the same operations;
/// within rounding otherwise.
void expect_same_bits(const Matrix6d& written_out, const Matrix6d& dense) {
  for (int i = 0; i < 6; ++i) {
    for (int j = 0; j < 6; ++j) {
#if defined(__FMA__)
      EXPECT_NEAR(written_out(i, j), dense(i, j), 1e-12 * std::max(1.0, std::abs(dense(i, j))))
          << i << "," << j;
#else
      EXPECT_EQ(written_out(i, j), dense(i, j)) << i << "," << j;
#endif
    }
  }
}

TEST(IcpTerm, TheWrittenOutHessianIsTheDenseProductBitForBit) {
  Random rnd;
  for (int trial = 0; trial < 200; ++trial) {
    const IcpCase icp_case = random_icp_case(rnd);
    const Eigen::Vector3d y = icp_case.pose * icp_case.p;
    Eigen::Matrix<double, 3, 6> jacobian;
    jacobian.leftCols<3>() << 0.0, -y.z(), y.y(), y.z(), 0.0, -y.x(), -y.y(), y.x(), 0.0;
    jacobian.rightCols<3>() = -Eigen::Matrix3d::Identity();
    const Matrix6d dense = 2.0 * jacobian.transpose() * icp_case.precision * jacobian;
    expect_same_bits(icp_hessian(y, icp_case.precision), dense);
  }
}

TEST(IcpTerm, TheLowerTriangleSumIsTheWrittenOutHessiansBitForBit) {
  Random rnd;
  Matrix6d full = Matrix6d::Zero();
  Matrix6d lower = Matrix6d::Zero();
  for (int trial = 0; trial < 200; ++trial) {
    const IcpCase icp_case = random_icp_case(rnd);
    const Eigen::Vector3d y = icp_case.pose * icp_case.p;
    const double weight = rnd.uniform(0.0, 2.0);
    full += weight * icp_hessian(y, icp_case.precision);
    add_icp_hessian_lower(lower, y, icp_case.precision, weight);
  }
  // The lower triangle is the full sum's, bit for bit; the strictly upper one is left alone.
  for (int i = 0; i < 6; ++i) {
    for (int j = 0; j < 6; ++j) {
      if (i >= j) {
        EXPECT_EQ(lower(i, j), full(i, j)) << i << "," << j;
      } else {
        EXPECT_EQ(lower(i, j), 0.0) << i << "," << j;
      }
    }
  }
}

TEST(RankOneUpdate, TheWrittenOutUpdateIsEigensBitForBit) {
  Random rnd;
  Matrix6d eigens = Matrix6d::Zero();
  Matrix6d written_out = Matrix6d::Zero();
  Matrix6d sum = Matrix6d::Zero();
  for (int trial = 0; trial < 200; ++trial) {
    Vector6d g;
    g << rnd.vector(10.0), rnd.vector(1.0);
    const double alpha = rnd.uniform(0.0, 2.0);
    eigens.selfadjointView<Eigen::Upper>().rankUpdate(g, alpha);
    add_upper_rank_one(written_out, g, alpha);
    sum += alpha * g * g.transpose();
  }
  expect_same_bits(written_out, eigens);
  // The upper triangle is the sum of alpha g g^T; the lower one is left as it was.
  for (int i = 0; i < 6; ++i) {
    for (int j = 0; j < 6; ++j) {
      if (j >= i) {
        EXPECT_NEAR(written_out(i, j), sum(i, j), 1e-9 * std::abs(sum(i, j))) << i << "," << j;
      } else {
        EXPECT_EQ(written_out(i, j), 0.0) << i << "," << j;
      }
    }
  }
}

TEST(RobustWeight, UsesSigmaSquared) {
  EXPECT_DOUBLE_EQ(robust_weight(0.0, 0.5), 1.0);
  EXPECT_DOUBLE_EQ(robust_weight(0.25, 0.5), 0.5);  // E = sigma^2 halves the weight
  EXPECT_DOUBLE_EQ(robust_weight(9.0, 3.0), 0.5);
  EXPECT_LT(robust_weight(100.0, 0.5), 0.01);
}

TEST(RobustWeight, CurvatureIsTheDerivativeOfTheWeightUpToSigmaSquared) {
  // w(E) is rho'(E) for rho(E) = sigma^2 ln(1 + E / sigma^2); the curvature factor is -w'(E).
  const double sigma = 0.1, sigma_sq = sigma * sigma;
  for (const double energy : {0.0, 1e-4, 3e-3, 0.0099}) {
    const double h = 1e-8;
    const double dw =
        (robust_weight(energy + h, sigma) - robust_weight(energy - h, sigma)) / (2 * h);
    EXPECT_NEAR(robust_weight_curvature(energy, sigma), -dw, 1e-5 / sigma_sq) << energy;
  }
  // Beyond sigma^2 it is capped at w / (2 E), continuously.
  EXPECT_NEAR(robust_weight_curvature(sigma_sq, sigma), 0.25 / sigma_sq, 1e-12);
  EXPECT_NEAR(robust_weight_curvature(sigma_sq * (1 + 1e-9), sigma), 0.25 / sigma_sq, 1e-6);
  for (const double energy : {0.02, 0.5, 30.0}) {
    const double w = robust_weight(energy, sigma);
    EXPECT_DOUBLE_EQ(robust_weight_curvature(energy, sigma), w / (2 * energy));
    EXPECT_LT(robust_weight_curvature(energy, sigma), w * w / sigma_sq * 2);
  }
}

TEST(RobustWeight, NewtonHessianOfTheRobustIcpTermMatchesFiniteDifferences) {
  // d2 rho(E(xi)) = w d2E + w'(E) g g^T (chain rule): the part beyond the weighted Hessian is
  // -c g g^T with c = robust_weight_curvature, for any E below sigma^2. Past sigma^2 the capped
  // correspondence Hessian w H - c g g^T keeps no negative curvature (Gauss-Newton H).
  Random rnd;
  const double sigma = 0.1;
  int capped = 0;
  for (int trial = 0; trial < 40; ++trial) {
    const IcpCase icp_case = random_icp_case(rnd);
    const Eigen::Isometry3d& pose = icp_case.pose;
    const Eigen::Vector3d& p = icp_case.p;
    const Eigen::Matrix3d& precision = icp_case.precision;
    // Residuals from 0.01 to 0.5 m: energies on both sides of sigma^2 = 0.01.
    const Eigen::Vector3d offset = rnd.vector(1.0).normalized() * rnd.uniform(0.01, 0.5);
    const Eigen::Vector3d q = pose * p + offset;
    auto energy = [&](const Vector6d& xi) {
      const Eigen::Vector3d r = q - apply_left_update(xi, pose) * p;
      return r.dot(precision * r);
    };
    auto rho = [&](const Vector6d& xi) {
      return sigma * sigma * std::log1p(energy(xi) / (sigma * sigma));
    };
    const IcpTerm term = evaluate_icp_term(q, pose * p, precision);
    const double w = robust_weight(term.energy, sigma);
    const double c = robust_weight_curvature(term.energy, sigma);
    if (term.energy > sigma * sigma) {
      ++capped;
      const Matrix6d newton = w * term.hessian - c * term.gradient * term.gradient.transpose();
      const Eigen::SelfAdjointEigenSolver<Matrix6d> eig(newton);
      EXPECT_GT(eig.eigenvalues().minCoeff(), -1e-9 * std::max(1.0, newton.norm()));
      continue;
    }
    // Small steps: 1e-6 rad moves the point 30 um against residuals of 1-100 mm.
    const double h = 1e-6;
    for (int i = 0; i < 6; ++i) {
      for (int j = 0; j < 6; ++j) {
        const Vector6d a = Vector6d::Unit(i) * h;
        const Vector6d b = Vector6d::Unit(j) * h;
        auto second = [&](const auto& f) {
          return (f(a + b) - f(a - b) - f(-a + b) + f(-a - b)) / (4 * h * h);
        };
        const double numeric = second(rho) - w * second(energy);
        const double expected = -c * term.gradient(i) * term.gradient(j);
        EXPECT_NEAR(expected, numeric, 1e-3 * std::max(1.0, std::abs(expected)))
            << "entry " << i << j << ", E " << term.energy;
      }
    }
  }
  EXPECT_GT(capped, 5);
  EXPECT_LT(capped, 35);
}

TEST(Regularizer, FlatCovarianceGetsBoundedInverse) {
  Eigen::Matrix3d cov = Eigen::Vector3d(1.0, 1.0, 0.0).asDiagonal();
  Eigen::Matrix3d inv;
  RegularizerConfig config;
  regularize_covariance(config, cov, inv);
  EXPECT_TRUE((cov * inv).isApprox(Eigen::Matrix3d::Identity(), 1e-9));
  EXPECT_NEAR(cov(2, 2), config.min_eigen_ratio, 1e-12);
  config.method = RegularizationMethod::kPlane;
  cov = Eigen::Vector3d(4.0, 2.0, 1e-9).asDiagonal();
  regularize_covariance(config, cov, inv);
  EXPECT_NEAR(cov(0, 0), 4.0, 1e-12);
  EXPECT_NEAR(cov(1, 1), 4.0, 1e-12);
  EXPECT_NEAR(cov(2, 2), 4.0 * config.plane_epsilon, 1e-12);
  EXPECT_TRUE((cov * inv).isApprox(Eigen::Matrix3d::Identity(), 1e-9));
}

TEST(IcpTerm, CombinedIsotropyIsSmallForPlanesAndOneForSpheres) {
  const Eigen::Matrix3d plane = Eigen::Vector3d(1.0, 1.0, 1e-4).asDiagonal();
  const Eigen::Matrix3d line = Eigen::Vector3d(1e-4, 1.0, 1e-4).asDiagonal();
  const Eigen::Matrix3d sphere = Eigen::Matrix3d::Identity();
  EXPECT_NEAR(combined_isotropy(plane, plane, 0.0), 1e-4, 1e-12);
  EXPECT_NEAR(combined_isotropy(line, line, 0.0), 1e-4, 1e-12);
  EXPECT_NEAR(combined_isotropy(sphere, sphere, 1e-6), 1.0, 1e-12);
  // A plane matched to a round distribution is round enough to be gated.
  EXPECT_GT(combined_isotropy(sphere, plane, 0.0), 0.4);
}

TEST(IcpTerm, RoundTestAgreesWithTheEigenvalues) {
  // combined_is_round decides most cases from the trace and determinant: it must agree with
  // the eigenvalue ratio everywhere, including near the limit.
  std::mt19937 rng(17);
  std::uniform_real_distribution<double> log_scale(-5.0, 0.5);
  std::normal_distribution<double> n(0.0, 1.0);
  auto random_covariance = [&] {
    const Eigen::Matrix3d r = so3_exp(Eigen::Vector3d(n(rng), n(rng), n(rng)));
    const Eigen::Vector3d eigenvalues(std::pow(10.0, log_scale(rng)),
                                      std::pow(10.0, log_scale(rng)),
                                      std::pow(10.0, log_scale(rng)));
    return Eigen::Matrix3d(r * eigenvalues.asDiagonal() * r.transpose());
  };
  int round = 0, flat = 0;
  for (const double limit : {0.01, 0.05, 0.2, 0.9}) {
    for (int i = 0; i < 20000; ++i) {
      const Eigen::Matrix3d cq = random_covariance();
      const Eigen::Matrix3d cp = random_covariance();
      const bool expected = combined_isotropy(cq, cp, 1e-6) > limit;
      ASSERT_EQ(combined_is_round(cq, cp, 1e-6, limit), expected)
          << "limit " << limit << ", isotropy " << combined_isotropy(cq, cp, 1e-6);
      (expected ? round : flat)++;
    }
  }
  EXPECT_GT(round, 10000);
  EXPECT_GT(flat, 10000);
}

}  // namespace
}  // namespace litamin2
