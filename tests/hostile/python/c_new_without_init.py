# a Simulation made by __new__, never initialised, then used
# Expected: refused, TypeError: __init__ || Error: __init__
import pbfengine
sim = pbfengine.Simulation.__new__(pbfengine.Simulation)
sim.field("position")
