// Particle files: .vtu frames written and read back bit for bit, checked by an independent
// Python reader (tests/check_vtu.py); the .pvd collection; CSV input; and every malformed
// file refused with a pbf::Error naming it, never a crash.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <csignal>
#include <cstdint>
#include <fmt/format.h>
#include <limits>
#include <sys/resource.h>

#include "engine/core/error.hpp"
#include "engine/io/csv.hpp"
#include "engine/io/particle_input.hpp"
#include "engine/io/vtu.hpp"
#include "test_util.hpp"

using namespace pbf;
using pbf::test::error_of;
namespace fs = std::filesystem;

namespace {


// A frame with awkward values: negative zero, a subnormal, numbers a float cannot hold.
struct Frame {
  std::size_t n = 5;
  std::vector<double> pos{0.1, 0.2, 0.3, -0.0, 1e-310, 1e300, 1.0 / 3, 2.0 / 3, 1.0, -5.5, 7, 8, 9e-9, 0.5, 0.25};
  std::vector<float> pos32{0.1f, 0.2f, 0.3f, -0.0f, 1e-40f, 3e38f, 1.0f / 3, 2.0f / 3, 1, -5.5f, 7, 8, 9e-9f, .5f, 0};
  std::vector<double> vel{1, -2, 3, 0.1, 0.2, 0.3, -1e-5, 0, 0, 4, 5, 6, 7, 8, 1.0 / 7};
  std::vector<std::int64_t> id{0, 7, -1, std::int64_t(1) << 53, 42};
  std::vector<double> rho{1000, 999.5, std::numeric_limits<double>::quiet_NaN(), 1e-3, 1001};

  void write(const fs::path& path, bool single) const {
    const VtuArray points{"Points", 3, single ? VtuType::Float32 : VtuType::Float64,
                          single ? static_cast<const void*>(pos32.data()) : pos.data()};
    write_vtu(path.string(), n, points,
              {{"velocity", 3, VtuType::Float64, vel.data()}, {"id", 1, VtuType::Int64, id.data()},
               {"rho", 1, VtuType::Float64, rho.data()}});
  }
};

bool same_bits(double a, double b) { return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b); }

std::string run_python(const std::string& args) {
  const std::string command = fmt::format("'{}' '{}/tests/check_vtu.py' {} 2>&1; echo \"exit $?\"", PBF_PYTHON,
                                          PBF_SOURCE_DIR, args);
  std::string out;
  FILE* pipe = popen(command.c_str(), "r");
  if (!pipe) return "popen failed";
  char buf[4096];
  for (std::size_t k; (k = fread(buf, 1, sizeof buf, pipe)) > 0;) out.append(buf, k);
  pclose(pipe);
  return out;
}

std::string json_numbers(const std::vector<double>& v) {
  std::vector<std::string> s;
  for (double x : v) s.push_back(std::isnan(x) ? "NaN" : fmt::format("{}", x));  // shortest exact text
  return fmt::format("[{}]", fmt::join(s, ","));
}

// A valid hand-written frame of two points in ascii; the malformed cases edit it.
const std::string kAscii = R"(<?xml version="1.0"?>
<VTKFile type="UnstructuredGrid" version="0.1" byte_order="LittleEndian">
  <UnstructuredGrid>
    <Piece NumberOfPoints="2" NumberOfCells="0">
      <PointData>
        <DataArray type="Float32" Name="mass" format="ascii"> 0.5 +0.25 </DataArray>
      </PointData>
      <Points>
        <DataArray type="Float64" NumberOfComponents="3" format="ascii">
          0 0.1 0.2
          1e-3 -4 5
        </DataArray>
      </Points>
    </Piece>
  </UnstructuredGrid>
</VTKFile>
)";

std::string base64(const std::string& bytes) {
  const char* alphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  for (std::size_t i = 0; i < bytes.size(); i += 3) {
    unsigned v = static_cast<unsigned char>(bytes[i]) << 16;
    if (i + 1 < bytes.size()) v |= static_cast<unsigned char>(bytes[i + 1]) << 8;
    if (i + 2 < bytes.size()) v |= static_cast<unsigned char>(bytes[i + 2]);
    out += alphabet[v >> 18 & 63];
    out += alphabet[v >> 12 & 63];
    out += i + 1 < bytes.size() ? alphabet[v >> 6 & 63] : '=';
    out += i + 2 < bytes.size() ? alphabet[v & 63] : '=';
  }
  return out;
}

template <class T>
std::string raw(std::initializer_list<T> values) {
  std::string s;
  for (T v : values) s.append(reinterpret_cast<const char*>(&v), sizeof v);
  return s;
}

std::string replaced(std::string s, const std::string& from, const std::string& to) {
  const auto at = s.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return at == std::string::npos ? s : s.replace(at, from.size(), to);
}

