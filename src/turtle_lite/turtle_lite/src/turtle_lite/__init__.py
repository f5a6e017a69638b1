"""turtle_lite: a turtlesim-compatible simulator (model modules import no rospy)."""
