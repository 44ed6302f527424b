"""The ray model through the bindings: docs/model.md's worked check, pinned in
tests/gain/ray_model_test.cpp, and the model's properties."""

import numpy as np
import pytest

import vantage as vt

# a = 0.997, cells [0.12, 0.12, 0.5, 0.5, 0.97, 0.5] (docs/model.md, "Worked check").
WORKED_CELLS = [0.12, 0.12, 0.5, 0.5, 0.97, 0.5]
WORKED_VISIBILITY = [1.0, 0.9995898464202707, 0.9991282570004986, 0.9902502264739204,
                     0.9793955677542567, 0.47427131583438575]
WORKED_POSTERIOR = [0.12, 0.018282034169898334, 0.01870196843434485, 0.023394515240657922,
                    0.5262545341824687, 0.5124517724733383]
WORKED_GAIN = [0.0, 0.39767800907352396, 0.8659108962037153, 0.8399026256972619,
               -0.8036183261778592, 0.00044741628433397906]


def test_worked_check_of_model_md():
    trace = vt.RayModel(0.997).trace(WORKED_CELLS)
    assert len(trace) == 6
    np.testing.assert_allclose(trace.visibility, WORKED_VISIBILITY, rtol=0, atol=1e-9)
    np.testing.assert_allclose(trace.posterior, WORKED_POSTERIOR, rtol=0, atol=1e-9)
    np.testing.assert_allclose(trace.gain, WORKED_GAIN, rtol=0, atol=1e-9)
    np.testing.assert_array_equal(trace.occupancy, WORKED_CELLS)
    np.testing.assert_allclose(trace.t, 0.997 ** np.arange(6), rtol=1e-12)


def test_gain_is_entropy_difference():
    trace = vt.RayModel(0.997).trace(WORKED_CELLS)
    for p, q, g in zip(trace.occupancy, trace.posterior, trace.gain):
        assert g == pytest.approx(vt.entropy_bits(p) - vt.entropy_bits(q), abs=1e-15)


def test_visibility_through_unobserved_cells_tends_to_its_limit():
    # docs/model.md: through unobserved cells (p = 0.5) v tends to 0.1 / (1.1 - t), t = a^m.
    a = 0.997
    trace = vt.RayModel(a).trace(np.full(3000, 0.5))
    assert np.all((trace.visibility >= 0.0) & (trace.visibility <= 1.0))
    assert np.all(np.diff(trace.visibility) <= 0.0)
    m = np.arange(3000)
    limit = 0.1 / (1.1 - a ** m)
    assert abs(trace.visibility[-1] - limit[-1]) < 1e-3


def test_alpha_one_never_loses_sight_through_free_cells():
    trace = vt.RayModel(1.0).trace([0.12] * 50)
    np.testing.assert_allclose(trace.visibility, 1.0, atol=1e-12)
