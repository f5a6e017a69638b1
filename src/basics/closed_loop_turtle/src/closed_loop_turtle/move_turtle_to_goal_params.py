"""move_turtle_to_goal's parameters: read once, checked, in one frozen dataclass.

The control law's defaults are the model's own (go_to_goal's Gains, Tolerances and Limits:
the lab's gains and tolerances, a Pioneer 3-DX's top speeds); the node adds its rate and the
world it accepts goals in.
"""
from dataclasses import dataclass

from course_common.arena import WORLD_SIZE_M
from course_common.param_loader import get_private
from course_common.params import check_number

from closed_loop_turtle.go_to_goal import Gains, Limits, Tolerances

DEFAULT_RATE_HZ = 100.0  # the lab's loop sleeps 0.01 s between commands


@dataclass(frozen=True)
class ControllerConfig:
    """move_turtle_to_goal's parameters, validated."""

    gains: Gains
    tolerances: Tolerances
    limits: Limits
    rate_hz: float
    world_size_m: float


def _number(name, default):
    return check_number('~' + name, get_private(name, default))


def _positive(name, default):
    return check_number('~' + name, get_private(name, default), low=0.0, low_open=True)


def load_config():
    """Reads and validates the private parameters. Raises ParamError or ValueError."""
    gains, tolerances, limits = Gains(), Tolerances(), Limits()  # the defaults
    k_rho, k_alpha, k_beta = (_number('k_rho', gains.k_rho), _number('k_alpha', gains.k_alpha),
                              _number('k_beta', gains.k_beta))
    try:
        gains = Gains(k_rho, k_alpha, k_beta)
    except ValueError as err:
        raise ValueError('parameters ~k_rho=%r, ~k_alpha=%r, ~k_beta=%r: %s (the lab\'s '
                         'conditions k_rho > 0, k_beta < 0, k_alpha > k_rho)'
                         % (k_rho, k_alpha, k_beta, err)) from None
    return ControllerConfig(
        gains=gains,
        tolerances=Tolerances(_positive('position_tolerance', tolerances.position_m),
                              _positive('heading_tolerance', tolerances.heading_rad)),
        limits=Limits(_positive('max_linear_mps', limits.max_linear_mps),
                      _positive('max_angular_radps', limits.max_angular_radps)),
        rate_hz=_positive('rate_hz', DEFAULT_RATE_HZ),
        world_size_m=_positive('world_size_m', WORLD_SIZE_M))
