// Dump styles: the chosen fields, in id order, with the values the particles hold; the VTK
// frames parse (by the engine's reader and by an independent Python one) and their .pvd
// lists each frame's simulated time; an unknown field names the valid ones; and a restart
// carries the frame counters on.
#include <gtest/gtest.h>

#include <cmath>
#include <fmt/format.h>
#include <fstream>
#include <sstream>

#include "engine/io/vtu.hpp"
#include "test_util.hpp"

using namespace pbf;
using pbf::test::read_file;
using pbf::test::run_engine;
using pbf::test::temp_dir;
using pbf::test::write_file;

namespace {

// Lines 1-5: 125 particles falling in a box, vorticity on.
const std::string kScene =
    "pbf.domain{lo = {0, 0, 0}, hi = {0.2, 0.2, 0.2}}; pbf.kernel_radius(0.02); pbf.timestep(0.001)\n"
    "pbf.lattice{lo = {0.05, 0.05, 0.05}, hi = {0.1, 0.1, 0.1}, spacing = 0.01}\n"
    "pbf.fix('g', 'gravity', {acceleration = {0, 0, -9.81}})\n"
    "pbf.fix('pbf', 'pbf', {}); pbf.fix('walls', 'box', {})\n"
    "pbf.fix('vort', 'vorticity', {})\n";

using pbf::test::read_frame_rows;

TEST(DumpVtk, FramesHoldTheParticlesValuesAndThePvdTheirTimes) {
  const auto dir = temp_dir("vtk");
  write_file(dir / "a.lua", kScene +
                                "pbf.fix('vtk', 'dump/vtk', {path = var.dir .. '/vtk/frame_*.vtu', every = 4,\n"
                                "  fields = {'id', 'velocity', 'speed', 'density_error', 'vorticity', 'mass'}})\n"
                                "pbf.fix('txt', 'dump/text', {path = var.dir .. '/txt/frame_*.txt', every = 4,\n"
                                "  fields = {'id', 'position', 'velocity', 'speed', 'vorticity', 'mass'}})\n"
                                "pbf.run(8)\n");
  auto r = run_engine("run " + (dir / "a.lua").string() + " -v dir=" + dir.string());
  ASSERT_EQ(r.code, 0) << r.output;
  for (int frame = 0; frame < 3; ++frame) {
    const auto text = read_frame_rows(dir / "txt" / fmt::format("frame_{:05d}.txt", frame));
    const ParticleTable vtu = read_vtu((dir / "vtk" / fmt::format("frame_{:05d}.vtu", frame)).string());
    ASSERT_EQ(vtu.count, 125u);
    ASSERT_EQ(text.size(), 125u);
    const Column *position = vtu.find("position"), *velocity = vtu.find("velocity"), *id = vtu.find("id"),
                 *speed = vtu.find("speed"), *vorticity = vtu.find("vorticity"), *mass = vtu.find("mass");
    ASSERT_TRUE(position && velocity && id && speed && vorticity && mass && vtu.find("density_error"));
    for (std::size_t i = 0; i < 125; ++i) {
      // Text writes the shortest form that reads back exactly: the values must agree bit for bit.
      const auto& row = text[i];
      ASSERT_EQ(row.size(), 12u);
      // Compared in the data's precision: text holds the shortest form of a float in float builds.
      auto same = [](double a, double b) { return real(a) == real(b); };
      EXPECT_EQ(id->values[i], row[0]);
      EXPECT_EQ(id->values[i], double(i));  // id order
      for (int c = 0; c < 3; ++c) {
        EXPECT_TRUE(same(position->values[3 * i + c], row[1 + c]));
        EXPECT_TRUE(same(velocity->values[3 * i + c], row[4 + c]));
        EXPECT_TRUE(same(vorticity->values[3 * i + c], row[8 + c]));
      }
      EXPECT_TRUE(same(speed->values[i], row[7]));
      EXPECT_NEAR(speed->values[i], std::hypot(row[4], row[5], row[6]), pbf::test::kRounding * (1 + row[7]));
      EXPECT_TRUE(same(mass->values[i], row[11]));
    }
  }
  const std::string pvd = read_file(dir / "vtk" / "frame.pvd");
  EXPECT_NE(pvd.find("timestep=\"0\" group=\"\" part=\"0\" file=\"frame_00000.vtu\""), std::string::npos) << pvd;
  EXPECT_NE(pvd.find("timestep=\"0.004\" group=\"\" part=\"0\" file=\"frame_00001.vtu\""), std::string::npos) << pvd;
  EXPECT_NE(pvd.find("timestep=\"0.008\" group=\"\" part=\"0\" file=\"frame_00002.vtu\""), std::string::npos) << pvd;

  // An implementation that shares nothing with the engine's reads the same files.
  if (std::string(PBF_PYTHON).empty()) GTEST_SKIP() << "no Python interpreter";
  const std::string check = std::string(PBF_PYTHON) + " " + PBF_SOURCE_DIR + "/tests/check_vtu.py ";
  auto py = pbf::test::Result{};
  FILE* pipe = popen((check + (dir / "vtk" / "frame_00002.vtu").string() + " 2>&1").c_str(), "r");
  ASSERT_TRUE(pipe);
  char buf[4096];
  std::size_t n;
  while ((n = fread(buf, 1, sizeof buf, pipe)) > 0) py.output.append(buf, n);
  EXPECT_EQ(pclose(pipe), 0) << py.output;
  EXPECT_NE(py.output.find("points 125"), std::string::npos) << py.output;
  EXPECT_NE(py.output.find("vorticity Float"), std::string::npos) << py.output;
}

TEST(Dumps, AnUnknownFieldListsTheValidOnes) {
  const auto dir = temp_dir("dump-field");
  write_file(dir / "a.lua", kScene + "pbf.fix('vtk', 'dump/vtk', {path = var.dir .. '/f_*.vtu', every = 1,\n"
                                     "  fields = {'velocity', 'presure'}})\npbf.run(1)\n");
  auto r = run_engine("run " + (dir / "a.lua").string() + " -v dir=" + dir.string());
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.output.find(":8: fix 'vtk' (dump/vtk): unknown field 'presure'; valid fields: position, velocity, "
                          "mass, lambda, vorticity, id, density, density_error, summed_density, speed, vorticity_magnitude"),
            std::string::npos)
      << r.output;
  write_file(dir / "b.lua", kScene + "pbf.fix('t', 'dump/text', {path = var.dir .. '/f.txt', every = 1})\n");
  r = run_engine("run " + (dir / "b.lua").string() + " -v dir=" + dir.string());
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.output.find("must contain one '*'"), std::string::npos) << r.output;
}

