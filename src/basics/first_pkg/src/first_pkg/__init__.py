"""The ROS basics deck's first package (first_pkg): the hello node."""
