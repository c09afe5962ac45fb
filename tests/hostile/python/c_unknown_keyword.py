# Simulation(thread=2)
# Expected: refused, TypeError: unexpected keyword argument 'thread'
import pbfengine
pbfengine.Simulation(thread=2)