TEST(Dumps, RestartsCarryFrameCountersAndTheCollectionOn) {
  const auto dir = temp_dir("dump-restart");
  const std::string pipeline = "pbf.fix('vtk', 'dump/vtk', {path = var.dir .. '/f_*.vtu', every = 3})\n";
  write_file(dir / "a.lua", kScene + pipeline + "pbf.run(4)\npbf.write_restart(var.dir .. '/r')\npbf.run(5)\n");
  auto r = run_engine("run " + (dir / "a.lua").string() + " -v dir=" + dir.string());
  ASSERT_EQ(r.code, 0) << r.output;
  const std::string straight = read_file(dir / "f.pvd");
  std::filesystem::remove(dir / "f.pvd");
  write_file(dir / "b.lua", "pbf.read_restart(var.dir .. '/r')\n" + kScene.substr(kScene.find("pbf.fix('g'")) +
                                pipeline + "pbf.run(5)\n");
  r = run_engine("run " + (dir / "b.lua").string() + " -v dir=" + dir.string());
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_EQ(read_file(dir / "f.pvd"), straight);  // frames 0..3 at steps 0, 3, 6, 9
  EXPECT_NE(straight.find("f_00003.vtu"), std::string::npos) << straight;
}

}  // namespace

namespace {

// The width and height a PNG's IHDR chunk declares.
std::pair<int, int> png_size(const std::string& bytes) {
  auto be32 = [&](std::size_t at) {
    return (int(static_cast<unsigned char>(bytes[at])) << 24) | (int(static_cast<unsigned char>(bytes[at + 1])) << 16) |
           (int(static_cast<unsigned char>(bytes[at + 2])) << 8) | int(static_cast<unsigned char>(bytes[at + 3]));
  };
  if (bytes.size() < 24 || bytes.compare(0, 8, "\x89PNG\r\n\x1a\n") != 0 || bytes.compare(12, 4, "IHDR") != 0)
    return {0, 0};
  return {be32(16), be32(20)};
}

TEST(DumpImage, PngFramesOfTheRequestedSizeSameBytesAtOneAndTwoThreads) {
  const auto dir = temp_dir("image");
  write_file(dir / "a.lua", kScene + "pbf.fix('img', 'dump/image', {path = var.dir .. '/img_*.png', every = 5,\n"
                                     "  width = 320, height = 240, color = 'vorticity', colormap = 'coolwarm'})\n"
                                     "pbf.run(10)\n");
  for (int threads : {1, 2}) {
    auto r = run_engine("run " + (dir / "a.lua").string() + " -v dir=" + (dir / std::to_string(threads)).string() +
                        " --threads " + std::to_string(threads));
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_NE(r.output.find("img (dump/image)"), std::string::npos) << "no timing line of its own\n" << r.output;
  }
  for (int frame = 0; frame < 3; ++frame) {
    const std::string name = fmt::format("img_{:05d}.png", frame);
    const std::string one = read_file(dir / "1" / name), two = read_file(dir / "2" / name);
    EXPECT_EQ(png_size(one), std::make_pair(320, 240)) << name;
    EXPECT_TRUE(one == two) << name << " differs between 1 and 2 threads";
  }
  EXPECT_FALSE(std::filesystem::exists(dir / "1" / "img_00003.png"));
}

TEST(DumpMovie, AnMp4OfEveryFrameAndAClearErrorWithoutFfmpeg) {
  const auto dir = temp_dir("movie");
  write_file(dir / "a.lua", kScene + "pbf.fix('m', 'dump/movie', {path = var.dir .. '/m.mp4', every = 2,\n"
                                     "  width = 160, height = 120})\npbf.run(10)\npbf.run(10)\n");
  auto r = run_engine("run " + (dir / "a.lua").string() + " -v dir=" + dir.string());
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("wrote " + (dir / "m.mp4").string() + " (11 frames)"), std::string::npos) << r.output;
  // ffprobe (from the ffmpeg package) counts the frames the file holds: one movie over both runs.
  const std::string probe = fmt::format(
      "ffprobe -v error -count_frames -select_streams v:0 -show_entries stream=nb_read_frames,width,height "
      "-of csv=p=0 {} > {} 2>&1",
      (dir / "m.mp4").string(), (dir / "probe").string());
  ASSERT_EQ(std::system(probe.c_str()), 0) << read_file(dir / "probe");
  EXPECT_EQ(read_file(dir / "probe"), "160,120,11\n");

