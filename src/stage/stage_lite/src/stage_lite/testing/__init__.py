"""stage_lite's test support, installed so that lessons' tests can use it (no rospy here)."""
