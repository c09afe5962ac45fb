-- ctrl_c.lua: the dam break, stopped as Ctrl-C stops it: at step var.at (default 10) the
-- script sends its own process SIGINT, the signal Ctrl-C sends (docs/scripting.md, "Ctrl-C").
-- Takes the variables of scenarios/dambreak.lua; run it from the repository root.
pbf.every("ctrl_c", var.at or 10, function()
  io.popen("kill -INT $PPID"):close()  -- $PPID: the shell's parent, this pbfengine
end)
dofile("scenarios/dambreak.lua")
