"""One request, three front-ends: the command line, the web API and Python give the same answer, or
the same error, because each only fills a request of the core's request layer (nbar/request) and
renders its answer. Every case runs through all three; an error is compared as the option it
names and what it says of it, with each front-end's spelling of option names undone (--mesh-size
on the command line, mesh_size in JSON and in Python)."""

from __future__ import annotations

import json
import os
import pathlib
import re
import subprocess
import tempfile
import time
import urllib.error
import urllib.request

import pytest

import nbar
from nbar import _nbar

ROOT = pathlib.Path(__file__).resolve().parents[2]
EXAMPLES = ROOT / "examples"
CRANK_ROCKER = EXAMPLES / "fourbar-crank-rocker.yaml"
STEEL = EXAMPLES / "fourbar-steel-bars.yaml"


def cli_path() -> str:
    return os.environ.get("NBAR_CLI") or str(ROOT / "build" / "apps" / "nbar" / "nbar")


@pytest.fixture(scope="module")
def server():
    """`nbar serve` on a port the system picks, for the module's cases."""
    if not os.path.exists(cli_path()):
        pytest.skip("the nbar program is not built")
    log = tempfile.TemporaryFile(mode="w+")
    process = subprocess.Popen([cli_path(), "serve", "--port", "0"], stdout=log, stderr=log)
    try:
        for _ in range(400):
            log.seek(0)
            found = re.search(r"http://127\.0\.0\.1:(\d+)/", log.read())
            if found:
                break
            assert process.poll() is None, "nbar serve exited"
            time.sleep(0.05)
        else:
            pytest.fail("nbar serve did not start")
        yield f"http://127.0.0.1:{found.group(1)}"
    finally:
        process.terminate()
        process.wait(timeout=10)


def post(base: str, path: str, body: dict):
    request = urllib.request.Request(base + path, data=json.dumps(body).encode(), method="POST",
                                     headers={"Content-Type": "application/json"})
    try:
        with urllib.request.urlopen(request, timeout=120) as answer:
            return answer.status, answer.read()
    except urllib.error.HTTPError as e:
        return e.code, e.read()


# Where the command line's output file goes when its flag is not -o (export's --svg FILE).
OUT = object()


def run_cli(args, output_suffix=None):
    """Exit code, standard output (or the output file's bytes) and standard error."""
    with tempfile.TemporaryDirectory() as folder:
        out = os.path.join(folder, "out" + output_suffix) if output_suffix else None
        if OUT in args:
            full = [cli_path()] + [out if a is OUT else str(a) for a in args]
        else:
            full = [cli_path()] + [str(a) for a in args] + (["-o", out] if out else [])
        done = subprocess.run(full, capture_output=True, timeout=300)
        data = done.stdout
        if out and os.path.exists(out):
            with open(out, "rb") as f:
                data = f.read()
        return done.returncode, data, done.stderr.decode()


def unspelled(message: str) -> str:
    """A message with the command line's spelling of option names undone: --mesh-size -> mesh_size."""
    return re.sub(r"--([a-z][a-z-]*)", lambda m: m.group(1).replace("-", "_"), message)


def cli_error(stderr: str) -> str:
    """The one error line of the command line, without its "error: " prefix and the CLI11 hint."""
    line = stderr.splitlines()[0]
    return unspelled(line[len("error: "):] if line.startswith("error: ") else line)


def flags(options: dict):
    """The command line's flags for the request's options."""
    out = []
    for key, value in options.items():
        flag = "--" + key.replace("_", "-")
        if value is True:
            out.append(flag)
        elif isinstance(value, list):
            out += [flag, ",".join(str(v) for v in value)]
        else:
            out += [flag, str(value)]
    return out


def python_error(call) -> tuple[str, str]:
    with pytest.raises(nbar.Error) as caught:
        call()
    return caught.value.kind, caught.value.message


