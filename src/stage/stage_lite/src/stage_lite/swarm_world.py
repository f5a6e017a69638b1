"""Stage worlds of N swarmbots: Stage's benchmark robot on an open floor of any size.

`bench/make_swarm_worlds.py [OUT_DIR] [N ...]` writes them (world_text, write_worlds).

The robot is benchmark/hospital.world's swarmbot as Stage 4.3.0 ships it: a 0.1 m position
model with 12 infrared rangers (one sample each, 2 m, 30 degrees wide, every 30 degrees) and
the `expand_swarm` controller; the world's settings are the hospital's (0.02 m resolution,
4 threads, flat out). The hospital's 1,000 robots stand in one strip, 200 columns by 5 rows
0.25 m apart, on a 140 m x 60 m floor; here that floor is a tile: N robots take ceil(N/1000)
tiles, each with its strip where the hospital has it (the last one only partly filled),
tiles side by side in a near-square grid, with no walls but one round the whole floor, so
every robot has the hospital's room to spread into. N = 1000 is the hospital without its
walls; N = 1 is one robot on the hospital's floor.

world_text(N, ros=True) is the same swarm for a controller that is a ROS node (the swarm
package): no `ctrl`, and the 12 infrared readings as one sensor of 12 samples. stage_ros
1.8.0 publishes only the first sensor of each ranger (and WARNs at every step for each
robot whose ranger has more), so Stage's 12 one-beam sensors would reach ROS as a 1-beam
base_scan. One sensor of 12 samples over 330 degrees has its beams 30 degrees apart, as the
IR sensors are, all 2 m; the ranger is turned 165 degrees on the robot so that beam i looks
along 30 i degrees, the heading of Stage's IR sensor i (tf's base_link -> base_laser_link
says so: yaw 165 degrees, and the scan's angle_min is -165 degrees in that frame).
"""
import math
import os

TILE_M = (140.0, 60.0)        # the hospital's floor
STRIP_COLUMNS, STRIP_ROWS = 200, 5
PITCH_M = 0.25
STRIP_ORIGIN_M = (-59.0, -15.0)   # the hospital's r0, from the floor's centre
PER_TILE = STRIP_COLUMNS * STRIP_ROWS
WALL_M = 0.2                  # the border's thickness
COUNTS = (1, 10, 100, 1000, 10000, 100000)
#: ros=True: the ring of 12 beams 30 degrees apart over 330 degrees, turned so that beam i
#: looks along 30 i degrees (IR sensor i)
RING_SAMPLES, RING_FOV_DEG, RING_YAW_DEG = 12, 330, 165

HEAD = """# %(n)d swarmbots on an open %(w).0f m x %(h).0f m floor (bench/make_swarm_worlds.py):
# Stage's benchmark swarmbot (worlds/benchmark/hospital.world) and its expand_swarm controller
resolution 0.02
speedup -1
paused 0
threads 4

model
(
  name "floor"
  size [%(w).3f %(h).3f 0.500]
  pose [0 0 0 0]
  color "gray30"
  gui_nose 0
  gui_grid 0
  gui_move 0
  gui_outline 0
  obstacle_return 1
  ranger_return 1
%(blocks)s)

define ir sensor
(
  samples 1
  range [0 2]
  fov 30
  color_rgba [1 0 0 0.3]
)

define swarmbot position
(
  size [0.100 0.100 0.100]
  color "random"
  ranger
  (
    pose [0 0 -0.050 0]
%(irs)s  )
  ctrl "expand_swarm"
)

"""


ROS_ROBOT = """define ir_ring sensor
(
  samples %(samples)d
  range [0 2]
  fov %(fov)d
  color_rgba [1 0 0 0.3]
)

define swarmbot position
(
  size [0.100 0.100 0.100]
  color "random"
  ranger
  (
    pose [0 0 -0.050 %(yaw)d]
    ir_ring()
  )
)

""" % dict(samples=RING_SAMPLES, fov=RING_FOV_DEG, yaw=RING_YAW_DEG)


def tiles_grid(count):
    """(columns, rows) of tiles for `count` tiles: a near-square floor."""
    tiles = max(1, math.ceil(count / PER_TILE))
    # tiles are 140 x 60: more rows than columns make the floor square
    cols = max(1, round(math.sqrt(tiles * TILE_M[1] / TILE_M[0])))
    rows = math.ceil(tiles / cols)
    return cols, rows


def places(count):
    """The robots' (x, y) in metres, from the floor's centre, in naming order."""
    cols, rows = tiles_grid(count)
    out = []
    for t in range(math.ceil(count / PER_TILE)):
        cx = (t % cols - (cols - 1) / 2.0) * TILE_M[0]
        cy = (t // cols - (rows - 1) / 2.0) * TILE_M[1]
        for k in range(min(PER_TILE, count - t * PER_TILE)):
            out.append((cx + STRIP_ORIGIN_M[0] + (k // STRIP_ROWS) * PITCH_M,
                        cy + STRIP_ORIGIN_M[1] + (k % STRIP_ROWS) * PITCH_M))
    return out


def border_blocks(width, height):
    """Four wall blocks round the floor's edge, in metres (they span the model's size, so
    Stage's scaling of blocks to the size leaves them as written)."""
    hw, hh, t = width / 2.0, height / 2.0, WALL_M
    rects = ((-hw, -hh, hw, -hh + t), (-hw, hh - t, hw, hh),
             (-hw, -hh, -hw + t, hh), (hw - t, -hh, hw, hh))
    lines = []
    for x0, y0, x1, y1 in rects:
        lines.append('  block( points 4 point[0] [%.3f %.3f] point[1] [%.3f %.3f] '
                     'point[2] [%.3f %.3f] point[3] [%.3f %.3f] z [0 0.5] )\n'
                     % (x0, y0, x1, y0, x1, y1, x0, y1))
    return ''.join(lines)


def world_text(count, ros=False):
    """The world of `count` swarmbots; ros=True: for a ROS controller (module docstring)."""
    cols, rows = tiles_grid(count)
    width, height = cols * TILE_M[0], rows * TILE_M[1]
    irs = ''.join('    ir( pose [0 0 0 %d] )\n' % (30 * i) for i in range(12))
    head = HEAD % dict(n=count, w=width, h=height, blocks=border_blocks(width, height),
                       irs=irs)
    if ros:
        # the same floor and settings; the robot's definitions replaced by ROS_ROBOT
        head = head[:head.index('define ir sensor')] + ROS_ROBOT
        head = head.replace('its expand_swarm controller', 'one sensor of 12 samples, for '
                            'a ROS controller (swarm_world.py, ros=True)')
    text = [head]
    for i, (x, y) in enumerate(places(count)):
        text.append('swarmbot( name "r%d" pose [ %.3f %.3f 0 0 ] )\n' % (i, x, y))
    return ''.join(text)


def write_worlds(out_dir, counts=COUNTS, ros=False):
    """Writes swarm_<N>.world (ros=True: swarm_ros_<N>.world) for each N; returns {N: path}."""
    os.makedirs(out_dir, exist_ok=True)
    out = {}
    for n in counts:
        if n < 1:
            raise ValueError('a swarm needs at least one robot, not %d' % n)
        path = os.path.join(out_dir, ('swarm_ros_%d.world' if ros else 'swarm_%d.world') % n)
        with open(path, 'w') as f:
            f.write(world_text(n, ros))
        out[n] = path
    return out
