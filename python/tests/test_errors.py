"""Bad input from Python: exceptions with the CLI's message and its place, never a crash."""

import os
import signal
import threading
import time

import pytest

import nbar

BASE = """points: {O: [0, 0], A: [1, 0]}
ground: [O]
bodies: {crank: [O, A]}
"""


def test_syntax_error_has_file_line_and_column():
    with pytest.raises(nbar.ModelError) as e:
        nbar.loads(BASE + "drivers: [{angle: crank, from: 0, to: 90}\n", "bad.yaml")
    err = e.value
    assert err.file == "bad.yaml" and err.line is not None and err.column is not None
    assert str(err).startswith(f"bad.yaml:{err.line}:{err.column}: ")
    assert err.kind == "invalid_model"


def test_unknown_point_is_located_at_its_line():
    text = BASE + "drivers:\n  - {angle: crank, from: 0, to: 90}\nforces:\n  - {point: Q, force: [0, 1]}\n"
    with pytest.raises(nbar.ModelError) as e:
        nbar.loads(text, "m.yaml")
    assert (e.value.line, e.value.column) == (7, 13) and "Q" in e.value.message


def test_wrong_driver_count_is_a_model_error():
    with pytest.raises(nbar.ModelError) as e:
        nbar.loads(BASE, "m.yaml")
    assert "driver" in e.value.message


def test_missing_file_names_the_file():
    with pytest.raises(nbar.Error) as e:
        nbar.load("no/such/model.yaml")
    assert "no/such/model.yaml" in str(e.value)


def test_a_loop_that_cannot_close_cannot_assemble():
    text = """points: {O2: [0, 0], O4: [200, 0], A: [40, 0], B: [120, 40]}
ground: [O2, O4]
bodies: {crank: [O2, A], coupler: [A, B], rocker: [O4, B]}
lengths: {crank: 40, coupler: 50, rocker: 50}
drivers: [{angle: crank, from: 0, to: 360}]
"""
    with pytest.raises(nbar.AssemblyError) as e:
        nbar.loads(text, "short.yaml").solve(steps=5)
    assert e.value.kind == "cannot_assemble" and e.value.message


def test_check_gives_the_whole_mechanisms_limits_where_the_sweep_stops(examples):
    # A Watt I six-bar whose dyad straightens (at 15.2758 deg) long before its four-bar's toggle
    # (99.7151 deg): check gives the dyad's, and the sweep driven past it stops there.
    text = (examples / "watt-sixbar-limited.yaml").read_text().replace("to: 15,", "to: 60,")
    m = nbar.loads(text, "watt.yaml")
    s = m.check()
    assert [w.code for w in s.warnings] == ["input_limited"]
    limit = s.limits["ahead"][0]
    assert limit["kind"] == "limit" and limit["bodies"] == ["link5", "link6"]
    assert s.limits["stop"] == limit["value"]
    assert s.limits["behind"][0]["value"] == pytest.approx(-limit["value"], rel=1e-12)
    with pytest.raises(nbar.LimitError) as e:
        m.solve(steps=601)
    assert e.value.result["input"][-1] <= limit["value"]
    assert e.value.result["input"][-1] >= limit["value"] - 0.1


def test_the_same_sweep_rocks_with_at_limits_reverse(examples):
    # The Watt I six-bar driven past its dyad's limit rocks instead of stopping: it turns back at
    # check's limit (15.2758 deg) and at its mirror, and one cycle ends on its start.
    text = (examples / "watt-sixbar-limited.yaml").read_text().replace("to: 15,", "to: 60,")
    m = nbar.loads(text, "watt.yaml")
    limit = m.check().limits["ahead"][0]["value"]
    r = m.solve(steps=200, at_limits="reverse", cycles=1)  # 201 would put two samples on the turns
    turns = r["reversals"]
    assert list(turns[:3]) == [0, 0, 0] and turns[-1] == 2
    assert max(r["input"]) < limit and max(r["input"]) > limit - 1.0
    assert min(r["input"]) > -limit and min(r["input"]) < -limit + 1.0
    assert r["input"][-1] == pytest.approx(r["input"][0], abs=1e-12)
    assert r["link5.angle"][-1] == pytest.approx(r["link5.angle"][0], abs=1e-9)
    with pytest.raises(nbar.BadInputError):
        m.solve(steps=11, at_limits="sideways")


