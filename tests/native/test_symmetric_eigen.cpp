// The closed-form eigen-decomposition of a symmetric 3 × 3 matrix (prep/SymmetricEigen.h) that shapes the
// particles' ellipsoids. References the solver did not produce: matrices built as R diag(λ) R^T from chosen
// eigenvalues and random rotations, and OpenVDB's Jacobi sweeps (the solver it replaced) on random
// covariances. Every result is checked for its residual |A v − λ v|, for orthonormal vectors and for NaN and
// infinity; the degenerate matrices each have a test of their own.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

#include <openvdb/math/Mat3.h>
#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/mat3x3.hpp>

#include "prep/SymmetricEigen.h"

namespace spindrift {
namespace {

struct Matrix {
  double a00, a01, a02, a11, a12, a22;

  glm::dmat3 full() const {  // column-major, symmetric
    return glm::dmat3(a00, a01, a02, a01, a11, a12, a02, a12, a22);
  }
  double largestEntry() const {
    return std::max(
        {std::abs(a00), std::abs(a01), std::abs(a02), std::abs(a11), std::abs(a12), std::abs(a22)});
  }
};

Matrix fromFull(const glm::dmat3& m) {
  return {m[0][0], m[1][0], m[2][0], m[1][1], m[2][1], m[2][2]};
}

// R diag(values) R^T.
Matrix withEigenvalues(const glm::dvec3& values, const glm::dmat3& rotation) {
  const glm::dmat3 diagonal(values.x, 0, 0, 0, values.y, 0, 0, 0, values.z);
  return fromFull(rotation * diagonal * glm::transpose(rotation));
}

glm::dmat3 randomRotation(std::mt19937& random) {
  std::normal_distribution<double> normal;
  const glm::dquat q =
      glm::normalize(glm::dquat(normal(random), normal(random), normal(random), normal(random)));
  return glm::mat3_cast(q);
}

SymmetricEigen3 decomposed(const Matrix& m) {
  SymmetricEigen3 result;
  EXPECT_TRUE(symmetricEigen3(m.a00, m.a01, m.a02, m.a11, m.a12, m.a22, result));
  return result;
}

// Finite, ascending values; unit, orthogonal vectors; A v = λ v to `tolerance` of the largest entry.
void expectDecomposes(const Matrix& m, const SymmetricEigen3& result, double tolerance) {
  const double scale = std::max(m.largestEntry(), std::numeric_limits<double>::min());
  for (int k = 0; k < 3; ++k) {
    ASSERT_TRUE(std::isfinite(result.values[k])) << k;
    for (int c = 0; c < 3; ++c)
      ASSERT_TRUE(std::isfinite(result.vectors[k][c])) << k;
    EXPECT_NEAR(glm::length(result.vectors[k]), 1.0, 1e-12) << k;
    for (int j = k + 1; j < 3; ++j)
      EXPECT_NEAR(glm::dot(result.vectors[k], result.vectors[j]), 0.0, 1e-12);
    // Relative to the largest entry, so that the check itself neither overflows nor underflows.
    const glm::dvec3 residual =
        (m.full() / scale) * result.vectors[k] - (result.values[k] / scale) * result.vectors[k];
    EXPECT_LE(glm::length(residual), tolerance) << "eigenvector " << k;
  }
  EXPECT_LE(result.values[0], result.values[1]);
  EXPECT_LE(result.values[1], result.values[2]);
}

TEST(SymmetricEigen, FindsTheChosenEigenvaluesOfRotatedDiagonals) {
  std::mt19937 random(7);
  std::uniform_real_distribution<double> value(-3.0, 3.0);
  for (int trial = 0; trial < 2000; ++trial) {
    glm::dvec3 values(value(random), value(random), value(random));
    const Matrix m = withEigenvalues(values, randomRotation(random));
    std::sort(&values[0], &values[0] + 3);
    const SymmetricEigen3 result = decomposed(m);
    for (int k = 0; k < 3; ++k)
      EXPECT_NEAR(result.values[k], values[k], 1e-13 * 3.0) << trial;
    expectDecomposes(m, result, 1e-12);
  }
}

TEST(SymmetricEigen, AgreesWithOpenVdbsJacobiSweepsOnCovariances) {
  std::mt19937 random(11);
  std::uniform_real_distribution<double> offset(-1.0, 1.0);
  for (int trial = 0; trial < 500; ++trial) {
    // The covariance of a few random points, as the anisotropy's neighbourhoods give.
    glm::dmat3 sum(0.0);
    for (int point = 0; point < 6; ++point) {
      const glm::dvec3 p(offset(random), 0.3 * offset(random), 0.05 * offset(random));
      sum += glm::outerProduct(p, p);
    }
    const Matrix m = fromFull(sum / 6.0);
    const openvdb::math::Mat3d matrix(m.a00, m.a01, m.a02, m.a01, m.a11, m.a12, m.a02, m.a12, m.a22);
    openvdb::math::Mat3d vectors;
    openvdb::math::Vec3d jacobi;
    ASSERT_TRUE(openvdb::math::diagonalizeSymmetricMatrix(matrix, vectors, jacobi));
    std::sort(&jacobi[0], &jacobi[0] + 3);
    const SymmetricEigen3 result = decomposed(m);
    for (int k = 0; k < 3; ++k)
      EXPECT_NEAR(result.values[k], jacobi[k], 1e-12) << trial << " value " << k;
    expectDecomposes(m, result, 1e-12);
  }
}

TEST(SymmetricEigen, ZeroMatrixGetsTheAxes) {
  const SymmetricEigen3 result = decomposed({0, 0, 0, 0, 0, 0});
  EXPECT_EQ(result.values, glm::dvec3(0.0));
  expectDecomposes({0, 0, 0, 0, 0, 0}, result, 0.0);
}

TEST(SymmetricEigen, MultipleOfIdentityHasATripleEigenvalue) {
  const Matrix m{2.5, 0, 0, 2.5, 0, 2.5};
  const SymmetricEigen3 result = decomposed(m);
  EXPECT_EQ(result.values, glm::dvec3(2.5));
  expectDecomposes(m, result, 0.0);
}

TEST(SymmetricEigen, UnsortedDiagonalIsSorted) {
  const Matrix m{3.0, 0, 0, -1.0, 0, 2.0};
  const SymmetricEigen3 result = decomposed(m);
  EXPECT_EQ(result.values, glm::dvec3(-1.0, 2.0, 3.0));
  EXPECT_EQ(result.vectors[0], glm::dvec3(0, 1, 0));
  EXPECT_EQ(result.vectors[2], glm::dvec3(1, 0, 0));
  expectDecomposes(m, result, 0.0);
}

TEST(SymmetricEigen, DoubleEigenvaluesEitherWay) {
  std::mt19937 random(3);
  for (const glm::dvec3& values : {glm::dvec3(1, 1, 2), glm::dvec3(1, 2, 2), glm::dvec3(-1, -1, 0)})
    for (int trial = 0; trial < 200; ++trial) {
      const Matrix m = withEigenvalues(values, randomRotation(random));
      const SymmetricEigen3 result = decomposed(m);
      for (int k = 0; k < 3; ++k)
        EXPECT_NEAR(result.values[k], values[k], 1e-13);
      expectDecomposes(m, result, 1e-12);
    }
}

TEST(SymmetricEigen, RankOneMatrix) {  // all neighbours on a line: one direction, two zero eigenvalues
  std::mt19937 random(5);
  for (int trial = 0; trial < 200; ++trial) {
    const glm::dvec3 n = randomRotation(random)[0];
    const Matrix m = fromFull(glm::outerProduct(n, n));
    const SymmetricEigen3 result = decomposed(m);
    EXPECT_NEAR(result.values[0], 0.0, 1e-14);
    EXPECT_NEAR(result.values[1], 0.0, 1e-14);
    EXPECT_NEAR(result.values[2], 1.0, 1e-14);
    EXPECT_NEAR(std::abs(glm::dot(result.vectors[2], n)), 1.0, 1e-12);
    expectDecomposes(m, result, 1e-12);
  }
}

TEST(SymmetricEigen, NearlyTripleEigenvalueStaysOrthonormal) {
  std::mt19937 random(9);
  std::uniform_real_distribution<double> tiny(-1e-9, 1e-9);
  for (int trial = 0; trial < 200; ++trial) {
    const Matrix m{1.0 + tiny(random), tiny(random), tiny(random),
                   1.0 + tiny(random), tiny(random), 1.0 + tiny(random)};
    expectDecomposes(m, decomposed(m), 1e-12);
  }
}

TEST(SymmetricEigen, HugeAndTinyScalesNeitherOverflowNorUnderflow) {
  std::mt19937 random(13);
  for (const double scale : {1e-300, 1e-160, 1e160, 1e300}) {
    const Matrix unit = withEigenvalues(glm::dvec3(0.2, 0.5, 1.0), randomRotation(random));
    const Matrix m{unit.a00 * scale, unit.a01 * scale, unit.a02 * scale,
                   unit.a11 * scale, unit.a12 * scale, unit.a22 * scale};
    const SymmetricEigen3 result = decomposed(m);
    EXPECT_NEAR(result.values[2] / scale, 1.0, 1e-12) << scale;
    expectDecomposes(m, result, 1e-12);
  }
}

TEST(SymmetricEigen, NotFiniteEntriesAreRefused) {
  SymmetricEigen3 result;
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  EXPECT_FALSE(symmetricEigen3(nan, 0, 0, 1, 0, 1, result));
  EXPECT_FALSE(symmetricEigen3(1, 0, inf, 1, 0, 1, result));
  EXPECT_FALSE(symmetricEigen3(1, 0, 0, 1, 0, -inf, result));
}

}  // namespace
}  // namespace spindrift
