"""The lessons' robot ids and team sizes: MAX_ROBOTS_NUM and their argv checks (no rospy).

The Stage lessons (stage_multi's move_robot, multi_sync's move_robot_sync and monitor) take a
robot id or a team size as argv[1] and print the course's own messages when it is wrong.
"""

# The lesson's MAX_ROBOTS_NUM: team sizes 1..20, robot ids 0..19.
MAX_ROBOTS = 20

# The lesson's error texts, verbatim (students compare them with the slides).
MISSING_TEAM_SIZE = 'You must specify team size.'
BAD_TEAM_SIZE = 'The team size must be an integer number between 1 and %d' % MAX_ROBOTS
MISSING_ROBOT_ID = 'You must specify robot id.'
BAD_ROBOT_ID = "The robot's ID must be an integer number between 0 and %d" % (MAX_ROBOTS - 1)


def parse_plain_int(text):
    """Return text as an int, or None when it is not a plain decimal integer (no atoi)."""
    text = text.strip()
    digits = text[1:] if text[:1] in '+-' else text
    if not digits.isdigit() or not digits.isascii():
        return None
    return int(text)


def parse_team_size(args):
    """Return the team size from the monitor's argv (without the program name).

    Raises ValueError with the lesson's message when it is missing, not an integer or
    outside 1..MAX_ROBOTS. Unlike the lesson's atoi, '4abc' and '4.0' are rejected.
    """
    if not args:
        raise ValueError(MISSING_TEAM_SIZE)
    size = parse_plain_int(args[0])
    if size is None or not 1 <= size <= MAX_ROBOTS:
        raise ValueError(BAD_TEAM_SIZE)
    return size


def parse_robot_id(args):
    """Return the robot id from move_robot's argv (without the program name).

    Raises ValueError with the lesson's message when it is missing, not an integer or
    outside 0..MAX_ROBOTS-1 (the lesson's check let 20 through: an off-by-one).
    """
    if not args:
        raise ValueError(MISSING_ROBOT_ID)
    robot_id = parse_plain_int(args[0])
    if robot_id is None or not 0 <= robot_id < MAX_ROBOTS:
        raise ValueError(BAD_ROBOT_ID)
    return robot_id


def valid_robot_id(robot_id):
    """True when robot_id is an id a team member may have (0..MAX_ROBOTS-1; bools refused,
    though Python counts them as ints: 'robot_True' names no robot)."""
    return isinstance(robot_id, int) and not isinstance(robot_id, bool) \
        and 0 <= robot_id < MAX_ROBOTS
