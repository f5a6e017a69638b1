# The desktop's terminals (bash --rcfile): the user's own ~/.bashrc, then the course
# workspace, then the student's overlay, so `rosrun` and `roslaunch` find both and a pyenv or
# conda set up in ~/.bashrc cannot hide Debian's python3 (the workspace's setup puts /usr/bin
# first).
# shellcheck disable=SC1090,SC1091
[ -f ~/.bashrc ] && . ~/.bashrc
. "$COURSE_WS_SETUP"
cd "$COURSE_DESKTOP_WORKSPACE" 2>/dev/null || cd
if [ -f "$COURSE_DESKTOP_WORKSPACE/devel/setup.bash" ]; then
  . "$COURSE_DESKTOP_WORKSPACE/devel/setup.bash"
  overlay="overlaid by $COURSE_DESKTOP_WORKSPACE/devel"
else
  overlay="your workspace $COURSE_DESKTOP_WORKSPACE: catkin_make there, then source devel/setup.bash"
fi
PS1='\[\e[1;32m\]\u@course\[\e[0m\]:\[\e[1;34m\]\w\[\e[0m\]\$ '
echo "Course workspace ready ($overlay)."
echo "Try: roslaunch multi_sync multi_sync.launch   New terminal: Ctrl+Alt+T (or right-click the desktop)"
unset overlay
