"""A light stand-in for rqt_graph: the live ROS graph, drawn with graphviz."""