# Requests refused by one rule of the request layer: (command, model, options, Python call, the
# message every front-end gives once option names are spelled as keys).
ERRORS = [
    ("solve", CRANK_ROCKER, {"order": 9}, lambda m: _nbar.analyse(m, order=9), "order: must be from 0 to 5, not 9"),
    ("solve", CRANK_ROCKER, {"steps": 0}, lambda m: _nbar.analyse(m, steps=0), "steps: must be a positive number, not 0"),
    ("solve", CRANK_ROCKER, {"max_steps": -3}, lambda m: _nbar.analyse(m, max_steps=-3),
     "max_steps: must be a positive number, not -3"),
    ("solve", CRANK_ROCKER, {"columns": ["nosuch"]}, lambda m: _nbar.analyse(m).table(["nosuch"]), None),
    ("stress", STEEL, {"method": "fe", "mesh_size": -1}, lambda m: _nbar.analyse(m, stress=True, method="fe", mesh_size=-1),
     "mesh_size: must be a positive number, not -1"),
    ("stress", STEEL, {"sections": 5}, lambda m: _nbar.analyse(m, stress=True, sections=5),
     "sections: must be from 10 to 100000, not 5"),
    ("stress", STEEL, {"method": "cfd"}, lambda m: _nbar.analyse(m, stress=True, method="cfd"),
     "method: must be one of beam, fe, not 'cfd'"),
    ("stress", STEEL, {"section_profile": "nosuch"},
     lambda m: _nbar.analyse(m, stress=True).section_profile("nosuch", 0),
     "section_profile: 'nosuch' is not a body of the model"),
    ("draw", CRANK_ROCKER, {"width": 50}, lambda m: _nbar.analyse(m, order=0).draw("svg", width=50),
     "width: must be from 100 to 10000, not 50"),
    ("draw", CRANK_ROCKER, {"trace": ["Z"]}, lambda m: _nbar.analyse(m, order=0).draw("svg", traces=["Z"]),
     "trace: 'Z' is not a point of the model; the points are: O2, O4, A, B, P"),
    ("draw", CRANK_ROCKER, {"step": 999, "steps": 13}, lambda m: _nbar.analyse(m, order=0, steps=13).draw("svg", step=999),
     "step 999 is not a solved step (0 to 12)"),
    ("animate", CRANK_ROCKER, {"fps": 200}, lambda m: _nbar.analyse(m, order=0).animate("svg", fps=200),
     "fps: must be from 0.1 to 120, not 200"),
    ("animate", CRANK_ROCKER, {"width": 9000}, lambda m: _nbar.analyse(m, order=0).animate("svg", width=9000),
     "width: must be from 64 to 8192, not 9000"),
    ("animate", CRANK_ROCKER, {"frames": 0}, None, "frames: must be from 1 to 100000, not 0"),
    ("report", CRANK_ROCKER, {"frames": 1}, lambda m: _nbar.report(m, frames=1), "frames: must be from 2 to 1000, not 1"),
    ("report", STEEL, {"mesh_size": 4}, None, "mesh_size: is the finite elements' element size: give stress_method fe too"),
    ("explain", CRANK_ROCKER, {"step": -1}, lambda m: _nbar.explain(m, step=-1), "step: must be 0 or more, not -1"),
    ("explain", CRANK_ROCKER, {"steps": 0}, lambda m: _nbar.explain(m, steps=0),
     "steps: must be a positive number, not 0"),
    ("explain", CRANK_ROCKER, {"format": "pdf"}, None,
     "format: must be one of text, markdown, latex, json, not 'pdf'"),
]

SUFFIX = {"draw": ".svg", "animate": ".svg", "plot": ".svg", "report": ".html", "export": ".out"}
ENDPOINT = {"solve": ("/api/solve", {}), "stress": ("/api/stress", {}), "draw": ("/api/render", {"kind": "draw"}),
            "animate": ("/api/render", {"kind": "animate", "format": "svg"}), "plot": ("/api/render", {"kind": "plot"}),
            "report": ("/api/report", {}), "explain": ("/api/explain", {}),
            "export": ("/api/render", {"kind": "plates"})}


def cli_args(command: str, model, options: dict):
    """The command line of a request: export names its file by the format's flag (--dxf FILE)."""
    if command == "export":
        options = dict(options)
        return ["export", model, "--" + options.pop("format", "svg"), OUT] + flags(options)
    return [command, model] + flags(options)


@pytest.mark.parametrize("command, model, options, python_call, message", ERRORS,
                         ids=[f"{c[0]}-{'-'.join(c[2])}" for c in ERRORS])
def test_one_error_in_every_front_end(server, command, model, options, python_call, message):
    code, _, stderr = run_cli(cli_args(command, model, options), SUFFIX.get(command))
    assert code == 2, stderr
    from_cli = cli_error(stderr)

    path, extra = ENDPOINT[command]
    status, body = post(server, path, {"model": model.read_text(), **extra, **options})
    error = json.loads(body)["error"]
    assert status == 400 and error["kind"] == "bad_input", body
    assert error["option"] == next(iter(options)) or error["option"] in options, body
    from_api = error["message"]

    assert from_cli == from_api
    if message is not None:
        assert from_api == message
    if python_call is not None:
        kind, from_python = python_error(lambda: python_call(_nbar.load(str(model))))
        assert kind == "bad_input"
        assert from_python == from_api


