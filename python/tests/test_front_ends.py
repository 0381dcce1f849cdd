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


def run_cli(args, output_suffix=None):
    """Exit code, standard output (or the output file's bytes) and standard error."""
    with tempfile.TemporaryDirectory() as folder:
        out = os.path.join(folder, "out" + output_suffix) if output_suffix else None
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
]

SUFFIX = {"draw": ".svg", "animate": ".svg", "plot": ".svg"}
ENDPOINT = {"solve": ("/api/solve", {}), "stress": ("/api/stress", {}), "draw": ("/api/render", {"kind": "draw"}),
            "animate": ("/api/render", {"kind": "animate", "format": "svg"}), "plot": ("/api/render", {"kind": "plot"})}


@pytest.mark.parametrize("command, model, options, python_call, message", ERRORS,
                         ids=[f"{c[0]}-{'-'.join(c[2])}" for c in ERRORS])
def test_one_error_in_every_front_end(server, command, model, options, python_call, message):
    code, _, stderr = run_cli([command, model] + flags(options), SUFFIX.get(command))
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
    code, from_cli, stderr = run_cli([command, model] + flags(options), SUFFIX.get(command))
    assert code == 0, stderr
    path, extra = ENDPOINT[command]
    status, from_api = post(server, path, {"model": model.read_text(), **extra, **options})
    assert status == 200, from_api
    assert from_api == from_cli
    if python_call is not None:
        assert python_call(_nbar.load(str(model))) == from_cli