def test_toggle_stop_raises_with_the_rows_so_far(examples):
    text = (examples / "fourbar-crank-rocker.yaml").read_text().replace("lengths: {crank: 80, rocker: 150}",
                                                                       "lengths: {crank: 130, rocker: 150}")
    m = nbar.loads(text, "long-crank.yaml")
    assert [w.code for w in m.check().warnings] == ["input_limited"]  # check says so before the sweep
    with pytest.raises(nbar.LimitError) as e:
        m.solve(steps=361)
    partial = e.value.result
    assert not partial.complete and 0 < partial.rows < 361
    assert partial.stop_reason in str(e.value)
    # Where the CLI says it: at the model's `sweep:` (or its first driver).
    sweep_line = 1 + text[:text.index("sweep:")].count("\n")
    assert (e.value.line, e.value.column) == (sweep_line, 1)
    assert str(e.value).startswith(f"long-crank.yaml:{sweep_line}:1: ")
    again = m.solve(steps=361, partial=True)
    assert again.rows == partial.rows and again.stop_reason == partial.stop_reason


def test_unknown_column_suggests_the_right_case(examples):
    m = nbar.load(examples / "compressor-myszka.yaml")
    with pytest.raises(nbar.BadInputError) as e:
        m.solve(columns="C.X")
    assert "C.X" in str(e.value)
    r = m.solve(steps=3, columns="C.x")
    with pytest.raises(nbar.BadInputError, match="did you mean 'C.x'") as missing:
        r["C.X"]
    assert missing.value.kind == "bad_input" and str(missing.value).startswith("no column 'C.X'")
    # A result is a mapping: an unknown column is a KeyError too, so `in` and get() work.
    assert isinstance(missing.value, KeyError) and isinstance(missing.value, nbar.ColumnError)
    assert "C.X" not in r and "C.x" in r
    assert r.get("C.X") is None and r.get("C.X", 7) == 7
    assert r.get("C.x") is r["C.x"]


def test_errors_raised_by_the_module_say_their_kind(examples):
    m = nbar.load(examples / "fourbar-crank-rocker.yaml")
    with pytest.raises(nbar.BadInputError) as e:
        m.draw().save("pose.bmp")
    assert e.value.kind == "bad_input"
    assert nbar.LimitError("x").kind == "stopped_at_limit" and nbar.ModelError("x").kind == "invalid_model"
    assert nbar.Error("x").kind == "error"


def test_bad_options_are_bad_input(examples):
    m = nbar.load(examples / "fourbar-crank-rocker.yaml")
    with pytest.raises(nbar.BadInputError) as e:
        m.solve(steps=0)
    assert e.value.file is None and str(e.value) == e.value.message  # about the call, not the file
    with pytest.raises(nbar.BadInputError, match="steps must be a whole number, not 2.5"):
        m.solve(steps=2.5)
    assert m.solve(steps=5.0, columns="crank").rows == 5  # a whole float is a count
    with pytest.raises(nbar.BadInputError, match="columns is empty"):
        m.solve(columns=[])
    with pytest.raises(nbar.BadInputError, match="^step 999 is not a step"):
        m.explain(step=999)
    with pytest.raises(nbar.BadInputError):
        m.solve(order=9)
    with pytest.raises(nbar.BadInputError):
        m.draw(step=1000, steps=10)
    with pytest.raises(nbar.BadInputError, match="not a point"):
        m.draw(traces=["Z"])
    with pytest.raises(nbar.BadInputError, match="does not exist"):
        m.draw().save("/no/such/folder/pose.svg")
    # A pose value that is no number used to spin for ever, out of reach of Ctrl-C.
    with pytest.raises(nbar.BadInputError, match="must be a finite number, not nan"):
        m.draw(at=float("nan"))
    with pytest.raises(nbar.BadInputError, match="not inf"):
        m.draw(at=float("inf"))


