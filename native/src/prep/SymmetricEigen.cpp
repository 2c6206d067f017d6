#include "prep/SymmetricEigen.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

namespace spindrift {
namespace {

// A symmetric matrix by its upper triangle.
struct Symmetric {
  double a00, a01, a02, a11, a12, a22;

  glm::dvec3 times(const glm::dvec3& v) const {
    return {a00 * v.x + a01 * v.y + a02 * v.z, a01 * v.x + a11 * v.y + a12 * v.z,
            a02 * v.x + a12 * v.y + a22 * v.z};
  }
};

// The eigenvector of `value` when it is a simple eigenvalue: A − λI has rank 2, so the cross product of two
// of its rows is orthogonal to both and spans its null space. The longest of the three is the best
// conditioned.
glm::dvec3 vectorOfSimpleValue(const Symmetric& a, double value) {
  const glm::dvec3 row0(a.a00 - value, a.a01, a.a02), row1(a.a01, a.a11 - value, a.a12),
      row2(a.a02, a.a12, a.a22 - value);
  const glm::dvec3 crosses[3] = {glm::cross(row0, row1), glm::cross(row0, row2), glm::cross(row1, row2)};
  int longest = 0;
  double longestSquared = glm::dot(crosses[0], crosses[0]);
  for (int k = 1; k < 3; ++k) {
    const double squared = glm::dot(crosses[k], crosses[k]);
    if (squared > longestSquared) longest = k, longestSquared = squared;
  }
  // Zero only where A − λI has rank below 2, i.e. λ is a triple eigenvalue and A a multiple of I, which the
  // caller handles before: any unit vector would do.
  if (!(longestSquared > 0.0)) return {1.0, 0.0, 0.0};
  return crosses[longest] / std::sqrt(longestSquared);
}

// Two unit vectors that make `w` (unit) an orthonormal basis, built from its larger components.
void orthogonalComplement(const glm::dvec3& w, glm::dvec3& u, glm::dvec3& v) {
  if (std::abs(w.x) > std::abs(w.y))
    u = glm::dvec3(-w.z, 0.0, w.x) / std::sqrt(w.x * w.x + w.z * w.z);
  else
    u = glm::dvec3(0.0, w.z, -w.y) / std::sqrt(w.y * w.y + w.z * w.z);
  v = glm::cross(w, u);
}

// The other two eigenpairs, given one unit eigenvector `first`: in the plane (u, v) orthogonal to it, A acts
// as the symmetric 2 × 2 matrix M = [u v]^T A [u v], diagonalised by one Jacobi rotation (Golub and Van Loan,
// 8.4.2). Unlike a null vector of M − λI for a λ from the cubic, whose error grows as sqrt(ε) near a double
// eigenvalue, this keeps close eigenvalues to rounding and their vectors orthonormal.
void pairInComplement(const Symmetric& a, const glm::dvec3& first, double values[2], glm::dvec3 vectors[2]) {
  glm::dvec3 u, v;
  orthogonalComplement(first, u, v);
  const glm::dvec3 au = a.times(u), av = a.times(v);
  const double m00 = glm::dot(u, au), m01 = glm::dot(u, av), m11 = glm::dot(v, av);
  if (m01 == 0.0) {
    values[0] = m00, values[1] = m11;
    vectors[0] = u, vectors[1] = v;
    return;
  }
  const double tau = (m11 - m00) / (2.0 * m01);
  // The smaller of the two rotations, tan θ = sign(τ) / (|τ| + sqrt(1 + τ²)); past 1e100, where τ² would
  // overflow, 1 / 2τ to rounding.
  const double magnitude = std::abs(tau);
  const double t = (tau >= 0.0 ? 1.0 : -1.0) /
                   (magnitude < 1e100 ? magnitude + std::sqrt(1.0 + tau * tau) : 2.0 * magnitude);
  const double c = 1.0 / std::sqrt(1.0 + t * t), s = t * c;
  values[0] = m00 - t * m01, values[1] = m11 + t * m01;
  vectors[0] = c * u - s * v, vectors[1] = s * u + c * v;
}

}  // namespace

bool symmetricEigen3(double a00, double a01, double a02, double a11, double a12, double a22,
                     SymmetricEigen3& result) {
  const double largest =
      std::max({std::abs(a00), std::abs(a01), std::abs(a02), std::abs(a11), std::abs(a12), std::abs(a22)});
  if (!std::isfinite(largest)) return false;
  result.vectors[0] = {1.0, 0.0, 0.0};
  result.vectors[1] = {0.0, 1.0, 0.0};
  result.vectors[2] = {0.0, 0.0, 1.0};
  if (largest == 0.0) {
    result.values = glm::dvec3(0.0);
    return true;
  }
  // Scaled to entries in [-1, 1], so that neither the squares nor the cubes below overflow or underflow.
  const Symmetric a{a00 / largest, a01 / largest, a02 / largest, a11 / largest, a12 / largest, a22 / largest};
  const double offDiagonal = a.a01 * a.a01 + a.a02 * a.a02 + a.a12 * a.a12;
  if (offDiagonal == 0.0) {
    // Diagonal: the axes, sorted by their values.
    int order[3] = {0, 1, 2};
    const double diagonal[3] = {a.a00, a.a11, a.a22};
    std::sort(order, order + 3, [&](int i, int j) { return diagonal[i] < diagonal[j]; });
    for (int k = 0; k < 3; ++k) {
      result.values[k] = diagonal[order[k]] * largest;
      result.vectors[k] = glm::dvec3(0.0);
      result.vectors[k][order[k]] = 1.0;
    }
    return true;
  }
  // A = qI + pB with tr B = 0 and tr B² = 6: B's eigenvalues are 2 cos(θ + 2πk/3), cos 3θ = det B / 2.
  const double q = (a.a00 + a.a11 + a.a22) / 3.0;
  const double b00 = a.a00 - q, b11 = a.a11 - q, b22 = a.a22 - q;
  const double p = std::sqrt((b00 * b00 + b11 * b11 + b22 * b22 + 2.0 * offDiagonal) / 6.0);
  const double c00 = b11 * b22 - a.a12 * a.a12, c01 = a.a01 * b22 - a.a12 * a.a02,
               c02 = a.a01 * a.a12 - b11 * a.a02;
  const double halfDeterminant =
      std::clamp(0.5 * (b00 * c00 - a.a01 * c01 + a.a02 * c02) / (p * p * p), -1.0, 1.0);
  const double angle = std::acos(halfDeterminant) / 3.0;
  constexpr double kTwoThirdsPi = 2.09439510239319549;
  // cos 3θ ≥ 0 puts the middle value nearer the smallest: the largest is the one apart, and its eigenvector
  // is the well-conditioned one to find first (and the smallest's otherwise). Its value is recomputed as the
  // Rayleigh quotient, as accurate as the vector.
  const double apart = q + 2.0 * p * std::cos(halfDeterminant >= 0.0 ? angle : angle + kTwoThirdsPi);
  double pairValues[2];
  glm::dvec3 pairVectors[2];
  const glm::dvec3 first = vectorOfSimpleValue(a, apart);
  pairInComplement(a, first, pairValues, pairVectors);
  const double values[3] = {glm::dot(first, a.times(first)), pairValues[0], pairValues[1]};
  const glm::dvec3 vectors[3] = {first, pairVectors[0], pairVectors[1]};
  // Ascending, by three compare-exchanges.
  int order[3] = {0, 1, 2};
  const auto exchange = [&](int i, int j) {
    if (values[order[j]] < values[order[i]]) std::swap(order[i], order[j]);
  };
  exchange(0, 1);
  exchange(1, 2);
  exchange(0, 1);
  for (int k = 0; k < 3; ++k) {
    result.values[k] = values[order[k]] * largest;
    result.vectors[k] = vectors[order[k]];
  }
  return true;
}

}  // namespace spindrift
