-- tests/mpi/inflow.lua: fluid that comes and goes, for the distributed-run tests (tests/mpi/run.py):
-- a pool in a tank's first third, a jet entering across its far wall (a 6 x 4 cm emitter facing -x,
-- at the height the first cut of every rank count passes) and a drain over the floor's middle
-- that the pool's spreading front reaches. Both cross the ranks' boundaries; the particles the
-- emitter creates are numbered as one process numbers them, wherever they land.
-- Writes OUT/f_*.txt (id, position, velocity), OUT/thermo.csv (the count, what came in and
-- what went out), OUT/probes.csv (a probe and a gauge beside the faces y = 0 and y = 0.2).
-- -v solver=wcsph for WCSPH; -v periodic=y makes the tank periodic across its width (the pool
-- fills the period; the jet's sheet spreads through the faces); -v profile=1 gives the jet's
-- velocity as a function of time and place (a profile across the opening that grows in time),
-- which every rank calls alike; -v buffer=1 gives the jet an inlet zone 4 cm deep; -v read=FILE continues from a restart, -v save=FILE writes one
-- at the end; -v steps=N runs until step N (default 200).
local s = 0.02
local wcsph = var.solver == "wcsph"
if var.read then
  pbf.read_restart(var.read)
else
  pbf.domain{lo = {0, 0, 0}, hi = {0.6, 0.2, 0.4}, periodic = var.periodic and {var.periodic} or nil}
  pbf.kernel_radius(2 * s)
  pbf.timestep(wcsph and 0.0005 or 0.002)
  pbf.lattice{lo = {0, 0, 0}, hi = {0.2, 0.2, 0.16}, spacing = s}
end
pbf.fix("gravity", "gravity", {acceleration = {0, 0, -9.81}})
if wcsph then
  pbf.fix("integrator", "leapfrog", {})
  pbf.fix("wcsph", "wcsph", {density = "continuity", sound_speed = 25})
  pbf.fix("viscosity", "sph_viscosity", {})
else
  pbf.fix("pbf", "pbf", {iterations = 4})
end
pbf.fix("walls", "box", {})
local jet = {center = {0.58, 0.1, 0.3}, normal = {-1, 0, 0}, size = {0.06, 0.04}, speed = 1.0}
if var.profile then
  jet.speed = nil
  jet.velocity = function(t, x, y, z)
    local across = (y - 0.1) / 0.03
    return {-(0.5 + 2 * t) * (1 - across * across), 0.2 * across, 0}
  end
end
if var.buffer then jet.buffer = 0.04 end
pbf.fix("jet", "emitter", jet)
pbf.fix("drain", "outflow", {region = "box", lo = {0.3, 0, 0}, hi = {0.4, 0.2, 0.03}})
pbf.compute("n", "count")
pbf.compute("in", "flow", {fix = "jet"})
pbf.compute("out", "flow", {fix = "drain"})
pbf.compute("v", "speed")
local out = var.out or "out/inflow"
pbf.fix("dump", "dump/text", {path = out .. "/f_*.txt", every = 50, fields = {"id", "position", "velocity"}})
pbf.compute("vel", "probe", {field = "velocity", points = {{0.25, 0.003, 0.05}, {0.35, 0.197, 0.02}}})
pbf.compute("depth", "gauge", {points = {{0.3, 0.001, 0}, {0.45, 0.199, 0}}})
pbf.fix("probes", "sample", {computes = {"vel", "depth"}, interval = 0.02, file = out .. "/probes.csv"})
pbf.thermo{every = 10, csv = out .. "/thermo.csv",
           columns = {"step", "n", "in.count", "in.mass", "out.count", "out.mass", "v.max"}}
pbf.run(tonumber(var.steps or 200) - pbf.step())
if var.save then pbf.write_restart(var.save) end
