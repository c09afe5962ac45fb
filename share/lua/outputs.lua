-- outputs.lua: the optional outputs every scenario offers, switched on with -v variables:
--   images=T     PNG pictures every T simulated seconds, OUT/image_00000.png, ...
--   draw=surface the pictures and the movie show the water's surface instead of spheres
--   movie=PATH   an mp4 of pictures every movie_interval seconds (default 0.02)
--   vtk=T        ParaView frames every T seconds, OUT/vtk/frame_*.vtu and OUT/vtk/frame.pvd
--   surface=T    the fluid's surface every T seconds (dump/surface): OUT/surface/surface_*.vtp
--                with OUT/surface/surface.pvd for ParaView and surface_*.ply for Blender;
--                surface_kernel picks the field (anisotropic, isotropic, spheres)
--   outputs.frames(out, restart_default): the text frames and restarts (below)
-- `view` holds the dump/image parameters (camera, colour field and scale) that pictures and
-- the movie share. A scenario loads it with
--   package.path = (debug.getinfo(1, "S").source:match("^@(.*[/\\])") or "./") .. "../share/lua/?.lua;" .. package.path
--   require("outputs").add(out, {color = "speed", min = 0, max = 2, direction = {1, 2, -1}})
local outputs = {}

function outputs.add(out, view)
  local function picture(extra)
    local p = {}
    for k, v in pairs(view) do p[k] = v end
    for k, v in pairs(extra) do p[k] = v end
    p.draw = var.draw
    return p
  end
  if var.images then pbf.fix("images", "dump/image", picture{path = out .. "/image_*.png", interval = var.images}) end
  if var.movie then
    pbf.fix("movie", "dump/movie", picture{path = var.movie, interval = var.movie_interval or 0.02})
  end
  if var.vtk then pbf.fix("vtk", "dump/vtk", {path = out .. "/vtk/frame_*.vtu", interval = var.vtk}) end
  if var.surface then
    pbf.fix("surface", "dump/surface", {path = out .. "/surface/surface_*.vtp", also = {"ply"}, interval = var.surface,
                                        kernel = var.surface_kernel})
  end
end

-- Text frames every `interval` seconds (-v interval, default 0.02) in OUT, and restarts every
-- restart_interval seconds (default `restart_default`; 0 for none) or every restart_every
-- steps, the newest two kept; nothing when OUT is "".
function outputs.frames(out, restart_default)
  if out == "" then return end
  pbf.fix("frames", "dump/text", {path = out .. "/frame_*.txt", interval = var.interval or 0.02})
  if var.restart_every then
    pbf.fix("restarts", "restart", {path = out .. "/restart.*.restart", every = var.restart_every})
  elseif (var.restart_interval or restart_default) > 0 then
    pbf.fix("restarts", "restart", {path = out .. "/restart.*.restart",
                                    interval = var.restart_interval or restart_default})
  end
end

return outputs
