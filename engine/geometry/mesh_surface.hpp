#pragma once
// Whether a triangle mesh bounds a solid, and turning its triangles to face outward; the
// volume it encloses.
#include <string>

#include "engine/geometry/triangle_mesh.hpp"

namespace pbf {

// Makes `mesh` a closed surface whose triangles all face outward, or throws a pbf::Error
// naming `what` (e.g. "mesh file 'tank.obj'").
//
// Always refused: an edge on one triangle only (an open surface), an edge on more than two
// (not a manifold), and a connected part whose triangles cannot all face one way (a
// one-sided surface, as a Moebius strip closed up): such a mesh has no inside.
//
// Which way is outward is then exact: the triangles of a connected part must agree across
// every edge they share, which leaves two ways for the part to face, and the outward one
// encloses a positive volume. A mesh that is wholly inside out is turned whatever `orient`
// says. Where only some triangles face the wrong way (against the triangles around them, or
// a whole separate part against the rest), `orient` turns them and logs how many; without
// it they are refused, the message naming the first (counting the file's triangles from 1)
// and its corners. A separate part inside another (the wall of a cavity) is made to face
// outward too: the cavity becomes solid.
void orient_surface(TriangleMesh& mesh, const std::string& what, bool orient);

// The volume the surface encloses (divergence theorem): positive when its triangles are
// oriented outward, negative when inward. Meaningful for closed meshes only.
double enclosed_volume(const TriangleMesh& mesh);

}  // namespace pbf