// Two points and a 'mass' as raw appended data: the mass block, then the Points block,
// each with a size header of `header` bytes (4 or 8) and `extra` bytes after the mass;
// `declared`: the header_type the file claims.
std::string appended_raw(const std::string& declared, std::size_t header, const std::string& extra = "") {
  auto block = [&](const std::string& data) {
    const std::uint64_t size = data.size();
    return std::string(reinterpret_cast<const char*>(&size), header) + data;  // little-endian: the low bytes
  };
  const std::string mass = block(raw<double>({0.5, 0.25})) + extra;
  const std::string points = block(raw<double>({0, 0.1, 0.2, 1e-3, -4, 5}));
  return "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" "
         "header_type=\"" + declared + "\">\n <UnstructuredGrid>\n  <Piece NumberOfPoints=\"2\" NumberOfCells=\"0\">\n"
         "   <PointData>\n    <DataArray type=\"Float64\" Name=\"mass\" format=\"appended\" offset=\"0\"/>\n"
         "   </PointData>\n   <Points>\n    <DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"appended\" "
         "offset=\"" + std::to_string(mass.size()) + "\"/>\n   </Points>\n  </Piece>\n </UnstructuredGrid>\n"
         " <AppendedData encoding=\"raw\">\n  _" + mass + points + "\n </AppendedData>\n</VTKFile>\n";
}

}  // namespace

TEST(Vtu, RoundTripsFloat64AndFloat32PointsAndArraysBitForBit) {
  const auto dir = test::temp_dir("vtu-roundtrip");
  const Frame f;
  for (bool single : {false, true}) {
    const auto path = dir / (single ? "f32.vtu" : "f64.vtu");
    f.write(path, single);
    EXPECT_FALSE(fs::exists(path.string() + ".tmp"));
    const ParticleTable t = read_vtu(path.string());
    EXPECT_EQ(t.path, path.string());
    ASSERT_EQ(t.count, f.n);
    ASSERT_EQ(t.columns.size(), 4u);
    EXPECT_EQ(t.columns[0].name, "position");
    EXPECT_EQ(t.columns[1].name, "velocity");
    EXPECT_EQ(t.columns[2].name, "id");
    EXPECT_EQ(t.columns[3].name, "rho");
    const Column* p = t.find("position");
    ASSERT_TRUE(p && p->components == 3 && p->values.size() == 15);
    for (std::size_t i = 0; i < 15; ++i)
      EXPECT_TRUE(same_bits(p->values[i], single ? double(f.pos32[i]) : f.pos[i])) << i;
    for (std::size_t i = 0; i < 15; ++i) EXPECT_TRUE(same_bits(t.find("velocity")->values[i], f.vel[i])) << i;
    for (std::size_t i = 0; i < 5; ++i) EXPECT_EQ(t.find("id")->values[i], double(f.id[i])) << i;
    for (std::size_t i = 0; i < 5; ++i) EXPECT_TRUE(same_bits(t.find("rho")->values[i], f.rho[i])) << i;
  }
  // No particles is a valid frame too.
  write_vtu((dir / "empty.vtu").string(), 0, {"Points", 3, VtuType::Float64, nullptr}, {});
  EXPECT_EQ(read_vtu((dir / "empty.vtu").string()).count, 0u);
}

TEST(Vtu, AnIndependentPythonReaderAgrees) {
  if (std::string(PBF_PYTHON).empty()) GTEST_SKIP() << "no Python interpreter found at configure time";
  const auto dir = test::temp_dir("vtu-python");
  const Frame f;
  f.write(dir / "frame.vtu", false);
  std::vector<double> id(f.id.begin(), f.id.end());
  test::write_file(dir / "expected.json",
                   fmt::format(R"({{"points": 5, "arrays": {{"Points": {}, "velocity": {}, "id": {}, "rho": {}}}}})",
                               json_numbers(f.pos), json_numbers(f.vel), json_numbers(id), json_numbers(f.rho)));
  const std::string out = run_python(fmt::format("'{}' '{}'", (dir / "frame.vtu").string(),
                                                 (dir / "expected.json").string()));
  EXPECT_NE(out.find("points 5\n"), std::string::npos) << out;
  EXPECT_NE(out.find("id Int64 1\n"), std::string::npos) << out;
  EXPECT_NE(out.find("ok\nexit 0"), std::string::npos) << out;
  // And the checker does fail on a wrong value.
  test::write_file(dir / "wrong.json", R"({"points": 5, "arrays": {"rho": [1000, 999.5, NaN, 0.001, 1002]}})");
  EXPECT_NE(run_python(fmt::format("'{}' '{}'", (dir / "frame.vtu").string(), (dir / "wrong.json").string()))
                .find("exit 1"),
            std::string::npos);
}

