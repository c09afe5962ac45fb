#include "engine/io/vtu.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fmt/format.h>

#include "engine/core/error.hpp"
#include "engine/io/atomic_file.hpp"
#include "engine/io/vtk_appended.hpp"

namespace pbf {

const char* type_name(VtuType t) {
  return t == VtuType::Float32 ? "Float32" : t == VtuType::Float64 ? "Float64" : "Int64";
}

std::size_t type_size(VtuType t) { return t == VtuType::Float32 ? 4 : 8; }

namespace {

void check_array(const std::string& path, const VtuArray& a, std::size_t n) {
  if (a.name.empty()) throw Error(fmt::format("{}: a vtu array needs a name", path));
  if (a.components < 1) throw Error(fmt::format("{}: array '{}' has {} components", path, a.name, a.components));
  if (n > 0 && !a.data) throw Error(fmt::format("{}: array '{}' has no data", path, a.name));
}

}  // namespace

void write_vtu(const std::string& path, std::size_t n, const VtuArray& points,
               const std::vector<VtuArray>& point_data) {
  check_array(path, points, n);
  if (points.components != 3 || points.type == VtuType::Int64)
    throw Error(fmt::format("{}: points must be 3-component Float32 or Float64", path));
  for (const auto& a : point_data) check_array(path, a, n);

  VtkAppendedFile out(path, "UnstructuredGrid");
  out.head(fmt::format("    <Piece NumberOfPoints=\"{}\" NumberOfCells=\"{}\">\n      <PointData>\n", n, n));
  for (const auto& a : point_data)
    out.declare(type_name(a.type), a.name, a.components, n * a.components * type_size(a.type));
  out.head("      </PointData>\n      <Points>\n");
  out.declare(type_name(points.type), "Points", 3, n * 3 * type_size(points.type));
  out.head("      </Points>\n      <Cells>\n");
  out.declare("Int64", "connectivity", 1, n * 8);
  out.declare("Int64", "offsets", 1, n * 8);
  out.declare("UInt8", "types", 1, n);
  out.head("      </Cells>\n    </Piece>\n");

  for (const auto& a : point_data) out.block(a.data, n * a.components * type_size(a.type));
  out.block(points.data, n * 3 * type_size(points.type));
  // One VTK_VERTEX (type 1) per particle: connectivity i, offsets i+1. Written in chunks
  // rather than materialised, so a frame costs no memory beyond the particle arrays.
  constexpr std::size_t kChunk = 4096;
  std::int64_t ints[kChunk];
  for (int pass = 0; pass < 2; ++pass) {
    out.begin_block(n * 8);
    for (std::size_t i = 0; i < n; i += kChunk) {
      const std::size_t m = std::min(kChunk, n - i);
      for (std::size_t k = 0; k < m; ++k) ints[k] = static_cast<std::int64_t>(i + k + pass);
      out.write(ints, m * 8);
    }
  }
  out.begin_block(n);
  const std::string vertex(kChunk, '\1');
  for (std::size_t i = 0; i < n; i += kChunk) out.write(vertex.data(), std::min(kChunk, n - i));
  out.commit();
}

void write_pvtu(const std::string& path, VtuType points, const std::vector<VtuArray>& point_data,
                const std::vector<std::string>& pieces) {
  std::string text =
      "<?xml version=\"1.0\"?>\n<VTKFile type=\"PUnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" "
      "header_type=\"UInt64\">\n  <PUnstructuredGrid GhostLevel=\"0\">\n    <PPointData>\n";
  for (const auto& a : point_data)
    text += fmt::format("      <PDataArray type=\"{}\" Name=\"{}\" NumberOfComponents=\"{}\"/>\n", type_name(a.type),
                        xml_escape(a.name), a.components);
  text += fmt::format("    </PPointData>\n    <PPoints>\n      <PDataArray type=\"{}\" NumberOfComponents=\"3\"/>\n"
                      "    </PPoints>\n",
                      type_name(points));
  for (const auto& piece : pieces) text += fmt::format("    <Piece Source=\"{}\"/>\n", xml_escape(piece));
  text += "  </PUnstructuredGrid>\n</VTKFile>\n";
  AtomicFile out(path);
  out.write(text);
  out.commit();
}

void write_pvd(const std::string& path, const std::vector<PvdDataSet>& datasets) {
  const auto dir = std::filesystem::absolute(path).parent_path();
  std::string text =
      "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"1.0\" byte_order=\"LittleEndian\">\n"
      "  <Collection>\n";
  for (const auto& [time, part, file] : datasets) {
    if (!std::isfinite(time)) throw Error(fmt::format("{}: frame '{}' has time {}", path, file, time));
    std::filesystem::path f(file);
    if (f.is_absolute()) f = f.lexically_relative(dir);
    // "{}" prints the shortest text that reads back as the same double.
    text += fmt::format("    <DataSet timestep=\"{}\" group=\"\" part=\"{}\" file=\"{}\"/>\n", time, part,
                        xml_escape(f.generic_string()));
  }
  text += "  </Collection>\n</VTKFile>\n";
  AtomicFile out(path);
  out.write(text);
  out.commit();
}

void write_pvd(const std::string& path, const std::vector<std::pair<double, std::string>>& frames) {
  std::vector<PvdDataSet> datasets;
  for (const auto& [time, file] : frames) datasets.push_back({time, 0, file});
  write_pvd(path, datasets);
}

}  // namespace pbf
