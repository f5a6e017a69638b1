"""stage_lite: a Stage 4.3 stand-in (model modules import no rospy) and the stageros node."""