TEST(Vtu, ReadsAsciiInlineBase64AndAppendedBase64WithUInt32OrUInt64Headers) {
  const auto dir = test::temp_dir("vtu-formats");
  test::write_file(dir / "ascii.vtu", kAscii);
  const ParticleTable a = read_vtu((dir / "ascii.vtu").string());
  ASSERT_EQ(a.count, 2u);
  EXPECT_EQ(a.find("position")->values, (std::vector<double>{0, 0.1, 0.2, 1e-3, -4, 5}));
  EXPECT_EQ(a.find("mass")->values, (std::vector<double>{0.5, 0.25}));

  // VTK encodes the size header and the data as two base64 runs; other writers as one run.
  const std::string points = raw<float>({1, 2, 3, 4, 5, 6});
  const std::string ids = raw<std::int32_t>({-7, 9});
  const std::string h32 = raw<std::uint32_t>({24}), h64 = raw<std::uint64_t>({24});
  for (const std::string& header : {std::string("UInt32"), std::string("UInt64")}) {
    const std::string& h = header == "UInt32" ? h32 : h64;
    const std::string id_header = header == "UInt32" ? raw<std::uint32_t>({8}) : raw<std::uint64_t>({8});
    std::string text = replaced(kAscii, "version=\"0.1\"", "header_type=\"" + header + "\"");
    text = replaced(text, "type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\"",
                    "type=\"Float32\" NumberOfComponents=\"3\" format=\"binary\"");
    text = replaced(text, "0 0.1 0.2\n          1e-3 -4 5", base64(h) + "\n" + base64(points));
    text = replaced(text, "type=\"Float32\" Name=\"mass\" format=\"ascii\"> 0.5 +0.25",
                    "type=\"Int32\" Name=\"id\" format=\"binary\">" + base64(id_header + ids));
    test::write_file(dir / "b64.vtu", text);
    const ParticleTable b = read_vtu((dir / "b64.vtu").string());
    EXPECT_EQ(b.find("position")->values, (std::vector<double>{1, 2, 3, 4, 5, 6})) << header;
    EXPECT_EQ(b.find("id")->values, (std::vector<double>{-7, 9})) << header;
  }

  // Appended base64 (VTK's "appended, encoded" mode): offsets count base64 characters.
  const std::string mass = base64(raw<std::uint64_t>({16})) + base64(raw<double>({0.5, 0.25}));
  const std::string pos = base64(raw<std::uint64_t>({48})) + base64(raw<double>({1, 2, 3, 4, 5, 6}));
  std::string text = replaced(kAscii, "version=\"0.1\"", "header_type=\"UInt64\"");
  text = replaced(text, "type=\"Float32\" Name=\"mass\" format=\"ascii\"> 0.5 +0.25 </DataArray>",
                  "type=\"Float64\" Name=\"mass\" format=\"appended\" offset=\"0\"/>");
  text = replaced(text, "format=\"ascii\">\n          0 0.1 0.2\n          1e-3 -4 5\n        </DataArray>",
                  fmt::format("format=\"appended\" offset=\"{}\"/>", mass.size()));
  text = replaced(text, "</VTKFile>",
                  "<AppendedData encoding=\"base64\">\n_" + mass + pos + "\n</AppendedData>\n</VTKFile>");
  test::write_file(dir / "appended64.vtu", text);
  const ParticleTable c = read_vtu((dir / "appended64.vtu").string());
  EXPECT_EQ(c.find("position")->values, (std::vector<double>{1, 2, 3, 4, 5, 6}));
  EXPECT_EQ(c.find("mass")->values, (std::vector<double>{0.5, 0.25}));
}

TEST(Vtu, EveryTruncationIsAnErrorNamingTheFile) {
  const auto dir = test::temp_dir("vtu-truncated");
  Frame().write(dir / "full.vtu", false);
  const std::string full = test::read_file(dir / "full.vtu");
  for (std::size_t len = 0; len + 1 < full.size(); ++len) {  // the last byte is the final newline
    // A new file each time: rewriting one file makes ext4 flush it on every close.
    const auto path = (dir / fmt::format("cut{}.vtu", len)).string();
    test::write_file(path, full.substr(0, len));
    const std::string e = error_of([&] { read_vtu(path); });
    EXPECT_NE(e.find(path), std::string::npos) << "cut at " << len << ": '" << e << "'";
    const bool says_why = e.find("truncated file") != std::string::npos || e.find("empty file") != std::string::npos ||
                          e.find("No document element") != std::string::npos;  // only the <?xml ...?> line left
    EXPECT_TRUE(says_why) << "cut at " << len << ": '" << e << "'";
  }
  const auto path = (dir / "whole.vtu").string();
  test::write_file(path, full.substr(0, full.size() - 1));
  EXPECT_EQ(read_vtu(path).count, 5u);
  fs::remove_all(dir);
}

