#pragma once

#include <glm/vec3.hpp>

namespace spindrift {

/// The eigen-decomposition of a real symmetric 3 × 3 matrix without iterations: the eigenvalue farthest from
/// the other two from the characteristic cubic's trigonometric solution, its eigenvector as the longest cross
/// product of two rows of A − λI (D. Eberly, "A Robust Eigensolver for 3 × 3 Symmetric Matrices", 2014), and
/// the other two pairs by one Jacobi rotation in the plane orthogonal to it. Values and vectors are accurate
/// to rounding, double and triple eigenvalues included (tests/native/test_symmetric_eigen.cpp). It replaced
/// OpenVDB's Jacobi sweeps in the particles' shaping (docs/frame-cost.md, session 43).
struct SymmetricEigen3 {
  glm::dvec3 values;      ///< Ascending.
  glm::dvec3 vectors[3];  ///< Unit and mutually orthogonal; vectors[k] belongs to values[k].
};

/// The matrix is given by its upper triangle: a00, a01, a02, a11, a12, a22. Returns false, and leaves
/// `result` unspecified, when an entry is NaN or infinite; every finite matrix has a decomposition (a
/// matrix that is zero or diagonal gets the axes).
bool symmetricEigen3(double a00, double a01, double a02, double a11, double a12, double a22,
                     SymmetricEigen3& result);

}  // namespace spindrift