  const std::string no_ffmpeg = "PATH=/nonexistent " + std::string(PBF_BINARY) + " run --log none " +
                                (dir / "a.lua").string() + " -v dir=" + (dir / "x").string() + " > " +
                                (dir / "log").string() + " 2>&1";
  EXPECT_NE(std::system(no_ffmpeg.c_str()), 0);
  EXPECT_NE(read_file(dir / "log").find("dump/movie needs ffmpeg on the PATH"), std::string::npos)
      << read_file(dir / "log");
}

}  // namespace

namespace {

TEST(ReadParticles, AVtkFrameOrACsvStartsANewRun) {
  const auto dir = temp_dir("read-particles");
  write_file(dir / "a.lua", kScene + "pbf.fix('vtk', 'dump/vtk', {path = var.dir .. '/f_*.vtu', every = 10,\n"
                                     "  fields = {'velocity', 'mass'}})\npbf.run(10)\n");
  auto r = run_engine("run " + (dir / "a.lua").string() + " -v dir=" + dir.string());
  ASSERT_EQ(r.code, 0) << r.output;
  // Frame 1 as the scene of a new run: same particles, velocities and masses.
  write_file(dir / "b.lua",
             "pbf.domain{lo = {0, 0, 0}, hi = {0.2, 0.2, 0.2}}; pbf.kernel_radius(0.02); pbf.timestep(0.001)\n"
             "local r = pbf.read_particles(var.file)\n"
             "assert(r.count == 125 and r.mass == 0, 'count ' .. r.count .. ' mass ' .. r.mass)\n"
             "pbf.fix('t', 'dump/text', {path = var.dir .. '/t_*.txt', every = 1, fields = {'position', 'velocity', "
             "'mass'}})\npbf.run(0)\n");
  r = run_engine("run " + (dir / "b.lua").string() + " -v dir=" + dir.string() + " -v file=" +
                 (dir / "f_00001.vtu").string());
  ASSERT_EQ(r.code, 0) << r.output;
  const ParticleTable frame = read_vtu((dir / "f_00001.vtu").string());
  const auto rows = read_frame_rows(dir / "t_00000.txt");
  ASSERT_EQ(rows.size(), 125u);
  for (std::size_t i = 0; i < 125; ++i)
    for (int c = 0; c < 3; ++c) {
      EXPECT_EQ(real(rows[i][c]), real(frame.find("position")->values[3 * i + c]));
      EXPECT_EQ(real(rows[i][3 + c]), real(frame.find("velocity")->values[3 * i + c]));
      EXPECT_EQ(real(rows[i][6]), real(frame.find("mass")->values[i]));
    }

  // A CSV without masses gets the mass rule; a particle outside the domain names the row.
  write_file(dir / "p.csv", "x,y,z,vx,vy,vz\n0.1,0.1,0.1,0,0,1\n0.11,0.1,0.1,0,0,1\n");
  r = run_engine("run " + (dir / "b.lua").string() + " -v dir=" + dir.string() + " -v file=" + (dir / "p.csv").string());
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.output.find("count 2 mass 0.00"), std::string::npos) << r.output;  // the mass rule's value
  write_file(dir / "q.csv", "x,y,z\n0.1,0.1,0.1\n0.1,0.1,0.3\n");
  r = run_engine("run " + (dir / "b.lua").string() + " -v dir=" + dir.string() + " -v file=" + (dir / "q.csv").string());
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.output.find((dir / "q.csv").string() + ": particle 1 at (0.1, 0.1, 0.3) is outside the domain"),
            std::string::npos)
      << r.output;
}

}  // namespace