TEST(Vtu, MalformedFilesAreErrorsNamingTheFile) {
  const auto dir = test::temp_dir("vtu-bad");
  const auto path = (dir / "bad.vtu").string();
  Frame().write(dir / "good.vtu", false);
  const std::string good = test::read_file(dir / "good.vtu");
  auto expect = [&](const std::string& text, const std::string& words) {
    test::write_file(path, text);
    EXPECT_ERROR_NAMING(read_vtu(path), path, words);
  };
  // The first block (velocity, 5 x 3 doubles) starts right after the '_'.
  const std::size_t block = good.find('_', good.find("<AppendedData")) + 1;
  for (std::uint64_t size : {std::uint64_t(112), std::uint64_t(1) << 62, ~std::uint64_t(0)}) {
    std::string text = good;
    std::memcpy(&text[block], &size, 8);
    expect(text, "velocity' holds " + std::to_string(size) + " bytes, but NumberOfPoints = 5 needs 120");
  }
  expect(replaced(good, "NumberOfPoints=\"5\"", "NumberOfPoints=\"6\""), "NumberOfPoints = 6 needs");
  expect(replaced(good, "NumberOfPoints=\"5\"", "NumberOfPoints=\"99999999999999\""), "more than a file of");
  expect(replaced(good, "NumberOfPoints=\"5\"", "NumberOfPoints=\"-1\""), "non-negative integer");
  expect(replaced(good, "offset=\"0\"", "offset=\"99999\""), "offset 99999 is beyond the appended data");
  expect(replaced(good, "type=\"UnstructuredGrid\"", "type=\"PolyData\""), "not an UnstructuredGrid");
  expect(replaced(good, "type=\"Int64\" Name=\"id\"", "type=\"Float128\" Name=\"id\""), "unknown type \"Float128\"");
  expect(replaced(good, "type=\"Int64\" Name=\"id\"", "type=\"Int32\" Name=\"id\""), "holds 40 bytes");
  expect(replaced(good, "header_type=\"UInt64\"", "header_type=\"UInt64\" compressor=\"vtkZLibDataCompressor\""),
         "compressed files");
  expect(replaced(good, "LittleEndian", "BigEndian"), "BigEndian");
  expect(replaced(good, "UInt64\">", "UInt16\">"), "header_type");
  expect(replaced(good, "<Points>", "<Pointz>"), "");  // an XML error: tags mismatch
  expect(replaced(replaced(good, "<Points>", "<Pointz>"), "</Points>", "</Pointz>"), "no <Points>");
  expect(replaced(good, "format=\"appended\"", "format=\"zip\""), "format \"zip\"");
  expect(replaced(good, "Name=\"rho\"", "Name=\"velocity\""), "appears twice");
  expect(replaced(good, "encoding=\"raw\"", "encoding=\"hex\""), "encoding \"hex\"");
  expect("", "empty file");
  expect("hello", "not valid XML");
  expect("<other/>", "no <VTKFile>");
  expect(replaced(kAscii, "1e-3", "1e-3x"), ":9: the Points array: '1e-3x' is not a number");
  expect(replaced(kAscii, "+0.25", "0.25 7"), "more than the 2 values");
  expect(replaced(kAscii, " +0.25 ", " "), "holds 1 values, but NumberOfPoints = 2 needs 2");
  expect(replaced(kAscii, " 0.5 +0.25 ", ""), "holds too few values for NumberOfPoints = 2");
  expect(replaced(kAscii, "1e-3 -4 5", "1e-3 -4 5 6 7"), "holds more than the 6 values");
  expect(replaced(kAscii, "NumberOfComponents=\"3\"", "NumberOfComponents=\"2\""), "has 2 components, expected 3");
  expect(replaced(kAscii, "format=\"ascii\">\n", "format=\"binary\">!!!!"), "not a base64 character");
  expect(replaced(replaced(kAscii, "format=\"ascii\">\n", "format=\"binary\">\n"), "0 0.1 0.2\n          1e-3 -4 5",
                  "AAAAAA=="),
         "holds 0 bytes, but NumberOfPoints = 2 needs 48");
  EXPECT_ERROR_NAMING(read_vtu((dir / "missing.vtu").string()), "missing.vtu", "cannot open");
}