def test_undefined_law_is_located():
    text = BASE + "drivers:\n  - {angle: crank, law: \"sqrt(t - 1)\"}\nsweep: {duration: 2}\n"
    with pytest.raises(nbar.Error) as e:
        nbar.loads(text, "law.yaml").solve()
    assert e.value.kind in ("undefined_law", "cannot_assemble")
    assert e.value.file == "law.yaml"


def test_a_law_undefined_inside_the_sweep_is_found_before_solving(examples):
    # 30/(t - 1) is fine at t = 0 and has no value at t = 1: solve() used to run up to it and
    # stop there as if at a toggle (LimitError, placed at `sweep:`).
    text = open(os.path.join(examples, "fourbar-crank-rocker.yaml")).read()
    text = text.replace("{angle: crank, from: 0, to: 360, speed: 120 rpm}",
                        "{angle: crank, law: \"30/(t-1)\"}")
    text = text.replace("sweep: {steps: 361}", "sweep: {duration: 2, steps: 21}")
    model = nbar.loads(text, "law.yaml")
    with pytest.raises(nbar.UndefinedLawError, match=r"law '30/\(t-1\)' is undefined at t = 1") as e:
        model.solve()
    line = next(i for i, row in enumerate(text.splitlines(), 1) if "30/(t-1)" in row)
    assert (e.value.line, e.value.kind) == (line, "undefined_law")


def test_solve_carries_the_warnings_check_gives_before_the_sweep(examples):
    # Degrees written with `angle: rad`: 360 rad is 57.3 turns, which check() has always said.
    text = open(os.path.join(examples, "fourbar-crank-rocker.yaml")).read().replace("angle: deg", "angle: rad")
    result = nbar.loads(text, "rad.yaml").solve(steps=50)
    turns = [w for w in result.warnings if w.code == "many_turns"]
    assert len(turns) == 1 and "57.3 times" in turns[0].message


def test_from_dict_rejects_what_json_cannot_hold():
    with pytest.raises(nbar.BadInputError):
        nbar.Model.from_dict({"points": {"O": [0, object()]}})
    # A NaN (np.arccos of 1.2, say) is refused at its line and column, as in a model file.
    with pytest.raises(nbar.ModelError) as nan:
        nbar.Model.from_dict({"points": {"O": [0, float("nan")]}})
    assert "must be a finite number, not 'NaN'" in nan.value.message
    assert nan.value.text.splitlines()[nan.value.line - 1].strip().startswith("NaN")
    with pytest.raises(nbar.ModelError) as e:
        nbar.Model.from_dict({"points": {"O": [0, 0]}, "ground": ["O"], "bodies": {"crank": ["O", "B"]}})
    assert "B" in e.value.message and e.value.line and "\"crank\"" in e.value.text


def test_ctrl_c_stops_a_long_sweep_within_a_second(examples):
    m = nbar.load(examples / "fourbar-crank-rocker.yaml")
    main = threading.main_thread().ident
    timer = threading.Timer(0.3, lambda: signal.pthread_kill(main, signal.SIGINT))
    start = time.monotonic()
    timer.start()
    with pytest.raises(KeyboardInterrupt):
        m.solve(steps=5_000_000, timeout=5)  # the time-out only guards the test
    assert time.monotonic() - start < 1.5
    # The interpreter and the model are still fine.
    assert m.solve(steps=3).complete


def test_timeout_cancels(examples):
    m = nbar.load(examples / "fourbar-crank-rocker.yaml")
    start = time.monotonic()
    with pytest.raises(nbar.Cancelled):
        m.solve(steps=5_000_000, timeout=0.2)
    assert time.monotonic() - start < 1.5


def test_max_steps_bounds_the_sweep_as_the_cli_does():
    model = nbar.loads(BASE + "drivers: [{angle: crank, from: 0, to: 90}]\n", "m.yaml")
    with pytest.raises(nbar.BadInputError, match="the sweep asks for 20 steps, more than the limit of 10"):
        model.solve(steps=20, max_steps=10)
    with pytest.raises(nbar.BadInputError, match="more than the limit of 10"):
        model.analyse(steps=20, max_steps=10)
    assert model.solve(steps=20, max_steps=20).rows == 20
    # The hint names Python's argument, not the command line's option.
    many = nbar.loads(BASE + "drivers: [{angle: crank, from: 0, to: 90}]\nsweep: {steps: 50}\n", "m.yaml")
    with pytest.raises(nbar.ModelError) as e:
        many.solve(max_steps=10)
    assert "raise the limit with max_steps=" in e.value.message and "--max-steps" not in e.value.message


