-- dambreak_wcsph.lua: the dam break of dambreak.lua (Martin & Moyce 1952) solved by weakly
-- compressible SPH instead of PBF: a leapfrog integrator, a summed density, the Tait
-- equation of state with sound speed c0 = 10 sqrt(2 g 2a), Monaghan's artificial viscosity,
-- and a time step chosen every step by the CFL condition (thermo's dt column). Same tank,
-- walls, gravity, computes, frames and restarts as dambreak.lua, whose variables it takes
-- (particles defaults to 8000 here). docs/physics.md compares the two solvers.
--
--   pbfengine run scenarios/dambreak_wcsph.lua [-v particles=8000] [-v t_end=1.0] [-v alpha=0.1]
var.solver = "wcsph"
dofile((debug.getinfo(1, "S").source:match("^@(.*[/\\])") or "./") .. "dambreak.lua")
