-- progress.lua: a slow run (every step waits 0.1 s of wall time), long enough for the
-- progress line pbfengine prints every 10 s (docs/scripting.md, pbf.run)
pbf.kernel_radius(0.2)
pbf.timestep(0.01)
pbf.lattice{lo = {0, 0, 0}, hi = {0.5, 0.5, 0.5}, spacing = 0.1}
pbf.every("wait", 1, function() os.execute("sleep 0.1") end)
pbf.run_until(1.2)
