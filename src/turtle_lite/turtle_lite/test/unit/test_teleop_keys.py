"""Unit tests for turtle_teleop_key's key mapping and configuration (teleop_keys)."""

import math

import pytest
from turtle_lite.teleop_keys import (
    BANNER,
    TeleopConfig,
    is_quit_key,
    key_to_command,
)

DEFAULT = TeleopConfig()
SCALED = TeleopConfig(scale_linear=3.0, scale_angular=0.5)


@pytest.mark.parametrize(
    ("key", "config", "expected"),
    [
        # Arrow sequences end in A-D; only that last byte drives (turtlesim 1.11).
        (ord("A"), DEFAULT, (2.0, 0.0)),
        (ord("B"), DEFAULT, (-2.0, 0.0)),
        (ord("D"), DEFAULT, (0.0, 2.0)),
        (ord("C"), DEFAULT, (0.0, -2.0)),
        (ord("A"), SCALED, (3.0, 0.0)),
        (ord("B"), SCALED, (-3.0, 0.0)),
        (ord("D"), SCALED, (0.0, 0.5)),
        (ord("C"), SCALED, (0.0, -0.5)),
    ],
)
def test_arrow_bytes_map_to_scaled_twist(key, config, expected):
    # Values are copied, not computed: exact up to float rounding (1e-12).
    assert key_to_command(key, config) == pytest.approx(expected, abs=1e-12)


@pytest.mark.parametrize(
    "key",
    [0x1B, ord("["), ord("a"), ord("b"), ord("c"), ord("d"), ord("x"), ord("E"), ord("q"),
     ord(" "), 0x00, 0xFF],
)
def test_other_bytes_publish_nothing(key):
    assert key_to_command(key, DEFAULT) is None


def test_escape_sequence_drives_once():
    commands = [key_to_command(b, DEFAULT) for b in b"\x1b[A"]
    assert [c for c in commands if c is not None] == [(2.0, 0.0)]


@pytest.mark.parametrize(("key", "quits"), [(ord("q"), True), (ord("Q"), False),
                                             (ord("A"), False), (0x1B, False)])
def test_only_lowercase_q_quits(key, quits):
    assert is_quit_key(key) is quits


@pytest.mark.parametrize("key", [-1, 256, 3.0, "A", None, True])
def test_bad_key_raises(key):
    with pytest.raises(ValueError):
        key_to_command(key, DEFAULT)


def test_defaults_are_turtlesims():
    assert (DEFAULT.scale_linear, DEFAULT.scale_angular) == (2.0, 2.0)


def test_int_scale_becomes_float():
    config = TeleopConfig(scale_linear=3, scale_angular=-1)
    assert isinstance(config.scale_linear, float)
    assert key_to_command(ord("C"), config) == (0.0, 1.0)


@pytest.mark.parametrize(
    "kwargs",
    [
        {"scale_linear": "fast"},
        {"scale_angular": None},
        {"scale_linear": True},
        {"scale_linear": math.nan},
        {"scale_angular": math.inf},
        {"scale_angular": [1.0]},
    ],
)
def test_bad_scale_raises(kwargs):
    with pytest.raises(ValueError, match="scale_"):
        TeleopConfig(**kwargs)


def test_banner_is_verbatim():
    assert BANNER == (
        "Reading from keyboard",
        "---------------------------",
        "Use arrow keys to move the turtle. 'q' to quit.",
    )
