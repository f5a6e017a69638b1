# Sourced by the workspace's setup.sh/setup.bash (catkin env hook of turtle_lite).
# Debian's ROS 1 lives in /usr/bin/python3. When another python3 comes first on PATH (pyenv,
# conda, a venv) and cannot import rospy, the ROS tools with a `#!/usr/bin/env python3`
# shebang (rosservice in the course's launch files, rostest nodes) would start under it and
# fail: put /usr/bin first, once.
if [ "$(command -v python3)" != "/usr/bin/python3" ] && ! python3 -c 'import rospy' >/dev/null 2>&1; then
  export PATH="/usr/bin:$PATH"
fi
