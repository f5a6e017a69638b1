"""stage_lite's model of Stage 4.3: world files, bodies, the grid, ray casts, motion (no rospy)."""