// The header_type names the width of every block's size header. One that disagrees with
// the data used to be read as shifted numbers, reported later as a particle outside the
// domain: now every block must hold exactly its header and its array's bytes.
TEST(Vtu, AHeaderTypeThatDisagreesWithTheDataIsNamed) {
  const auto dir = test::temp_dir("vtu-header-type");
  const auto path = (dir / "f.vtu").string();
  for (const auto& [declared, header] : {std::pair{"UInt32", 4}, std::pair{"UInt64", 8}}) {
    test::write_file(path, appended_raw(declared, header));
    const ParticleTable t = read_vtu(path);
    EXPECT_EQ(t.find("position")->values, (std::vector<double>{0, 0.1, 0.2, 1e-3, -4, 5})) << declared;
    EXPECT_EQ(t.find("mass")->values, (std::vector<double>{0.5, 0.25})) << declared;
  }
  test::write_file(path, appended_raw("UInt32", 8));
  EXPECT_ERROR_NAMING(read_vtu(path), path, ":9: the Points array: header_type=\"UInt32\" says block sizes are 4-byte "
                    "numbers, but the data have 8-byte ones: the header_type does not match the data (it should be "
                    "\"UInt64\")");
  test::write_file(path, appended_raw("UInt64", 4));
  EXPECT_ERROR_NAMING(read_vtu(path), path, "header_type=\"UInt64\" says block sizes are 8-byte numbers, but the "
                    "data have 4-byte ones");
  // The same in a frame of the engine's own, and in inline base64 blocks.
  Frame().write(dir / "engine.vtu", false);
  test::write_file(path, replaced(test::read_file(dir / "engine.vtu"), "UInt64", "UInt32"));
  EXPECT_ERROR_NAMING(read_vtu(path), path, "the header_type does not match the data (it should be \"UInt64\")");
  std::string text = replaced(kAscii, "version=\"0.1\"", "header_type=\"UInt64\"");
  text = replaced(text, "format=\"ascii\">\n          0 0.1 0.2\n          1e-3 -4 5",
                  "format=\"binary\">" + base64(raw<std::uint32_t>({48}) + raw<double>({0, 0.1, 0.2, 1e-3, -4, 5})));
  test::write_file(path, text);
  EXPECT_ERROR_NAMING(read_vtu(path), path, "the header_type does not match the data (it should be \"UInt32\")");
}

TEST(Vtu, BlocksMustHoldExactlyTheirArrays) {
  const auto dir = test::temp_dir("vtu-blocks");
  const auto path = (dir / "f.vtu").string();
  test::write_file(path, appended_raw("UInt64", 8, "abcd"));
  EXPECT_ERROR_NAMING(read_vtu(path), path, "PointData array 'mass': its block holds 4 bytes after the 16 its size "
                    "header announces");
  const std::string good = appended_raw("UInt64", 8);
  test::write_file(path, replaced(good, "offset=\"24\"", "offset=\"0\""));
  EXPECT_ERROR_NAMING(read_vtu(path), path, "two DataArrays start at offset 0 of the appended data");
  // A <Cells> array (not read, but its offset counts) starting inside the mass block.
  test::write_file(path, replaced(good, "   </Points>\n", "   </Points>\n   <Cells>\n    <DataArray type=\"Int64\" "
                                  "Name=\"offsets\" format=\"appended\" offset=\"10\"/>\n   </Cells>\n"));
  EXPECT_ERROR_NAMING(read_vtu(path), path, "PointData array 'mass' needs 16 bytes, but the next array's data start "
                    "after 2 (their offsets overlap)");
  std::string text = replaced(kAscii, "format=\"ascii\">\n", "format=\"binary\">");
  text = replaced(text, "0 0.1 0.2\n          1e-3 -4 5", base64(raw<std::uint32_t>({48}) + raw<double>({0, 0.1, 0.2, 1e-3, -4, 5})) + "AAA");
  test::write_file(path, text);
  EXPECT_ERROR_NAMING(read_vtu(path), path, "the Points array ends inside a group of four base64 characters");
}

TEST(Vtu, MalformedNumbersADirectoryAndADeviceAreNamed) {
  const auto dir = test::temp_dir("vtu-numbers");
  const auto path = (dir / "f.vtu").string();
  test::write_file(path, replaced(kAscii, "1e-3", "+-1e-3"));  // was read as -1e-3
  EXPECT_ERROR_NAMING(read_vtu(path), path, ":9: the Points array: '+-1e-3' is not a number");
  test::write_file(path, replaced(kAscii, "1e-3", "1e999"));
  EXPECT_ERROR_NAMING(read_vtu(path), path, "'1e999' is out of the range of a double");
  // It used to say "basic_filebuf::underflow error reading the file: Is a directory".
  fs::create_directories(dir / "frame.vtu");
  EXPECT_ERROR_NAMING(read_vtu((dir / "frame.vtu").string()), "frame.vtu", "cannot open the file: it is a directory");
  EXPECT_ERROR_NAMING(read_particle_file((dir / "frame.vtu").string()), "frame.vtu", "it is a directory");
  // A device would be read for ever (and a FIFO would block the open): refused at once.
  fs::create_symlink("/dev/zero", dir / "zero.vtu");
  EXPECT_ERROR_NAMING(read_particle_file((dir / "zero.vtu").string()), "zero.vtu", "it is not a regular file");
}

