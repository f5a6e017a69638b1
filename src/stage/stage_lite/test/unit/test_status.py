"""stage_lite.view.status: Stage's clock string and the measured real-time factor."""
import pytest
from stage_lite.view.status import RateMeter, clock_string


@pytest.mark.parametrize('sim_ns, factor, paused, text', [
    (3_200_000_000, 1.1, False, ' 0m 03s 200msec [1.1]'),   # the Stage screenshot
    (0, 0.0, False, ' 0m 00s 000msec [0.0]'),
    (754_300_000_000, 38.14, True, ' 12m 34s 300msec [38.1] [ PAUSED ]'),
    (3_723_100_000_000, 1.0, False, '1h 2m 03s 100msec [1.0]'),
])
def test_clock_string_is_stages(sim_ns, factor, paused, text):
    assert clock_string(sim_ns, factor, paused) == text


def test_rate_meter_measures_over_its_window():
    meter = RateMeter(window_s=1.0)
    assert meter.factor() == 0.0
    for k in range(31):                          # 3 s of wall time at 2 x real time
        meter.add(100.0 + 0.1 * k, 0.2 * k)
    assert meter.factor() == pytest.approx(2.0, abs=1e-9)
    for k in range(1, 21):                       # then 2 s at real time
        meter.add(103.0 + 0.1 * k, 6.0 + 0.1 * k)
    assert meter.factor() == pytest.approx(1.0, abs=1e-9)
