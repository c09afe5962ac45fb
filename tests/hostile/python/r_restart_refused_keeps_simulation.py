# a refused restart leaves the Simulation empty
# Expected: refused, Error: g.restart && not a pbfengine restart
import pbfengine
sim = pbfengine.Simulation(log=None, log_level="warn")
open("g.restart", "wb").write(b"garbage" * 10)
try:
    sim.read_restart("g.restart")
finally:
    assert sim.count == 0 and sim.step == 0, "the refused restart changed the Simulation"
