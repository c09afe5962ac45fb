#pragma once
// The mass, centre of mass and inertia of a homogeneous solid bounded by a closed triangle
// mesh, exactly (the mesh's polyhedron, not an approximation of it).
//
// Each triangle (a, b, c), oriented outward, and the origin span a tetrahedron of signed volume
//   V_t = det[a b c] / 6,
// and the second moment (covariance) of a tetrahedron with a vertex at the origin is
//   C_t = det[a b c] A C0 A^T,   A = [a b c] (columns),   C0 = [[2,1,1],[1,2,1],[1,1,2]] / 120
// (the canonical tetrahedron's). Summed over the triangles the signs cancel outside the solid,
// so that V = sum V_t, the first moment sum V_t (a + b + c) / 4, and C = rho sum C_t about the
// origin; moved to the centre x_c, C_c = C - m x_c x_c^T, and the inertia tensor is
//   I = trace(C_c) 1 - C_c
// (Blow and Binstock 2004, "How to find the inertia tensor (or other mass properties) of a
// 3D solid body represented by a triangle mesh"; Tonon 2004 gives the same integrals). The
// "origin" is the mesh's bounding-box centre, so that a body far from the world's origin keeps
// its digits.
//
// The principal moments and axes are the eigenvalues and eigenvectors of I (Jacobi rotations:
// the tensor is symmetric, three by three, and the iteration converges to round-off).
#include <array>
#include <string>

#include "engine/geometry/triangle_mesh.hpp"

namespace pbf {

using Matrix3 = std::array<std::array<double, 3>, 3>;

struct MassProperties {
  double volume = 0, mass = 0;
  std::array<double, 3> center{0, 0, 0};
  Matrix3 inertia{};  // about the centre, world axes (kg m^2)
};

// Throws (naming `what`) unless the mesh is closed (every edge shared by exactly two
// triangles, in opposite directions) and encloses a positive volume (outward normals).
MassProperties mass_properties(const TriangleMesh& mesh, double density, const std::string& what);

// The principal moments (ascending) and axes (columns of `axes`, a right-handed rotation) of a
// symmetric tensor.
void principal_axes(const Matrix3& tensor, std::array<double, 3>& moments, Matrix3& axes);

}  // namespace pbf
