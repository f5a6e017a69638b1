"""The lesson markers' colours (r, g, b in 0..1), which rviz's view is checked for (no rospy).

turtle_lite's lesson_markers draws the arena and the robots' trails in them; rviz.screen looks
for them on a screenshot.
"""

#: Robot colours, cycled in the order robots are first seen: distinct on rviz's dark grey
#: background and none of them the arena's yellow.
PALETTE = ((0.20, 0.80, 0.20), (0.95, 0.30, 0.25), (0.30, 0.60, 1.00), (0.90, 0.40, 0.90),
           (0.20, 0.90, 0.90), (1.00, 0.60, 0.20), (0.70, 0.70, 0.70), (0.60, 0.45, 0.25))
ARENA_RGB = (1.0, 0.85, 0.0)


def robot_color(index):
    """The colour of the index-th robot seen (index >= 0), cycling through PALETTE."""
    if not isinstance(index, int) or isinstance(index, bool) or index < 0:
        raise ValueError('robot index %r: expected an integer >= 0' % (index,))
    return PALETTE[index % len(PALETTE)]
