"""swarm: one ROS node driving a whole Stage swarm (Stage's expand_swarm law on base_scan)."""
