"""The approach to a charger fasr and fasr2 share (their Dock(), examples/ctrl/fasr.cc,
fasr2.cc): beyond 0.5 m cruise at 0.4 m/s toward it unless avoiding, nearer creep at
0.02 m/s, stop within 0.08 m, and back off at 0.01 m/s while stalled against it; and the
three modes both switch between. Not a controller itself (no init)."""

CRUISE_SPEED = 0.4    # m/s
CREEP_DISTANCE = 0.5  # m: closer than this, creep
DOCK_CREEP = 0.02     # m/s
DOCK_CLOSE = 0.08     # m: docked
DOCK_BACK = -0.01     # m/s when stalled against it

MODE_WORK, MODE_DOCK, MODE_UNDOCK = 'work', 'dock', 'undock'


def start_working(robot):
    """The state both start in: working, not avoiding, no charger seen."""
    robot.mode = MODE_WORK
    robot.avoid_count = 0
    robot.charger_ahoy = False
    robot.charger_bearing = 0.0
    robot.charger_range = 0.0
    robot.charger_heading = 0.0


def run_mode(robot):
    """The step of the robot's mode: its dock(), work() or undock()."""
    if robot.mode == MODE_DOCK:
        robot.dock()
    elif robot.mode == MODE_WORK:
        robot.work()
    else:
        robot.undock()


def approach(pos, charger_range, a_goal, obstacle_avoid):
    """One Dock() step toward a charger seen charger_range away, turning at a_goal;
    obstacle_avoid() is the robot's avoid step (True while avoiding). True when it stopped
    there: docked."""
    if charger_range > CREEP_DISTANCE:
        if not obstacle_avoid():
            pos.set_x_speed(CRUISE_SPEED)
            pos.set_turn_speed(a_goal)
        return False
    pos.set_turn_speed(a_goal)
    pos.set_x_speed(DOCK_CREEP)
    docked = charger_range < DOCK_CLOSE
    if docked:
        pos.stop()
    if pos.stalled():
        pos.set_x_speed(DOCK_BACK)
    return docked
