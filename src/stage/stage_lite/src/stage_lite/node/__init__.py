"""stageros, the node: stage_ros 1.8.0's interface on stage_lite's model (stage_lite.model).

The ROS glue (stageros_node, stage_publish, stage_services, step_loop, rospy_clock,
stageros_params) and its pure helpers (stageros_args, names, pacing, wire, map_msg: no rospy,
tested alone). The window and the pictures are stage_lite.view's.
"""
