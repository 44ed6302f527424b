"""The package's surface: every public class, method, property and function says what it does,
and arrays of any numeric type and memory order are taken."""

import inspect

import numpy as np
import pytest

import vantage as vt


def public_members():
    for name in dir(vt):
        if name.startswith("_"):
            continue
        obj = getattr(vt, name)
        if isinstance(obj, (int, float)):
            continue
        yield name, obj
        if inspect.isclass(obj):
            for member, value in vars(obj).items():
                # Result classes have no constructor of their own; they keep object's __init__.
                constructible = member == "__init__" and value is not object.__init__ and \
                    not (value.__doc__ or "").startswith("Initialize self")
                if not member.startswith("_") or constructible:
                    yield f"{name}.{member}", value


@pytest.mark.parametrize("name, obj", list(public_members()))
def test_everything_has_a_docstring(name, obj):
    doc = (getattr(obj, "__doc__", None) or "").strip()
    if isinstance(obj, property) or inspect.isclass(obj):
        assert doc, name
    else:
        # pybind11 puts the signature first; a docstring of our own must follow it.
        lines = [line for line in doc.splitlines() if line.strip()]
        assert len(lines) >= 2, f"{name}: only {doc!r}"


def test_any_numeric_type_and_order_is_taken():
    spec = vt.GridSpec((0, 0, 0), 0.1, (6, 6, 6))
    fov = vt.SensorFov(min_range=0.0)
    points = np.array([[0.45, 0.25, 0.25], [0.35, 0.15, 0.35]])
    reference = vt.OccupancyGrid(spec)
    reference.integrate(points, np.eye(4), fov, mode="endpoint")
    other = vt.OccupancyGrid(spec)
    other.integrate(np.asfortranarray(points.astype(np.float32)), np.eye(4, dtype=int), fov,
                    mode="endpoint")
    f32 = points.astype(np.float32).astype(np.float64)
    again = vt.OccupancyGrid(spec)
    again.integrate(f32, np.eye(4), fov, mode="endpoint")
    np.testing.assert_array_equal(other.log_odds(), again.log_odds())
    assert reference.counts() == other.counts()
    assert reference.counts()["occupied"] == 2


def test_a_mapper_continues_an_existing_map():
    spec = vt.GridSpec((0, 0, 0), 0.1, (6, 6, 6))
    start = vt.OccupancyGrid(spec)
    p = np.full(spec.shape, 0.5)
    p[5, 5, 5] = 0.9
    start.set_probabilities(p)
    mapper = vt.Mapper(start, integration="endpoint")
    mapper.add_scan(np.array([[0.45, 0.25, 0.25]]), np.eye(4), vt.SensorFov(min_range=0.0))
    states = mapper.grid.states()
    assert states[5, 5, 5] == vt.OCCUPIED and states[4, 2, 2] == vt.OCCUPIED
    assert start.counts()["occupied"] == 1  # the mapper took a copy


def test_sequences_of_any_kind_are_taken():
    spec = vt.GridSpec([0, 0, 0], 0.1, np.array([6, 6, 6]))
    assert spec == vt.GridSpec((0, 0, 0), 0.1, (6, 6, 6)) and spec.dims == (6, 6, 6)
    with pytest.raises(ValueError, match="dims must hold 3 integers, got 2"):
        vt.GridSpec((0, 0, 0), 0.1, [6, 6])
    cloud = np.array([[0.45, 0.25, 0.25]])
    fov = vt.SensorFov(min_range=0.0)
    grid, plan = vt.plan((cloud,), [np.eye(4)], fov, spec, [vt.look_at((0, 0.3, 0.3), (1, 0.3, 0.3))])
    assert grid.counts()["occupied"] >= 1 and plan.best == 0
