-- tests/mpi/dambreak.lua: a small PBF dam break (gravity, pbf, vorticity, xsph, box walls, a
-- solid block, a damping zone at the far end) for the distributed-run tests (tests/mpi/run.py). The column starts in the
-- first 3/8 of the tank and reaches its far wall, so it crosses every cut the decomposition makes among 2 or 3
-- ranks (all of which start inside the column), and the boxes are rebalanced as it goes.
-- Writes OUT/f_*.txt (dump/text: id, position, velocity, the density and the vorticity's
-- magnitude, which read neighbours), OUT/vtk (ParaView frames: .vtu, or .pvtu and pieces on
-- several ranks, and frame.pvd), OUT/surface (dump/surface's meshes), OUT/probes.csv (probes, gauges, extent, a percentile)
-- and OUT/thermo.csv.
-- -v read=FILE continues from a restart, -v save=FILE writes one at the end; -v steps=N runs
-- until step N (default 250).
local s = 0.02
if var.read then
  pbf.read_restart(var.read)
else
  pbf.domain{lo = {0, 0, 0}, hi = {0.8, 0.2, 0.4}}
  pbf.kernel_radius(2 * s)
  pbf.timestep(0.002)
  pbf.lattice{lo = {0, 0, 0}, hi = {0.3, 0.2, 0.3}, spacing = s}
end
pbf.fix("gravity", "gravity", {acceleration = {0, 0, -9.81}})
pbf.fix("pbf", "pbf", {error = 0.002, max_iterations = 20})
pbf.fix("vorticity", "vorticity", {})
pbf.fix("xsph", "xsph", {})
pbf.fix("walls", "box", {})
-- A damping zone over the tank's far end, which the front reaches.
pbf.fix("zone", "damping", {from = {0.6, 0, 0}, to = {0.8, 0, 0}, rate = 20})
-- A block in the column, across the first cut (x = 0.15 at 2 ranks): its particles meet the
-- wall on both sides of it, and its load sums both ranks' pushes.
pbf.fix("block", "solid", {shape = "box", lo = {0.1, 0.06, 0}, hi = {0.2, 0.14, 0.1}})
pbf.compute("load", "load", {solid = "block"})
pbf.compute("ke", "kinetic_energy")
pbf.compute("pe", "potential_energy")
pbf.compute("v", "speed")
pbf.compute("err", "density_error")
pbf.compute("it", "iterations")
pbf.compute("n", "count")  -- every rank's particles, not this rank's
local out = var.out or "out/mpi"
pbf.fix("dump", "dump/text", {path = out .. "/f_*.txt", every = 50,
                              fields = {"id", "position", "velocity", "density", "vorticity_magnitude"}})
pbf.fix("vtk", "dump/vtk", {path = out .. "/vtk/frame_*.vtu", every = 50, fields = {"id", "velocity", "density"}})
pbf.fix("surface", "dump/surface", {path = out .. "/surface/surface_*.ply", every = 100, fields = {"velocity", "density"}})
-- Probes and gauges, each point measured by the rank whose box holds it.
pbf.compute("vel", "probe", {field = "velocity", points = {{0.1, 0.1, 0.05}, {0.4, 0.1, 0.02}, {0.75, 0.05, 0.1}}})
pbf.compute("rho", "probe", {field = "density", points = {{0.1, 0.1, 0.05}, {0.35, 0.12, 0.03}}})
pbf.compute("depth", "gauge", {points = {{0.05, 0.1, 0}, {0.3, 0.1, 0}, {0.6, 0.1, 0}, {0.79, 0.19, 0}}})
pbf.compute("box", "extent")
pbf.compute("front", "front", {axis = "x", percentile = 95})
pbf.fix("probes", "sample", {computes = {"vel", "rho", "depth", "box", "front"}, interval = 0.01,
                             file = out .. "/probes.csv"})
pbf.thermo{every = 10, csv = out .. "/thermo.csv",
           columns = {"step", "particles", "n", "ke", "pe", "v.max", "v.avg", "err.avg", "err.max", "it.avg", "it.error",
                      "load.fx", "load.fy", "load.fz"}}
print(string.format("dambreak: %d particles on %d rank(s)", pbf.count(), pbf.ranks()))
pbf.run(tonumber(var.steps or 250) - pbf.step())
if var.save then pbf.write_restart(var.save) end
