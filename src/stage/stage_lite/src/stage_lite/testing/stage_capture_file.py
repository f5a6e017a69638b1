"""Read the files stage_capture writes (real Stage's own worlds run headless) into numpy.

stage_capture (test/golden/stage_capture/) records after loading and after each
World::Update(): the sim time, every position model's world pose x, y, a (m, m, rad; in
the world file's model order) and stall flag, and the flag count of each flag model (the
top-level models and every position model). The file is an 8-byte magic, a JSON header,
then fixed-size little-endian records; a file cut short mid-record keeps its whole records.
"""
import json
import struct

import numpy as np

MAGIC = b'STGCAP1\0'


def record_dtype(n_pos, n_flag):
    """The numpy dtype of one record for n_pos position models and n_flag flag models."""
    if n_pos < 0 or n_flag < 0:
        raise ValueError('model counts must be >= 0, got %r, %r' % (n_pos, n_flag))
    return np.dtype([('t_us', '<u8'), ('pose', '<f8', (n_pos, 3)), ('stall', 'u1', (n_pos,)),
                     ('flags', '<u4', (n_flag,))])


def parse(data):
    """(header, arrays) of a capture's bytes.

    arrays: t_s (T,) float64 sim time in s; pose (T, N, 3) float64 x, y, a; stall (T, N)
    bool; flags (T, F) uint32. Raises ValueError on a file that is not a capture.
    """
    if data[:8] != MAGIC:
        raise ValueError('not a stage_capture file (magic %r)' % data[:8])
    if len(data) < 12:
        raise ValueError('stage_capture file cut short in its header')
    (length,) = struct.unpack('<I', data[8:12])
    if len(data) < 12 + length:
        raise ValueError('stage_capture file cut short in its header')
    header = json.loads(data[12:12 + length].decode('utf-8'))
    n_pos = len(header['position_models'])
    n_flag = len(header['flag_models'])
    dtype = record_dtype(n_pos, n_flag)
    body = data[12 + length:]
    count = len(body) // dtype.itemsize
    rec = np.frombuffer(body, dtype=dtype, count=count)
    arrays = {
        't_s': rec['t_us'].astype(np.float64) / 1e6,
        'pose': np.array(rec['pose'], dtype=np.float64).reshape(count, n_pos, 3),
        'stall': np.array(rec['stall'], dtype=bool).reshape(count, n_pos),
        'flags': np.array(rec['flags'], dtype=np.uint32).reshape(count, n_flag),
    }
    return header, arrays


def load(path):
    """(header, arrays) of the capture file at path (see parse)."""
    with open(path, 'rb') as f:
        return parse(f.read())