def test_check_prints_why_the_start_cannot_be_assembled():
    text = """points: {O2: [0, 0], O4: [200, 0], A: [40, 0], B: [120, 40]}
ground: [O2, O4]
bodies: {crank: [O2, A], coupler: [A, B], rocker: [O4, B]}
lengths: {crank: 40, coupler: 50, rocker: 50}
drivers: [{angle: crank, from: 0, to: 360}]
"""
    s = nbar.loads(text, "short.yaml").check()
    assert s.assembly is None and "crank 40 + coupler 50 + rocker 50 < frame 200 m:" in s.assembly_error
    failed = str(s).index("Assembly at the start: FAILED\n")
    # The reason is printed right under the FAILED line, with its place in the file.
    assert str(s)[failed:].splitlines()[1] == "  " + s.assembly_error
    assert s.assembly_error.startswith("short.yaml:")


def test_every_stop_at_a_limit_is_placed_at_the_driver_as_solve_places_it(toggle_stop):
    m = toggle_stop
    places = []
    for run in (lambda: m.solve(steps=361), lambda: m.draw(at=150), lambda: m.explain(step=200)):
        with pytest.raises(nbar.LimitError) as e:
            run()
        places.append((e.value.line, e.value.column))
    assert places == [(6, 5)] * 3  # the driver's line, not the model's first line
    with pytest.raises(nbar.LimitError, match=r"^dr\.yaml:6:5: cannot reach crank = 150 deg: it stops at crank = 99\.7"):
        m.draw(at=150)


def test_arguments_of_the_wrong_type_are_bad_input_not_type_errors(examples):
    m = nbar.load(examples / "fourbar-crank-rocker.yaml")
    for run, message in [(lambda: m.draw(at="90"), "at must be a number, not '90'"),
                         (lambda: m.draw(width="600"), "width must be a whole number, not '600'"),
                         (lambda: m.draw(step="3"), "step must be a whole number, not '3'"),
                         (lambda: m.animate(fps="24"), "fps must be a number, not '24'"),
                         (lambda: m.animate(frames=2.5), "frames must be a whole number, not 2.5"),
                         (lambda: m.solve(timeout="1"), "timeout must be a number, not '1'"),
                         (lambda: m.explain(step="30"), "step must be a whole number, not '30'"),
                         (lambda: m.draw(traces=[3]), "traces must be point names (strings), not 3")]:
        with pytest.raises(nbar.BadInputError) as e:
            run()
        assert e.value.message == message and e.value.kind == "bad_input"
    # numpy's numbers are numbers.
    import numpy as np
    assert m.draw(at=np.float64(90), width=np.int64(400)).svg.startswith("<?xml")


def test_orders_past_five_are_bad_input_not_a_crash(examples):
    # Model.columns(order=6) and solve(columns=..., order=6) ended the interpreter (SIGSEGV).
    m = nbar.load(examples / "fourbar-crank-rocker.yaml")
    for run in (lambda: m.columns(order=6), lambda: m.solve(order=6, columns="P.x"),
                lambda: m.dynamics(columns="crank.*", order=9), lambda: m.solve(order=-1, columns="P.x")):
        with pytest.raises(nbar.BadInputError, match="the derivative order must be between 0 and 5"):
            run()
    assert "P.jerk.x" in m.columns(order=5) or any(c.startswith("P.") for c in m.columns(order=5))


def test_an_endless_timeout_is_no_limit(examples):
    # inf and 1e12 s overflowed the clock into the past and cancelled at once.
    m = nbar.load(examples / "fourbar-crank-rocker.yaml")
    for timeout in (float("inf"), 1e300, 1e12):
        assert m.solve(steps=5, timeout=timeout).rows == 5


