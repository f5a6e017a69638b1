"""The autopilot's parameter names: each says its unit; the names before units still work.

Pure (no rospy): the node asks which name to read for each parameter and logs the warning.
Until the names carried units (``~speed`` where multi_sync says ``~speed_mps``) the
autopilot read the old names; a launch file or a rosparam YAML written for them keeps
working, with a deprecation warning naming the new name.
"""
from dataclasses import dataclass

#: The parameter names with units, in the node's order.
NAMES = ('centre_x_m', 'centre_y_m', 'half_width_m', 'half_height_m', 'speed_mps',
         'lookahead_m', 'max_turn_radps')
#: Name before units -> name with units (same value, same unit).
OLD_NAMES = {'centre_x': 'centre_x_m', 'centre_y': 'centre_y_m', 'half_width': 'half_width_m',
             'half_height': 'half_height_m', 'speed': 'speed_mps', 'lookahead': 'lookahead_m',
             'max_turn': 'max_turn_radps'}
_OLD_OF = {new: old for old, new in OLD_NAMES.items()}


@dataclass(frozen=True)
class NameChoice:
    """Which private parameter to read for one setting, and the warning to log (or None)."""

    read: str
    warning: str = None


def choose_name(name, is_set):
    """The name to read for the parameter ``name`` (one of NAMES), given which names are set.

    is_set(private_name) says whether ``~private_name`` is set. The new name wins; the old
    name is read only when the new one is unset, with a warning naming the new one; with
    neither set the new name is read (its default applies). Raises ValueError for a name
    that is not one of NAMES.
    """
    if name not in _OLD_OF:
        raise ValueError('unknown autopilot parameter %r: expected one of %s'
                         % (name, ', '.join(NAMES)))
    old = _OLD_OF[name]
    if not is_set(old):
        return NameChoice(name)
    if is_set(name):
        return NameChoice(name, '~%s is deprecated and ignored: ~%s is set too and wins'
                          % (old, name))
    return NameChoice(old, '~%s is deprecated: rename it ~%s (same value and unit)'
                      % (old, name))
