"""Every public call, given bad input, raises an nbar.Error of the right class: never a bare
ValueError, TypeError or RuntimeError that ``except nbar.Error`` would miss."""

import pytest

import nbar

STEEL = "fourbar-steel-bars.yaml"


def raises(cls, call, *args, **kwargs):
    """The nbar.Error `call` raises, checked to be an instance of `cls`."""
    try:
        call(*args, **kwargs)
    except nbar.Error as e:
        assert isinstance(e, cls), f"{type(e).__name__} ({e.kind}: {e}) instead of {cls.__name__}"
        assert e.kind == cls.default_kind or cls is nbar.Error, (e.kind, cls.default_kind)
        return e
    except Exception as e:  # noqa: BLE001 -- the point of the test: nothing else may leave
        pytest.fail(f"{type(e).__name__} that is not an nbar.Error: {e}")
    pytest.fail(f"{call} raised nothing")


@pytest.fixture
def crank(examples):
    return nbar.load(examples / "fourbar-crank-rocker.yaml")


def test_loading(tmp_path):
    raises(nbar.ModelError, nbar.loads, "points: [", "broken.yaml")
    raises(nbar.ModelError, nbar.loads, "points: {O: [0, 0]}\nbodies: {a: [O, Q]}\n", "unknown.yaml")
    raises(nbar.ModelError, nbar.load, tmp_path / "missing.yaml")
    raises(nbar.BadInputError, nbar.load, 42)
    raises(nbar.BadInputError, nbar.loads, 42)
    raises(nbar.BadInputError, nbar.Model.from_dict, {"points": {"O": object()}})


def test_exporting_a_model_with_kinetics(examples):
    # Was a bare ValueError from the C++ writer's std::invalid_argument.
    e = raises(nbar.BadInputError, nbar.load(examples / STEEL).to_yaml)
    assert "only kinematic models" in e.message


def test_solving(crank):
    raises(nbar.BadInputError, crank.solve, steps=-1)
    raises(nbar.BadInputError, crank.solve, steps="ten")
    raises(nbar.BadInputError, crank.solve, order=9)
    raises(nbar.ColumnError, crank.solve, steps=5, columns="no-such-column")
    raises(nbar.BadInputError, crank.solve, steps=5, timeout=-1)
    raises(nbar.BadInputError, crank.columns, order="two")
    result = crank.solve(steps=5)
    raises(nbar.ColumnError, result.__getitem__, "no-such-column")
    raises(nbar.BadInputError, nbar.plot, result, "no-such-column")


def test_kinetics_and_stress(examples, crank):
    steel = nbar.load(examples / STEEL)
    raises(nbar.BadInputError, steel.stress, steps=5, sections=1)
    raises(nbar.BadInputError, steel.stress, steps=5, method="magic")
    raises(nbar.BadInputError, steel.stress, steps=5, method="fe", mesh_size=-1)
    raises(nbar.BadInputError, steel.dynamics, steps=-1)


def test_pictures(crank, tmp_path):
    raises(nbar.BadInputError, crank.draw, step=10**6, steps=5)
    raises(nbar.BadInputError, crank.draw, width=0, steps=5)
    raises(nbar.BadInputError, crank.draw, width="wide", steps=5)
    raises(nbar.BadInputError, crank.draw, traces="nowhere", steps=5)
    raises(nbar.BadInputError, crank.draw(steps=5).save, tmp_path / "pose.bmp")
    raises(nbar.BadInputError, crank.draw(steps=5).save, 42)
    raises(nbar.BadInputError, crank.draw(steps=5).save, tmp_path / "no-folder" / "pose.svg")
    raises(nbar.BadInputError, crank.animate, frames=3, fps=0, steps=5)
    raises(nbar.BadInputError, crank.animate, frames=3, width=-5, steps=5)
    animation = crank.animate(frames=2, width=120, height=100, steps=5)
    raises(nbar.BadInputError, animation.save, tmp_path / "a.avi")
    raises(nbar.BadInputError, animation.data, "avi")


def test_explain(crank):
    raises(nbar.BadInputError, crank.explain, step=10**6, steps=5)
    raises(nbar.BadInputError, crank.explain, step=-1)
    raises(nbar.BadInputError, crank.explain, step="first")


def test_synthesis(tmp_path):
    raises(nbar.ModelError, nbar.synth.task, {"task": "nonsense"})
    raises(nbar.ModelError, nbar.synth.load, tmp_path / "missing.yaml")
    raises(nbar.BadInputError, nbar.synth.load, 42)
    raises(nbar.BadInputError, nbar.synth.task, {"task": "five-point", "points": [object()]})
    # The pivots coincide: the solver's complaint, placed at the task.
    raises(nbar.ModelError, nbar.synth.five_point, ((0, 0), (0, 0)), [(1, 1), (2, 1), (3, 2), (4, 2), (5, 1)])
    raises(nbar.BadInputError, nbar.synth.five_point, ((0, 0),), [(1, 1)] * 5)
    raises(nbar.BadInputError, nbar.synth.burmester, [(0, 0)])
    raises(nbar.ModelError, nbar.synth.function, "log(", (1, 2), (0, 90), (0, 90))
    raises(nbar.BadInputError, nbar.synth.run, {"task": "five-point"}, top=-1)


def test_internal_errors_are_nbar_errors():
    assert issubclass(nbar.InternalError, nbar.Error)
    assert nbar.InternalError("x").kind == "internal"