# Requests answered the same way: (command, model, options, the Python call giving the same bytes).
ANSWERS = [
    ("solve", CRANK_ROCKER, {"steps": 13, "order": 3, "format": "json"},
     lambda m: _nbar.analyse(m, steps=13, order=3).json().encode()),
    ("solve", CRANK_ROCKER, {"steps": 7, "columns": ["crank", "B.*"], "format": "json"},
     lambda m: _nbar.analyse(m, steps=7).json(["crank", "B.*"]).encode()),
    ("stress", STEEL, {"steps": 13, "format": "json"},
     lambda m: _nbar.analyse(m, steps=13, stress=True).stress_report("json").encode()),
    ("stress", STEEL, {"steps": 5, "method": "fe", "mesh_size": 8, "format": "json"},
     lambda m: _nbar.analyse(m, steps=5, stress=True, method="fe", mesh_size=8).stress_report("json").encode()),
    ("draw", CRANK_ROCKER, {"steps": 25, "step": 6, "trace": ["P"], "width": 400, "height": 300, "labels": True},
     lambda m: _nbar.analyse(m, steps=25, order=0).draw("svg", step=6, traces=["P"], width=400, height=300,
                                                 labels=True).encode()),
    ("animate", CRANK_ROCKER, {"steps": 13, "frames": 4, "fps": 10, "width": 300, "height": 200},
     lambda m: _nbar.analyse(m, steps=13, order=0).animate("svg", frames=4, fps=10, width=300, height=200).encode()),
    ("plot", CRANK_ROCKER, {"steps": 13, "y": ["rocker.omega"], "width": 400, "height": 300, "title": "rocker"}, None),
]


@pytest.mark.parametrize("command, model, options, python_call", ANSWERS,
                         ids=[f"{c[0]}-{'-'.join(c[2])}" for c in ANSWERS])
def test_one_answer_in_every_front_end(server, command, model, options, python_call):
    code, from_cli, stderr = run_cli(cli_args(command, model, options), SUFFIX.get(command))
    assert code == 0, stderr
    path, extra = ENDPOINT[command]
    status, from_api = post(server, path, {"model": model.read_text(), **extra, **options})
    assert status == 200, from_api
    assert from_api == from_cli
    if python_call is not None:
        assert python_call(_nbar.load(str(model))) == from_cli


# ------------------------------------------------------------------------------ report, explain

def test_a_report_is_the_same_page(server):
    options = {"frames": 4}
    code, from_cli, stderr = run_cli(cli_args("report", CRANK_ROCKER, options), ".html")
    assert code == 0, stderr
    page, complete, _ = _nbar.report(_nbar.load(str(CRANK_ROCKER)), frames=4)
    assert complete and page.encode() == from_cli
    status, from_api = post(server, "/api/report", {"model": CRANK_ROCKER.read_text(), **options})
    assert status == 200, from_api
    # The page names its model: the file on the command line and in Python, "model" in the API.
    assert from_api == from_cli.replace(str(CRANK_ROCKER).encode(), b"model")
    assert from_api.count(b"<svg") == from_cli.count(b"<svg") > 0


def test_an_explanation_is_the_same(server):
    options = {"step": 3, "steps": 13, "format": "json"}
    code, from_cli, stderr = run_cli(cli_args("explain", CRANK_ROCKER, options))
    assert code == 0, stderr
    status, from_api = post(server, "/api/explain", {"model": CRANK_ROCKER.read_text(), **options})
    assert status == 200, from_api
    assert from_api == from_cli
    explained = json.loads(from_cli)
    assert json.loads(_nbar.explain(_nbar.load(str(CRANK_ROCKER)), step=3, steps=13).json()) == explained
    # Sample 3 of 13 over the crank's turn: the crank at 90 deg, its pin A at (0, 80) mm.
    assert explained["step"] == 3


# ------------------------------------------------------------------------------------- export
# Python has no plates for cutting (no export): the command line and the web API only.

DOUBLE_ROCKER = EXAMPLES / "fourbar-double-rocker.yaml"


@pytest.mark.parametrize("options", [{"format": "svg"}, {"format": "dxf"}, {"format": "dxf", "at": 90},
                                     {"format": "svg", "at": -30.5}],
                         ids=["svg", "dxf", "dxf-at-90", "svg-at--30.5"])
