# Sourced by the workspace's setup.sh/setup.bash (catkin env hook of turtle_lite).
# Debian's ROS 1 lives in /usr/bin/python3. When another python3 or python comes first on PATH
# (pyenv, conda, a venv) and cannot import rospy, the scripts with a `#!/usr/bin/env python3`
# shebang (rosservice in the course's launch files, rostest nodes) or Noetic's
# `#!/usr/bin/env python` (students' and the ROS wiki's scripts; Debian's python-is-python3
# makes /usr/bin/python) would start under it and fail: put /usr/bin first, once.
for _debian_python in python3 python; do
  if [ "$(command -v "$_debian_python")" != "/usr/bin/$_debian_python" ] \
     && ! "$_debian_python" -c 'import rospy' >/dev/null 2>&1; then
    export PATH="/usr/bin:$PATH"
    break
  fi
done
unset _debian_python
