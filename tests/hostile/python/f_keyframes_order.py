# keyframes whose times go back
# Expected: refused, Error: keyframes && key 2
import pbfengine
pbfengine.keyframes([{"t": 1}, {"t": 0.5}])