def test_the_plates_are_the_same(server, options):
    code, from_cli, stderr = run_cli(cli_args("export", STEEL, options), ".out")
    assert code == 0, stderr
    status, from_api = post(server, "/api/render", {"model": STEEL.read_text(), "kind": "plates", **options})
    assert status == 200, from_api
    assert from_api == from_cli
    if options["format"] == "dxf":
        assert from_cli.startswith(b"  0\nSECTION\n")
    else:
        assert b"<svg" in from_cli[:200]
    if "at" not in options:  # as drawn: the same as the model file's pose, not the sweep's
        code, at_zero, _ = run_cli(cli_args("export", STEEL, {**options, "at": 90}), ".out")
        assert code == 0 and at_zero != from_cli


# An error in the model or in reaching the pose: the same kind and message, with the command
# line's prefix (the model file's name when the error has no place of its own) taken off.
EXPORT_ERRORS = [
    (CRANK_ROCKER, {"format": "svg"}, 2, 400, "bad_input",
     "no body has a `shape` or a `bar`: there is nothing to cut"),
    (DOUBLE_ROCKER, {"format": "svg", "at": 180}, 4, 422, "stopped_at_limit", None),
]


@pytest.mark.parametrize("model, options, code, status, kind, message", EXPORT_ERRORS, ids=["nothing-to-cut", "at-180"])
def test_export_errors_are_the_same(server, model, options, code, status, kind, message):
    got_code, _, stderr = run_cli(cli_args("export", model, options), ".out")
    answer_status, body = post(server, "/api/render", {"model": model.read_text(), "kind": "plates", **options})
    error = json.loads(body)["error"]
    from_cli = cli_error(stderr)
    # The command line says where in the model (a stop past a limit: at the sweep, as solve does);
    # the answer gives the same place as its line and column.
    placed = re.match(re.escape(str(model)) + r"(?::(\d+):(\d+))?: ", from_cli)
    if placed:
        from_cli = from_cli[placed.end():]
        if placed.group(1):
            assert (error.get("line"), error.get("column")) == (int(placed.group(1)), int(placed.group(2))), body
    assert (got_code, answer_status, error["kind"]) == (code, status, kind), (stderr, body)
    assert from_cli == error["message"]
    if message is not None:
        assert error["message"] == message


# ---------------------------------------------------------------------------------- synthesis
# Each method's request: the task is a document (a file for the command line and Python, the
# body's `task` for the API); the options are the request's.

SYNTH = EXAMPLES / "synthesis"
TASKS = {"five-point": SYNTH / "five-point-crank-rocker.yaml", "nine-point": SYNTH / "nine-point-crank-rocker.yaml",
         "burmester": SYNTH / "burmester-four-positions.yaml", "function": SYNTH / "function-log10.yaml",
         "path": SYNTH / "path" / "crank-rocker-measured.yaml"}


def same_numbers(a, b, where="$"):
    """The same JSON, numbers to 1e-9 relative: several threads may change a homotopy's last bits."""
    if isinstance(a, dict):
        assert isinstance(b, dict) and a.keys() == b.keys(), where
        for k in a:
            same_numbers(a[k], b[k], f"{where}.{k}")
    elif isinstance(a, list):
        assert isinstance(b, list) and len(a) == len(b), where
        for i, (x, y) in enumerate(zip(a, b)):
            same_numbers(x, y, f"{where}[{i}]")
    elif isinstance(a, float) or isinstance(b, float):
        assert b == pytest.approx(a, rel=1e-9, abs=1e-12), where
    else:
        assert a == b, where


def synth_cli(kind: str, task_file, options: dict):
    return run_cli(["synth", kind, task_file] + flags(options))


SYNTH_ANSWERS = [
    ("five-point", {"top": 3, "threads": 1, "seed": 7}),
    ("nine-point", {"top": 2, "threads": 1}),
    ("burmester", {"top": 3}),
    ("function", {"all": True}),
    ("path", {"top": 2, "threads": 1}),
]


@pytest.mark.parametrize("kind, options", SYNTH_ANSWERS, ids=[a[0] for a in SYNTH_ANSWERS])
def test_one_synthesis_answer_in_every_front_end(server, kind, options):
    task_file = TASKS[kind]
    code, out, stderr = synth_cli(kind, task_file, {**options, "format": "json"})
    assert code == 0, stderr
    from_cli = json.loads(out)
    status, body = post(server, f"/api/synth/{kind}", {"task": task_file.read_text(), **options})
    assert status == 200, body
    same_numbers(from_cli, json.loads(body))
    same_numbers(from_cli, nbar.synth.run(task_file, **options).data)
    assert from_cli["task"] == kind
    designs = from_cli["designs"]
    assert 1 <= len(designs) <= options.get("top", 20)
    # The best design does its task: the simulated linkage meets the targets.
    if kind in ("five-point", "nine-point", "burmester"):
        assert designs[0]["max_error"] < 1e-6
    elif kind == "path":
        assert designs[0]["rms_error"] < 0.42


