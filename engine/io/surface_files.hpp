#pragma once
// A reconstructed surface (engine/surface/surface.hpp) in the formats rendering tools read:
//   .vtp  ParaView: VTK PolyData with the normals and attributes as point data;
//   .ply  Blender, Houdini, MeshLab: binary little-endian PLY, float x y z nx ny nz and each
//         attribute (a vector as NAME_x, NAME_y, NAME_z), faces as int index lists;
//   .obj  anything: text, v, vn and f a//a b//b c//c (no attributes);
//   .vdb  Houdini, Blender: a narrow-band level set of the mesh (OpenVDB's meshToLevelSet),
//         grid "surface", negative inside, `voxel` wide voxels and 3 voxels each side.
// Each is written whole through a temporary file and a rename; a file that cannot be written
// is a pbf::Error naming it.
#include <string>

#include "engine/surface/surface.hpp"

namespace pbf {

void write_surface_vtp(const std::string& path, const SurfaceMesh& mesh);
void write_surface_ply(const std::string& path, const SurfaceMesh& mesh, const std::string& comment = "");
void write_surface_obj(const std::string& path, const SurfaceMesh& mesh, const std::string& comment = "");
void write_surface_vdb(const std::string& path, const SurfaceMesh& mesh, double voxel);

}  // namespace pbf
