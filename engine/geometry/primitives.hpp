#pragma once
// Closed, outward-oriented triangle meshes of the analytic solids, for drawing them and
// writing them for ParaView (the physics uses their exact distances, engine/geometry/shape.hpp),
// and the patch of a plane inside a box. Invalid sizes throw a pbf::Error naming the argument.
#include <array>

#include "engine/geometry/triangle_mesh.hpp"

namespace pbf {

// The box [lo, hi]: 8 vertices, 12 triangles. Needs lo < hi on every axis.
TriangleMesh box_mesh(const std::array<double, 3>& lo, const std::array<double, 3>& hi);

// An icosphere (vertices on the sphere), subdivided until no edge is longer than `max_edge`
// or it has 20 480 triangles.
TriangleMesh sphere_mesh(const std::array<double, 3>& center, double radius, double max_edge);

// A capped cylinder from the centre of its base to the centre of its top (vertices on the
// surface): as many sides as keep the rim's edges within `max_edge`, 16 to 1024.
TriangleMesh cylinder_mesh(const std::array<double, 3>& base, const std::array<double, 3>& top, double radius,
                           double max_edge);

// The polygon where the plane through `point` with normal `normal` cuts the box [lo, hi],
// as triangles facing along `normal` (an open surface: for drawing only). Empty when the
// plane misses the box or only touches it.
TriangleMesh plane_patch(const std::array<double, 3>& point, const std::array<double, 3>& normal,
                         const std::array<double, 3>& lo, const std::array<double, 3>& hi);

}  // namespace pbf
