-- periodic = {1}: refused (a list of names)
pbf.domain{lo = {0, 0, 0}, hi = {0.1, 0.1, 0.1}, periodic = {1}}
