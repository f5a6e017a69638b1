"""The ROS basics deck's talker and listener (chat_pkg)."""
