-- poiseuille.lua: Poiseuille flow between two plates. Fluid at rest fills a channel between
-- no-slip plates at z = 0 and z = H, periodic along x (the flow) and y (a thin slab); a body
-- force F along x (the `gravity` fix) starts it at t = 0. WCSPH with the Laplacian viscosity
-- (Morris et al. 1997) and the box's no-slip wall term. The analytic flow (issue 32):
--   steady    u(z) = F / (2 nu) z (H - z),   centre line u_max = F H^2 / (8 nu)
--   start-up  u(z, t) = u(z) - sum_{n odd} 4 F H^2 / (nu pi^3 n^3) sin(n pi z / H) exp(-n^2 pi^2 nu t / H^2)
-- share/validation/poiseuille.py compares the probes with them (docs/validation/poiseuille.md).
--
--   pbfengine run scenarios/poiseuille.lua [-v t_end=8] [-v out=out] [-v spacing=0.005]
--
-- The defaults: H = 0.1 m, nu = 1e-3 m^2/s, F = 8e-3 m/s^2, so u_max = 0.01 m/s, the
-- Reynolds number u_max H / nu = 1 (laminar) and the viscous time H^2 / (pi^2 nu) = 1.01 s
-- (t_end = 8 s leaves exp(-8) of the slowest mode, 0.03% of u_max). The sound speed c0 = 30
-- u_max = 0.3 m/s: Mach 0.033 at the centre line, and 10.6 sqrt(F H) (the speed a pressure
-- must reach to hold the body force over H, were it not periodic). With 20 spacings across H
-- (spacing 5 mm, h = 2 spacings) the step is the viscous limit of `cfl`, 0.125 (h/2)^2 / nu =
-- 3.1 ms (the Courant step 0.15 h / c0 is 4.8 ms): 2,600 steps of 960 particles.
--
-- Variables: spacing (m, default H / 20), support (the kernel's radius in spacings, default
-- 2), height (H, m, default 0.1), nu (m^2/s, default 1e-3), force (F, m/s^2, default 8e-3),
-- sound_speed (m/s, default 30 u_max), length (along x, default 8 spacings), width (along y,
-- default 6 spacings; both at least 2 h), t_end (s, default 8), interval (s between probe
-- rows, default 0.05), out (directory, default "out"; the probes go to out/profile.csv).
-- The probes: 19 heights z = H/20 ... 19 H/20, each at 4 points (x, y) = (L/4 or 3L/4, W/4
-- or 3W/4), labelled z<k><a-d> with z = k H / 20; the script averages the 4.
local here = debug.getinfo(1, "S").source:match("^@(.*[/\\])") or "./"
package.path = here .. "../share/lua/?.lua;" .. package.path
local H = var.height or 0.1
local nu = var.nu or 1e-3
local F = var.force or 8e-3
local u_max = F * H * H / (8 * nu)
local s = var.spacing or H / 20
s = H / math.floor(H / s + 0.5)              -- a whole number of layers across
local h = (var.support or 2) * s
local L = var.length or 8 * s
local W = var.width or 6 * s
L = s * math.floor(L / s + 0.5)              -- whole lattices along the periods
W = s * math.floor(W / s + 0.5)
local c0 = var.sound_speed or 30 * u_max
local t_end = var.t_end or 8
local out = var.out or "out"
if out ~= "" then os.execute(string.format("mkdir -p '%s'", out)) end

pbf.domain{lo = {0, 0, 0}, hi = {L, W, H}, periodic = {"x", "y"}}
pbf.kernel_radius(h)
pbf.timestep(0.125 * (h / 2) ^ 2 / nu)       -- cfl chooses every step after the first
pbf.lattice{lo = {0, 0, 0}, hi = {L, W, H}, spacing = s}

pbf.fix("force", "gravity", {acceleration = {F, 0, 0}})
pbf.fix("integrator", "leapfrog", {})
pbf.fix("wcsph", "wcsph", {sound_speed = c0})
pbf.fix("viscosity", "sph_viscosity", {kind = "laplacian", nu = nu})
pbf.fix("cfl", "cfl", {})
pbf.fix("walls", "box", {no_slip = true})

local points, labels = {}, {}
for k = 1, 19 do
  for a, xy in ipairs({{0.25, 0.25}, {0.75, 0.25}, {0.25, 0.75}, {0.75, 0.75}}) do
    points[#points + 1] = {xy[1] * L, xy[2] * W, k * H / 20}
    labels[#labels + 1] = string.format("z%02d%s", k, string.sub("abcd", a, a))
  end
end
pbf.compute("u", "probe", {field = "velocity", points = points, labels = labels})
pbf.fix("profile", "sample", {computes = {"u"}, interval = var.interval or 0.05, file = out .. "/profile.csv"})

pbf.compute("err", "density_error")
pbf.compute("v", "speed")
pbf.thermo{every = math.max(1, math.floor(0.5 / (0.125 * (h / 2) ^ 2 / nu))),
           columns = {"step", "time", "dt", "err.avg", "err.max", "v.avg", "v.max"}}

print(string.format("poiseuille: %d particles, spacing %.4g m, h %.4g m, H %.4g m, nu %.4g m^2/s, F %.4g m/s^2, "
                    .. "u_max %.4g m/s, c0 %.4g m/s, viscous time %.4g s", pbf.count(), s, h, H, nu, F, u_max, c0,
                    H * H / (math.pi ^ 2 * nu)))
pbf.run_until(t_end)