TEST(Vtu, CorruptedBytesGiveAnErrorOrATableNeverACrash) {
  const auto dir = test::temp_dir("vtu-fuzz");
  Frame().write(dir / "good.vtu", true);
  const std::string good = test::read_file(dir / "good.vtu");
  std::mt19937 rng(12345);
  for (int trial = 0; trial < 1000; ++trial) {
    const auto path = (dir / fmt::format("fuzz{}.vtu", trial)).string();
    std::string text = good;
    for (int k = 0; k < 1 + trial % 3; ++k) text[rng() % text.size()] = static_cast<char>(rng());
    test::write_file(path, text);
    try {
      const ParticleTable t = read_vtu(path);
      for (const auto& c : t.columns) ASSERT_EQ(c.values.size(), t.count * c.components);
    } catch (const Error& e) {
      ASSERT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
    }
  }
  fs::remove_all(dir);
}

TEST(Vtu, WriteErrorsNameThePathAndLeaveNoFile) {
  const Frame f;
  EXPECT_ERROR_NAMING(f.write("/nonexistent-dir/frame.vtu", false), "/nonexistent-dir/frame.vtu", "cannot create");
  // A full disk, simulated by a file-size limit: the write fails part way.
  const auto dir = test::temp_dir("vtu-full");
  const auto path = (dir / "big.vtu").string();
  std::vector<double> big(3 * 100000, 0.5);
  rlimit old{};
  ASSERT_EQ(getrlimit(RLIMIT_FSIZE, &old), 0);
  rlimit small = old;
  small.rlim_cur = 64 * 1024;
  const auto old_handler = std::signal(SIGXFSZ, SIG_IGN);  // fail with EFBIG instead of dying
  ASSERT_EQ(setrlimit(RLIMIT_FSIZE, &small), 0);
  const std::string e = error_of([&] { write_vtu(path, 100000, {"Points", 3, VtuType::Float64, big.data()}, {}); });
  setrlimit(RLIMIT_FSIZE, &old);
  std::signal(SIGXFSZ, old_handler);
  EXPECT_NE(e.find(path + ": cannot write"), std::string::npos) << e;
  EXPECT_FALSE(fs::exists(path));
  EXPECT_FALSE(fs::exists(path + ".tmp"));
}

TEST(Pvd, ListsFramesWithExactTimesAndRelativeFiles) {
  const auto dir = test::temp_dir("pvd");
  const auto pvd = (dir / "run.pvd").string();
  write_pvd(pvd, {{0.0, "frame_00000.vtu"}});
  write_pvd(pvd, {{0.0, "frame_00000.vtu"}, {0.1 + 0.2, "frame_00001.vtu"}, {2.5, (dir / "x/frame_2.vtu").string()}});
  const std::string text = test::read_file(pvd);
  EXPECT_NE(text.find("<VTKFile type=\"Collection\""), std::string::npos) << text;
  EXPECT_NE(text.find("timestep=\"0.30000000000000004\" group=\"\" part=\"0\" file=\"frame_00001.vtu\""),
            std::string::npos) << text;
  EXPECT_NE(text.find("file=\"x/frame_2.vtu\""), std::string::npos) << text;
  EXPECT_FALSE(fs::exists(pvd + ".tmp"));
  EXPECT_ERROR_NAMING(write_pvd(pvd, {{std::nan(""), "a.vtu"}}), pvd, "has time nan");
  if (std::string(PBF_PYTHON).empty()) GTEST_SKIP() << "no Python interpreter found at configure time";
  EXPECT_EQ(run_python("--pvd '" + pvd + "'"),
            "0.0 0 frame_00000.vtu\n0.30000000000000004 0 frame_00001.vtu\n2.5 0 x/frame_2.vtu\nexit 0\n");
}

TEST(Csv, ReadsHeaderCommentsBlankLinesAndSpaces) {
  const auto dir = test::temp_dir("csv");
  test::write_file(dir / "p.csv", "# particles\n\n x , y,z,\"mass\"\r\n0.1, 0.2 ,0.3,1e-3\n  # more\n\n-1,+2,3.5,4\n");
  const ParticleTable t = read_csv((dir / "p.csv").string());
  ASSERT_EQ(t.count, 2u);
  ASSERT_EQ(t.columns.size(), 4u);
  EXPECT_EQ(t.columns[3].name, "mass");
  EXPECT_EQ(t.find("x")->values, (std::vector<double>{0.1, -1}));
  EXPECT_EQ(t.find("y")->values, (std::vector<double>{0.2, 2}));
  EXPECT_EQ(t.find("mass")->values, (std::vector<double>{1e-3, 4}));
  EXPECT_EQ(t.find("z")->components, 1);
}

