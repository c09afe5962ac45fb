-- Writes a restart seed of fuzz/corpus/restart/ (fuzz/README.md): a small restart made by
-- the engine itself, with the fields and fix states a solver saves. 8 particles, so each
-- file stays under 2 kB.
--
--   for s in pbf wcsph; do
--     pbfengine run fuzz/seeds/restarts.lua -v solver=$s -v out=fuzz/corpus/restart -v tmp=/tmp/pbf-seeds
--   done
pbf.domain{lo = {0, 0, 0}, hi = {0.2, 0.2, 0.2}}
pbf.kernel_radius(0.02)
pbf.timestep(0.001)
pbf.lattice{lo = {0.05, 0.05, 0.05}, hi = {0.07, 0.07, 0.07}, spacing = 0.01}
pbf.fix("g", "gravity", {acceleration = {0, 0, -9.81}})
if var.solver == "wcsph" then
  -- The acceleration and (continuity) density fields; cfl's and wcsph's saved state.
  pbf.fix("integrator", "leapfrog", {})
  pbf.fix("wcsph", "wcsph", {density = "continuity", sound_speed = 5})
  pbf.fix("viscosity", "sph_viscosity", {})
  pbf.fix("cfl", "cfl", {})
else
  pbf.fix("pbf", "pbf", {})
end
pbf.fix("walls", "box", {})
-- Fixes with saved state: a dump's frame counter and collection, the restart fix's files.
pbf.fix("frames", "dump/vtk", {path = var.tmp .. "/frames/f_*.vtu", every = 1})
pbf.fix("save", "restart", {path = var.tmp .. "/r.*.restart", every = 2})
pbf.run(3)
pbf.write_restart(var.out .. "/" .. var.solver .. ".restart")
