#pragma once
// What the `solid` fix is made of, from its parameters: a mesh file or a primitive, placed
// (scale, rotation, translation). It makes the signed-distance shape the density map is
// built from, the surface the outputs draw, and checks the solid against the domain.
#include <cstdint>
#include <memory>
#include <string>

#include "engine/bodies/mass_properties.hpp"
#include "engine/core/domain.hpp"
#include "engine/geometry/shape.hpp"
#include "engine/geometry/triangle_mesh.hpp"
#include "engine/registry/params.hpp"

namespace pbf {

class SolidShape {
 public:
  // Reads the shape's parameters (and the mesh file); `id` names the solid in messages.
  SolidShape(const std::string& id, const Params& p);

  const std::string& name() const { return shape_name_; }
  bool is_plane() const { return shape_name_ == "plane"; }
  const std::string& file() const { return file_; }            // "" for a primitive
  std::uint64_t file_hash() const { return file_hash_; }       // FNV-1a of the file's bytes
  // The placed surface (a plane's: where it cuts the domain, known after make_shape).
  const TriangleMesh& surface() const { return surface_; }

  // The placed solid's mass, centre and inertia at this density, exactly: a mesh's (and a
  // box's) polyhedral integrals, a sphere's and a cylinder's closed forms carried through the
  // placement. Refuses a plane and a mesh that is not closed.
  MassProperties mass_properties(double density) const;

  // The signed distance of the placed solid, exact for primitives, from a grid of `cell`
  // reaching `reach` for a mesh. Refuses a solid that lies outside the domain.
  std::unique_ptr<Shape> make_shape(const Domain& dom, double cell, double reach);

 private:
  std::unique_ptr<Shape> primitive(const Domain& dom);
  void check_against_domain(const Domain& dom) const;

  std::string id_, shape_name_;
  std::string file_;
  std::uint64_t file_hash_ = 0;
  Placement placement_;
  Point lo_{}, hi_{};  // the primitive's two points (box corners, sphere centre, cylinder ends, plane point and normal)
  double radius_ = 0;
  Point plane_point_{}, plane_normal_{};  // a plane's, placed in the world
  bool mesh_ = false;
  TriangleMesh surface_;
};

}  // namespace pbf