TEST(Csv, MalformedFilesNameTheFileAndLine) {
  const auto dir = test::temp_dir("csv-bad");
  const auto path = (dir / "bad.csv").string();
  auto expect = [&](const std::string& text, const std::string& words) {
    test::write_file(path, text);
    EXPECT_ERROR_NAMING(read_csv(path), path, words);
  };
  expect("x,y,z\n1,2,3\n1,2\n", "bad.csv:3: expected 3 fields (x,y,z), found 2");
  expect("x,y,z\n1,2,3,4\n", "bad.csv:2: expected 3 fields");
  expect("# c\nx,y,z\n1,2,abc\n", "bad.csv:3: column 'z': 'abc' is not a number");
  expect("x,y,z\n1,2,3x\n", "'3x' is not a number");
  expect("x,y,z\n1,,3\n", "column 'y': '' is not a number");
  expect("x,y,x\n1,2,3\n", "bad.csv:1: column 'x' appears twice");
  expect("x,,z\n1,2,3\n", "bad.csv:1: column 2 of the header has no name");
  expect("1,2,3\n4,5,6\n", "bad.csv:1: the first line must be a header");
  expect("", "bad.csv: empty file");
  expect("# only a comment\n\n", "bad.csv: empty file");
  expect("x,y,z\n\n", "bad.csv: no data rows after the header on line 1");
  EXPECT_ERROR_NAMING(read_csv((dir / "missing.csv").string()), "missing.csv", "cannot open");
}

// A UTF-8 byte-order mark (Excel's "CSV UTF-8") used to become part of the first column's
// name, so a file with x, y, z was refused for having no x.
TEST(Csv, AcceptsAUtf8ByteOrderMarkAndRefusesUtf16) {
  const auto dir = test::temp_dir("csv-bom");
  test::write_file(dir / "p.csv", "\xEF\xBB\xBFx,y,z\r\n0.1,0.2,0.3\r\n");
  const ParticleInput in = interpret_particles(read_particle_file((dir / "p.csv").string()));
  EXPECT_EQ(in.x, (std::vector<double>{0.1}));
  test::write_file(dir / "q.csv", "\xEF\xBB\xBF# exported\nx,y,z\n1,2,3\n");
  EXPECT_EQ(read_csv((dir / "q.csv").string()).count, 1u);
  test::write_file(dir / "w.csv", std::string("\xFF\xFEx\0,\0y\0", 8));
  EXPECT_ERROR_NAMING(read_csv((dir / "w.csv").string()), "w.csv:1: the file is UTF-16 text; save it as UTF-8 or ASCII",
                    "");
}

TEST(Csv, MalformedNumbersADirectoryAndADeviceAreNamed) {
  const auto dir = test::temp_dir("csv-numbers");
  const auto path = (dir / "p.csv").string();
  test::write_file(path, "x,y,z\n1,+-2,3\n");  // was read as -2
  EXPECT_ERROR_NAMING(read_csv(path), path, "p.csv:2: column 'y': '+-2' is not a number");
  test::write_file(path, "x,y,z\n1,2,1e999\n");
  EXPECT_ERROR_NAMING(read_csv(path), path, "column 'z': '1e999' is out of the range of a double");
  fs::create_directories(dir / "d.csv");
  EXPECT_ERROR_NAMING(read_csv((dir / "d.csv").string()), "d.csv", "cannot open the file: it is a directory");
  fs::create_symlink("/dev/zero", dir / "zero.csv");
  EXPECT_ERROR_NAMING(read_particle_file((dir / "zero.csv").string()), "zero.csv", "it is not a regular file");
}

TEST(ParticleInput, ScalarColumnsWithVelocityAndMass) {
  const auto dir = test::temp_dir("input-csv");
  test::write_file(dir / "p.CSV",
                   "id,x,y,z,vx,vy,vz,mass,T\n7,0.1,0.2,0.3,1,2,3,0.5,20\n8,0.4,0.5,0.6,-1,-2,-3,0.25,21\n");
  const ParticleInput in = interpret_particles(read_particle_file((dir / "p.CSV").string()));
  EXPECT_EQ(in.x, (std::vector<double>{0.1, 0.4}));
  EXPECT_EQ(in.y, (std::vector<double>{0.2, 0.5}));
  EXPECT_EQ(in.z, (std::vector<double>{0.3, 0.6}));
  EXPECT_EQ(in.vx, (std::vector<double>{1, -1}));
  EXPECT_EQ(in.vz, (std::vector<double>{3, -3}));
  EXPECT_EQ(in.mass, (std::vector<double>{0.5, 0.25}));
  EXPECT_EQ(in.ignored, (std::vector<std::string>{"id", "T"}));
}

TEST(ParticleInput, PositionVectorFromAVtuFrameAndZeroVelocityByDefault) {
  const auto dir = test::temp_dir("input-vtu");
  const std::vector<double> pos{1, 2, 3, 4, 5, 6};
  const std::vector<double> rho{1000, 1001};
  write_vtu((dir / "f.vtu").string(), 2, {"Points", 3, VtuType::Float64, pos.data()},
            {{"rho", 1, VtuType::Float64, rho.data()}});
  const ParticleInput in = interpret_particles(read_particle_file((dir / "f.vtu").string()));
  EXPECT_EQ(in.x, (std::vector<double>{1, 4}));
  EXPECT_EQ(in.z, (std::vector<double>{3, 6}));
  EXPECT_EQ(in.vy, (std::vector<double>{0, 0}));
  EXPECT_TRUE(in.mass.empty());
  EXPECT_EQ(in.ignored, (std::vector<std::string>{"rho"}));
}

