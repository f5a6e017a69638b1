"""The floor plan as a nav_msgs/OccupancyGrid body, for the optional latched /map (no rospy).

stageros has no /map; with ~publish_map the node publishes the world's static obstacles so rviz
draws the floor plan under the robots. Stage's grid (the world's ``resolution``, 2 cm) is
shrunk by a whole factor to about ~map_resolution (a cell is occupied if any cell under it
is): a 54 x 58.7 m floor at 2 cm is 8 million cells, at 5 cm 1.3 million.
The body is packed with numpy's tobytes(): genpy packs int8[] one Python int per cell.
"""
import struct

import numpy as np

from ..model.floor import coarsen
from .wire import HEADER_STAMP, string_bytes

OCCUPIED = 100
FREE = 0
_INFO = struct.Struct('<IIfII7d')   # map_load_time, resolution, width, height, origin pose


def map_grid(occupancy, wanted_resolution_m):
    """(cells int8 rows x cols, resolution m, origin x, origin y) of a world occupancy()."""
    grid, ox, oy, res = occupancy
    if not wanted_resolution_m > 0:
        raise ValueError('the map resolution must be > 0 m, not %r' % (wanted_resolution_m,))
    factor = max(1, round(wanted_resolution_m / res))
    cells = np.where(coarsen(np.asarray(grid, dtype=bool), factor), OCCUPIED, FREE)
    return cells.astype(np.int8), res * factor, ox, oy


def grid_body(secs, nsecs, frame_id, cells, resolution_m, origin_x, origin_y, seq=0):
    """The serialised OccupancyGrid (no length prefix): row 0 of cells is the lowest y."""
    rows, cols = cells.shape
    data = np.ascontiguousarray(cells, dtype=np.int8)
    return b''.join((HEADER_STAMP.pack(seq, secs, nsecs), string_bytes(frame_id),
                     _INFO.pack(secs, nsecs, resolution_m, cols, rows,
                                origin_x, origin_y, 0.0, 0.0, 0.0, 0.0, 1.0),
                     struct.pack('<I', data.size), data.tobytes()))
