-- periodic = {"w"}: refused, naming the parameter and the name
pbf.domain{lo = {0, 0, 0}, hi = {0.1, 0.1, 0.1}, periodic = {"x", "w"}}