TEST(ParticleInput, MissingOrBadColumnsAreErrorsNamingTheFile) {
  auto table = [](std::vector<Column> columns) {
    ParticleTable t{"parts.csv", 2, std::move(columns), 0, 2};
    return t;
  };
  auto col = [](const std::string& name, std::vector<double> v, int k = 1) { return Column{name, k, std::move(v)}; };
  const auto x = col("x", {0, 1}), y = col("y", {0, 1}), z = col("z", {0, 1});
  EXPECT_ERROR_NAMING(interpret_particles(table({col("a", {1, 2}), col("velocity", {0, 0, 0, 0, 0, 0}, 3)})),
                    "parts.csv", "no particle positions: expected a 3-component column 'position' or columns x, y, "
                                 "z (or ParaView's Points:0, Points:1, Points:2); found: a, velocity (3 components)");
  // ParaView's CSV export: vector components as NAME:0, NAME:1, NAME:2.
  const ParticleInput pv = interpret_particles(table({col("Points:0", {0, 1}), col("Points:1", {2, 3}),
                                                      col("Points:2", {4, 5}), col("velocity:0", {6, 7}),
                                                      col("velocity:1", {8, 9}), col("velocity:2", {10, 11})}));
  EXPECT_EQ(pv.y, (std::vector<double>{2, 3}));
  EXPECT_EQ(pv.vz, (std::vector<double>{10, 11}));
  EXPECT_TRUE(pv.ignored.empty());
  EXPECT_ERROR_NAMING(interpret_particles(table({x, y})), "parts.csv", "x, y, z go together, but z is missing");
  EXPECT_ERROR_NAMING(interpret_particles(table({x, y, z, col("vy", {0, 0})})), "parts.csv", "but vx is missing");
  EXPECT_ERROR_NAMING(interpret_particles(table({col("position", {0, 1, 2, 3}, 2)})), "parts.csv",
                    "column 'position' has 2 components, expected 3");
  EXPECT_ERROR_NAMING(interpret_particles(table({x, y, col("z", {0, std::nan("")})})), "parts.csv",
                    "particle 1 (0-based, in file order) has position (1, 1, nan)");
  EXPECT_ERROR_NAMING(interpret_particles(table({x, y, z, col("velocity", {0, 0, INFINITY, 0, 0, 0}, 3)})),
                    "parts.csv", "particle 0 (0-based, in file order) has velocity");
  EXPECT_ERROR_NAMING(interpret_particles(table({x, y, z, col("mass", {1, 0})})), "parts.csv", "particle 1 (0-based, "
                    "in file order) has mass 0");
  EXPECT_ERROR_NAMING(interpret_particles(table({x, y, col("z", {0})})), "parts.csv", "column 'z' holds 1 values");
  EXPECT_ERROR_NAMING(interpret_particles(ParticleTable{"none.csv", 0, {col("x", {}), col("y", {}), col("z", {})}, 0, 0}),
                    "none.csv", "holds no particles");
  EXPECT_ERROR_NAMING(read_particle_file("frames/p.xyz"), "frames/p.xyz", "unsupported particle file type '.xyz'; "
                    "supported: .vtu");
}

TEST(ParticleInput, MessagesListAFewColumnsAndValuesMustFitThePrecision) {
  std::vector<Column> many;
  for (int k = 0; k < 30; ++k) many.push_back(Column{"c" + std::to_string(k), 1, {0}});
  EXPECT_ERROR_NAMING(interpret_particles(ParticleTable{"wide.csv", 1, many, 0, 1}), "wide.csv",
                    "found: c0, c1, c2, c3, c4, c5, c6, c7, c8, c9, c10, c11, c12, c13, c14, c15, c16, c17, c18, c19, "
                    "and 10 more");
  auto one = [](double vx, double mass) {
    return ParticleTable{"p.csv", 1, {Column{"x", 1, {0}}, Column{"y", 1, {0}}, Column{"z", 1, {0}},
                                      Column{"vx", 1, {vx}}, Column{"vy", 1, {0}}, Column{"vz", 1, {0}},
                                      Column{"mass", 1, {mass}}}, 0, 1};
  };
  if (sizeof(real) == 4) {  // a float build: 1e39 would become infinite, 1e-50 zero
    EXPECT_ERROR_NAMING(interpret_particles(one(1e39, 1)), "p.csv", "has velocity (1e+39, 0, 0), not finite in single");
    EXPECT_ERROR_NAMING(interpret_particles(one(0, 1e-50)), "p.csv", "has mass 1e-50; masses must be positive and "
                      "finite in single precision");
  } else {
    EXPECT_EQ(interpret_particles(one(1e39, 1e-50)).vx[0], 1e39);
  }
}
