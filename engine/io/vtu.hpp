#pragma once
// VTK XML UnstructuredGrid (.vtu) frames, one VTK_VERTEX cell per particle, and the
// ParaView collection (.pvd) that lists them (and the solids' .vtp surfaces) with their times.
//
// The writer always produces the one layout ParaView, VisIt and meshio all read fastest
// (engine/io/vtk_appended.hpp): LittleEndian, UInt64 block headers, every array "appended"
// into one raw block. The reader accepts what other tools commonly write as well (inline
// base64 "binary" or "ascii" arrays, UInt32 headers, any integer or float type), except
// compressed files.
#include <cstddef>
#include <string>
#include <utility>
#include <vector>

#include "engine/io/particle_table.hpp"

namespace pbf {

enum class VtuType { Float32, Float64, Int64 };
const char* type_name(VtuType t);  // as VTK names it: "Float32", ...
std::size_t type_size(VtuType t);  // bytes of one value

struct VtuArray {
  std::string name;
  int components = 1;
  VtuType type = VtuType::Float64;
  const void* data = nullptr;  // n * components values of `type`, interleaved
};

// Writes one frame of n particles: `points` (3 components, Float32 or Float64) and the
// PointData arrays. Writes PATH.tmp and renames it, so a reader never sees half a frame.
// Throws pbf::Error naming the path if the file cannot be written (disk full included).
void write_vtu(const std::string& path, std::size_t n, const VtuArray& points,
               const std::vector<VtuArray>& point_data);

// The parallel frame (.pvtu) of a distributed run: the arrays' names, types and components
// (data unused) and the pieces' .vtu files, relative to the .pvtu's directory. ParaView reads
// the pieces as one data set.
void write_pvtu(const std::string& path, VtuType points, const std::vector<VtuArray>& point_data,
                const std::vector<std::string>& pieces);

// One DataSet of a collection: the file that holds `part` at `time`. ParaView shows the
// parts of one time together (part 0 the particles, then one part per solid).
struct PvdDataSet {
  double time;
  int part;
  std::string file;
};

// Rewrites the whole collection (through PATH.tmp and a rename, so it is valid at every
// moment of a run), DataSets in the order given. Files are written as given, so pass them
// relative to the .pvd's directory; an absolute one is made relative to it.
void write_pvd(const std::string& path, const std::vector<PvdDataSet>& datasets);
// The same with every file part 0: one (time, file) per frame.
void write_pvd(const std::string& path, const std::vector<std::pair<double, std::string>>& frames);

// Reads a .vtu: column "position" (3 components) from the Points, then each PointData array
// under its own name, all converted to double. Every malformed file is a pbf::Error naming
// the file and what is wrong; sizes in the file are checked against its length before
// anything is allocated from them.
ParticleTable read_vtu(const std::string& path);

}  // namespace pbf
