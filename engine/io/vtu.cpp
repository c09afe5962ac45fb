#include "engine/io/vtu.hpp"

#include <algorithm>
#include <bit>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fmt/format.h>
#include <fstream>
#include <iterator>
#include <string_view>

#include "engine/core/error.hpp"
#include "engine/io/atomic_file.hpp"

namespace pbf {

// Both directions copy array bytes as they are and call them LittleEndian.
static_assert(std::endian::native == std::endian::little, "vtu.cpp assumes a little-endian machine");

namespace {

// ---------------------------------------------------------------- writing

std::string xml_escape(const std::string& s) {
  std::string out;
  for (char c : s) {
    if (c == '&') out += "&amp;";
    else if (c == '<') out += "&lt;";
    else if (c == '"') out += "&quot;";
    else out += c;
  }
  return out;
}

const char* type_name(VtuType t) {
  return t == VtuType::Float32 ? "Float32" : t == VtuType::Float64 ? "Float64" : "Int64";
}

std::size_t type_size(VtuType t) { return t == VtuType::Float32 ? 4 : 8; }

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

  // The head lists every array with its offset into the appended block; the blocks follow
  // in the same order, each a UInt64 byte count and the bytes.
  std::uint64_t offset = 0;
  std::string head = fmt::format(
      "<?xml version=\"1.0\"?>\n"
      "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\">\n"
      "  <UnstructuredGrid>\n    <Piece NumberOfPoints=\"{}\" NumberOfCells=\"{}\">\n",
      n, n);
  auto entry = [&](const char* type, const std::string& name, int components, std::size_t bytes) {
    head += fmt::format(
        "        <DataArray type=\"{}\" Name=\"{}\" NumberOfComponents=\"{}\" format=\"appended\" offset=\"{}\"/>\n",
        type, xml_escape(name), components, offset);
    offset += sizeof(std::uint64_t) + bytes;
  };
  head += "      <PointData>\n";
  for (const auto& a : point_data) entry(type_name(a.type), a.name, a.components, n * a.components * type_size(a.type));
  head += "      </PointData>\n      <Points>\n";
  entry(type_name(points.type), "Points", 3, n * 3 * type_size(points.type));
  head += "      </Points>\n      <Cells>\n";
  entry("Int64", "connectivity", 1, n * 8);
  entry("Int64", "offsets", 1, n * 8);
  entry("UInt8", "types", 1, n);
  head += "      </Cells>\n    </Piece>\n  </UnstructuredGrid>\n  <AppendedData encoding=\"raw\">\n   _";

  AtomicFile out(path);
  out.write(head);
  auto block = [&](const void* data, std::uint64_t bytes) {
    out.write(&bytes, sizeof bytes);
    out.write(data, bytes);
  };
  for (const auto& a : point_data) block(a.data, n * a.components * type_size(a.type));
  block(points.data, n * 3 * type_size(points.type));

  // One VTK_VERTEX (type 1) per particle: connectivity i, offsets i+1. Written in chunks
  // rather than materialised, so a frame costs no memory beyond the particle arrays.
  constexpr std::size_t kChunk = 4096;
  std::int64_t ints[kChunk];
  for (int pass = 0; pass < 2; ++pass) {
    const std::uint64_t bytes = n * 8;
    out.write(&bytes, sizeof bytes);
    for (std::size_t i = 0; i < n; i += kChunk) {
      const std::size_t m = std::min(kChunk, n - i);
      for (std::size_t k = 0; k < m; ++k) ints[k] = static_cast<std::int64_t>(i + k + pass);
      out.write(ints, m * 8);
    }
  }
  const std::uint64_t type_bytes = n;
  out.write(&type_bytes, sizeof type_bytes);
  const std::string vertex(kChunk, '\1');
  for (std::size_t i = 0; i < n; i += kChunk) out.write(vertex.data(), std::min(kChunk, n - i));
  out.write("\n  </AppendedData>\n</VTKFile>\n");
  out.commit();
}

void write_pvd(const std::string& path, const std::vector<std::pair<double, std::string>>& frames) {
  const auto dir = std::filesystem::absolute(path).parent_path();
  std::string text =
      "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"1.0\" byte_order=\"LittleEndian\">\n"
      "  <Collection>\n";
  for (const auto& [time, file] : frames) {
    if (!std::isfinite(time)) throw Error(fmt::format("{}: frame '{}' has time {}", path, file, time));
    std::filesystem::path f(file);
    if (f.is_absolute()) f = f.lexically_relative(dir);
    // "{}" prints the shortest text that reads back as the same double.
    text += fmt::format("    <DataSet timestep=\"{}\" group=\"\" part=\"0\" file=\"{}\"/>\n", time,
                        xml_escape(f.generic_string()));
  }
  text += "  </Collection>\n</VTKFile>\n";
  AtomicFile out(path);
  out.write(text);
  out.commit();
}

}  // namespace pbf