def test_a_synthesis_table_is_the_same(server):
    task_file = TASKS["function"]
    code, from_cli, stderr = synth_cli("function", task_file, {})
    assert code == 0, stderr
    status, from_api = post(server, "/api/synth/function", {"task": task_file.read_text(), "format": "table"})
    assert status == 200, from_api
    assert from_api == from_cli
    assert str(nbar.synth.run(task_file)).encode() == from_cli
    assert from_cli.startswith(b"function task")


# (method, options, the message every front-end gives; Python's call or None when Python has no
# such argument).
SYNTH_ERRORS = [
    ("five-point", {"top": -1}, "top: must be 0 or more, not -1", True),
    ("burmester", {"threads": 2000}, "threads: must be from 0 to 1024, not 2000", True),
    ("function", {"top": 2.5}, "top: must be a whole number, not 2.5", True),
    ("nine-point", {"seed": -5}, "seed: must be 0 or more, not -5", True),
    ("path", {"format": "csv"}, "format: must be one of table, json, not 'csv'", False),
]


@pytest.mark.parametrize("kind, options, message, in_python", SYNTH_ERRORS, ids=[e[0] for e in SYNTH_ERRORS])
def test_one_synthesis_error_in_every_front_end(server, kind, options, message, in_python):
    task_file = TASKS[kind]
    code, _, stderr = synth_cli(kind, task_file, options)
    assert code == 2, stderr
    assert cli_error(stderr) == message
    status, body = post(server, f"/api/synth/{kind}", {"task": task_file.read_text(), **options})
    error = json.loads(body)["error"]
    assert (status, error["kind"], error["option"], error["message"]) == (400, "bad_input", next(iter(options)),
                                                                         message)
    if in_python:
        kind_of, from_python = python_error(lambda: nbar.synth.run(task_file, **options))
        assert (kind_of, from_python) == ("bad_input", message)


def test_a_seed_is_refused_by_the_methods_without_random_starts(server):
    code, _, stderr = synth_cli("burmester", TASKS["burmester"], {"seed": 3})
    assert code == 2 and cli_error(stderr) == "seed: unknown option of burmester; it takes: format, all, top, threads"
    kind, message = python_error(lambda: nbar.synth.run(TASKS["function"], seed=3))
    assert (kind, message) == ("bad_input", "seed: unknown option of function; it takes: format, all, top, threads")
    status, body = post(server, "/api/synth/burmester", {"task": TASKS["burmester"].read_text(), "seed": 3})
    assert (status, json.loads(body)["error"]["message"]) == (
        400, "unknown option 'seed'; this endpoint takes: task, models, format, all, top, threads")


# A task the reader refuses: the same message at the same line and column of the task.
SYNTH_TASK_ERRORS = [
    ("five-point", "task: five-point\npivots: {a: [0, 0], b: [200, 0]}\npoints: [[1, 2], [3, 4]]\n"),
    ("nine-point", "task: nine-point\npoints:\n  - [0, 0]\n  - [1, 0]\n"),
    ("burmester", "task: burmester\nposes:\n  - {point: [0, 0], angle: 0}\n"),
    ("function", "task: function\nfunction: 'sqrt(x) + ('\nx: [1, 2]\ninput_range: [90, 150]\n"
                 "output_range: [60, 120]\n"),
    ("path", "task: path\npoints: [[0, 0], [1, 1], [2, 0]]\n"),
]


@pytest.mark.parametrize("kind, text", SYNTH_TASK_ERRORS, ids=[e[0] for e in SYNTH_TASK_ERRORS])
def test_a_bad_task_is_located_alike(server, tmp_path, kind, text):
    task_file = tmp_path / "task.yaml"
    task_file.write_text(text)
    code, _, stderr = synth_cli(kind, task_file, {})
    assert code == 1, stderr
    found = re.match(r"error: (.*):(\d+):(\d+): (.*)$", stderr.splitlines()[0])
    assert found and found.group(1) == str(task_file), stderr
    from_cli = (int(found.group(2)), int(found.group(3)), found.group(4))
    status, body = post(server, f"/api/synth/{kind}", {"task": text})
    error = json.loads(body)["error"]
    assert (status, error["kind"], error["file"]) == (422, "invalid_model", "task"), body
    assert (error["line"], error["column"], error["message"]) == from_cli
    with pytest.raises(nbar.ModelError) as caught:
        nbar.synth.run(task_file)
    assert (caught.value.line, caught.value.column, caught.value.message) == from_cli
    assert from_cli[0] >= 1
