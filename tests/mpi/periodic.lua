-- tests/mpi/periodic.lua: a PBF dam break in a tank periodic along x and y (walls on z only:
-- the box fix leaves the periodic axes), for the distributed-run tests (tests/mpi/run.py,
-- case identical_periodic). The column collapses both ways along x, through the periodic
-- faces, and meets itself on the other side; every rank's box meets a periodic face or a
-- neighbour's, so ghosts cross the faces as images. Writes OUT/f_*.txt (id, position,
-- velocity, density, |omega|), OUT/probes.csv (probes and gauges beside and across the
-- periodic faces, extent, a percentile), OUT/thermo.csv and OUT/surface/surface_*.ply.
-- -v steps=N (default 200);
-- -v read=FILE continues from a restart, -v save=FILE writes one at the end.
local s = 0.02
if var.read then
  pbf.read_restart(var.read)
else
  pbf.domain{lo = {0, 0, 0}, hi = {0.8, 0.2, 0.4}, periodic = {"x", "y"}}
  pbf.kernel_radius(2 * s)
  pbf.timestep(0.002)
  pbf.lattice{lo = {0.2, 0, 0}, hi = {0.5, 0.2, 0.3}, spacing = s}
end
pbf.fix("gravity", "gravity", {acceleration = {0, 0, -9.81}})
pbf.fix("pbf", "pbf", {error = 0.002, max_iterations = 20})
pbf.fix("vorticity", "vorticity", {})
pbf.fix("xsph", "xsph", {})
pbf.fix("walls", "box", {})
pbf.compute("ke", "kinetic_energy")
pbf.compute("v", "speed")
pbf.compute("err", "density_error")
pbf.compute("it", "iterations")
local out = var.out or "out/periodic"
-- The surface across the periodic faces (meshed in slabs along z, the one axis not periodic).
pbf.fix("surface", "dump/surface", {path = out .. "/surface/surface_*.ply", every = 100})
pbf.fix("dump", "dump/text", {path = out .. "/f_*.txt", every = 40,
                              fields = {"id", "position", "velocity", "density", "vorticity_magnitude"}})
-- Points beside the faces x = 0 and x = 0.8, y = 0 and y = 0.2: their neighbourhoods reach across.
pbf.compute("vel", "probe", {field = "velocity", points = {{0.005, 0.1, 0.03}, {0.795, 0.195, 0.03}, {0.35, 0.002, 0.05}}})
pbf.compute("rho", "probe", {field = "density", points = {{0.002, 0.003, 0.02}, {0.4, 0.1, 0.05}}})
pbf.compute("depth", "gauge", {points = {{0.001, 0.1, 0}, {0.799, 0.199, 0}, {0.35, 0, 0}}})
pbf.compute("box", "extent")
pbf.compute("front", "front", {axis = "x", percentile = 95})
pbf.fix("probes", "sample", {computes = {"vel", "rho", "depth", "box", "front"}, interval = 0.01,
                             file = out .. "/probes.csv"})
pbf.thermo{every = 10, csv = out .. "/thermo.csv",
           columns = {"step", "particles", "ke", "v.max", "v.avg", "err.avg", "err.max", "it.avg"}}
print(string.format("periodic: %d particles on %d rank(s)", pbf.count(), pbf.ranks()))
pbf.run(tonumber(var.steps or 200) - pbf.step())
if var.save then pbf.write_restart(var.save) end
