"""A robot team across hosts: network namespaces as hosts, the ROS network check."""
