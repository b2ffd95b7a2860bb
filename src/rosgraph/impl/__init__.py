"""rosgraph.impl: the graph model rosgraph's command and rqt_graph's dot code read."""
