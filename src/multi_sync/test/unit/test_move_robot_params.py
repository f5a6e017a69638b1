"""Unit tests of multi_sync.move_robot_params: move_robot's parameters, defaults and bounds."""
import pytest
from course_common.params import ParamError
from multi_sync.motion import STAGE, TURTLESIM, WORLD_SIZE_M, DriveLimits
from multi_sync.move_robot_params import (
    STAGE_MAX_DISTANCE_M,
    MoveRobotConfig,
    drive_limits,
    load_config,
)


def server(**params):
    """A parameter server holding params (private names without '~'), as get_param."""
    def get_param(name, default):
        assert name.startswith('~'), name
        return params.get(name[1:], default)
    return get_param


@pytest.mark.parametrize('simulator', [None, TURTLESIM, STAGE])
def test_defaults_are_drive_limits(simulator):
    config = load_config(server(), simulator)
    limits = DriveLimits()
    assert (config.speed_mps, config.stop_distance_m, config.min_gap_m) == \
        (limits.speed_mps, limits.stop_distance_m, limits.min_gap_m) == (0.2, 0.5, 1.0)
    assert (config.rate_hz, config.cone_half_angle_rad, config.input_timeout_s) == \
        (10.0, 0.35, 2.0)
    assert config == MoveRobotConfig(world_size_m=None if simulator == STAGE else WORLD_SIZE_M)


def test_stage_reads_no_world_size():
    def get_param(name, default):
        assert name != '~world_size_m', 'move_robot_sync read ~world_size_m'
        return default
    assert load_config(get_param, STAGE).world_size_m is None
    assert load_config(server(world_size_m='not read'), STAGE).world_size_m is None


@pytest.mark.parametrize('params, simulator, text', [
    ({'speed_mps': -0.2}, None, 'parameter ~speed_mps = -0.2: expected a finite number in (0, 10]'),
    ({'rate_hz': 0}, STAGE, 'parameter ~rate_hz = 0'),
    ({'stop_distance_m': float('nan')}, None, 'parameter ~stop_distance_m = nan'),
    ({'min_gap_m': 'far'}, TURTLESIM, "parameter ~min_gap_m = 'far'"),
    ({'cone_half_angle_rad': 4.0}, STAGE, 'parameter ~cone_half_angle_rad = 4.0'),
    ({'stop_distance_m': 150.0}, STAGE,
     'parameter ~stop_distance_m = 150.0: expected a finite number in [0, 100]'),
    ({'stop_distance_m': 150.0}, None,  # beyond both simulators' bounds: refused at once
     'parameter ~stop_distance_m = 150.0: expected a finite number in [0, 100]'),
    ({'min_gap_m': 100.5}, STAGE, 'parameter ~min_gap_m = 100.5: expected a finite number in '
     '[0, 100]'),
    ({'stop_distance_m': 8.0}, TURTLESIM,
     'parameter ~stop_distance_m = 8.0: expected a finite number in [0, 5.54444]'),
    ({'world_size_m': 0.5}, TURTLESIM, 'parameters ~stop_distance_m and ~world_size_m: '
     'stop_distance_m must be less than half the world (0.5 m), got 0.5'),
])
def test_bad_values_are_refused_by_name(params, simulator, text):
    with pytest.raises(ParamError if 'parameter ~' in text else ValueError) as err:
        load_config(server(**params), simulator)
    assert text in str(err.value)


@pytest.mark.parametrize('distance', [8.0, STAGE_MAX_DISTANCE_M])
def test_stage_bounds_the_distances_by_a_lasers_reach(distance):
    config = load_config(server(stop_distance_m=distance, min_gap_m=distance), STAGE)
    assert (config.stop_distance_m, config.min_gap_m) == (distance, distance)


@pytest.mark.parametrize('params', [
    {'stop_distance_m': 8.0}, {'min_gap_m': 20.0}, {'stop_distance_m': 50.0, 'min_gap_m': 100.0},
])
def test_move_robot_loads_stages_distances_before_its_simulator_is_known(params):
    # move_robot (either simulator): its first pose names the simulator, after the load.
    config = load_config(server(**params), None)
    for name, value in params.items():
        assert getattr(config, name) == value


@pytest.mark.parametrize('params', [
    {}, {'stop_distance_m': 8.0}, {'min_gap_m': 20.0}, {'world_size_m': 0.5},
    {'stop_distance_m': STAGE_MAX_DISTANCE_M, 'min_gap_m': STAGE_MAX_DISTANCE_M},
])
def test_on_stage_move_robot_drives_by_stages_bounds(params):
    config = load_config(server(**params), None)
    limits = drive_limits(config, STAGE)
    assert (limits.speed_mps, limits.stop_distance_m, limits.min_gap_m) == \
        (config.speed_mps, config.stop_distance_m, config.min_gap_m)
    assert limits.world_size_m is None  # no square on Stage


@pytest.mark.parametrize('params, text', [
    ({'stop_distance_m': 8.0},
     'parameter ~stop_distance_m = 8.0: expected a finite number in [0, 5.54444]'),
    ({'min_gap_m': 20.0}, 'parameter ~min_gap_m = 20.0: expected a finite number in [0, 11.0889]'),
    ({'world_size_m': 0.5}, 'parameters ~stop_distance_m and ~world_size_m: '
     'stop_distance_m must be less than half the world (0.5 m), got 0.5'),
])
def test_on_turtlesim_move_robot_refuses_what_does_not_fit_the_square(params, text):
    config = load_config(server(**params), None)
    with pytest.raises(ValueError) as err:
        drive_limits(config, TURTLESIM)
    assert text in str(err.value)


@pytest.mark.parametrize('params, stop_m, world_m', [
    ({}, 0.5, WORLD_SIZE_M),
    ({'stop_distance_m': 5.5}, 5.5, WORLD_SIZE_M),
    ({'stop_distance_m': 2.0, 'world_size_m': 4.5}, 2.0, 4.5),
])
def test_on_turtlesim_move_robot_drives_in_its_square(params, stop_m, world_m):
    limits = drive_limits(load_config(server(**params), None), TURTLESIM)
    assert (limits.stop_distance_m, limits.world_size_m) == (stop_m, world_m)