def test_counts_and_flags_of_the_wrong_kind_are_bad_input(examples):
    m = nbar.load(examples / "fourbar-crank-rocker.yaml")
    for run, message in [(lambda: m.solve(steps=2**31), "steps must be a whole number from"),
                         (lambda: m.solve(max_steps=0), "max_steps must be a whole number from 1"),
                         (lambda: m.solve(order="2", columns="P.x"), "order must be a whole number, not '2'"),
                         (lambda: m.solve(columns=[1, 2]), "columns must be names or globs"),
                         (lambda: m.solve(dynamics="yes"), "dynamics must be True or False"),
                         (lambda: m.draw(labels="no"), "labels must be True or False"),
                         (lambda: m.draw(title=None), "title must be a string"),
                         (lambda: m.stress(sections=10**8), "sections: must be from 10 to 100000, not 100000000"),
                         (lambda: m.report(frames=1), "frames: must be from 2 to 1000, not 1"),
                         (lambda: m.draw(traces=5), "traces must be a point name or a list of point names, not 5"),
                         (lambda: m.draw(step=5, at=90), "at: give step or at, not both"),
                         (lambda: nbar.synth.five_point(pivots=[(0, 0), (1, 0)], points=[(0, 1)] * 5, units=5),
                          "units must be a length unit"),
                         (lambda: nbar.loads(None), "text must be a string"),
                         (lambda: nbar.Model.from_dict({}, name=None), "name must be a string")]:
        with pytest.raises(nbar.BadInputError) as e:
            run()
        assert message in e.value.message, e.value.message


def test_a_column_key_that_is_no_string_is_missing_not_a_crash(examples):
    r = nbar.load(examples / "fourbar-crank-rocker.yaml").solve(steps=3)
    assert 0 not in r and r.get(0) is None and r.get(None, 7) == 7
    with pytest.raises(nbar.ColumnError, match="columns are named by strings, not 0"):
        r[0]


def test_an_unknown_column_asked_of_solve_or_plot_is_a_column_error_with_a_suggestion(examples):
    m = nbar.load(examples / "fourbar-crank-rocker.yaml")
    with pytest.raises(nbar.ColumnError) as e:
        m.solve(columns="rocker.omeg")
    assert isinstance(e.value, KeyError) and "did you mean 'rocker.omega'" in e.value.message
    assert len(e.value.message) < 200
    with pytest.raises(nbar.ColumnError, match="did you mean 'rocker.omega'"):
        nbar.plotting.columns(m.solve(steps=3), "rocker.omeg")


def test_an_explanation_copies_and_a_drawing_saves_under_an_upper_case_extension(examples, tmp_path):
    import copy
    explanation = nbar.load(examples / "fourbar-crank-rocker.yaml").explain(step=3)
    # copy looked up special names on an instance without _native and recursed without end.
    assert copy.copy(explanation).text == explanation.text
    assert copy.deepcopy(explanation).text == explanation.text
    drawing = explanation.draw()
    drawing.save(tmp_path / "centres.PNG")
    assert (tmp_path / "centres.PNG").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    with pytest.raises(nbar.BadInputError, match="a drawing is saved as .svg or .png"):
        drawing.save(tmp_path / "centres.jpg")


def test_text_with_a_lone_surrogate_is_bad_input_at_its_line_and_column():
    # What a broken decoder (or "\ud800" in a JSON string) leaves: no UTF-8 form for the core.
    with pytest.raises(nbar.BadInputError, match=r"text holds '\\udcff' at line 3, column 4: half of a UTF-16"):
        nbar.loads("points:\n  A: [0, 0]\n  B\udcff: [1, 0]\n")
    with pytest.raises(nbar.BadInputError, match="name holds"):
        nbar.loads("points: {}\n", name="m\ud800.yaml")


def test_a_dict_nested_ten_thousand_deep_is_bad_input_not_a_recursion_error():
    deep = {}
    inner = deep
    for _ in range(10000):
        inner["a"] = {}
        inner = inner["a"]
    with pytest.raises(nbar.BadInputError, match="nested too deeply to be a model"):
        nbar.Model.from_dict(deep)
    # Shallower than Python's recursion limit, the reader says how deep and where.
    lists = []
    inner = lists
    for _ in range(600):
        inner.append([])
        inner = inner[0]
    with pytest.raises(nbar.ModelError, match="nested [0-9]+ levels deep here") as e:
        nbar.Model.from_dict({"points": lists})
    assert e.value.line is not None and e.value.column is not None
