"""The package's public face: the stub names what the module has, and everything has a docstring."""

import ast
import inspect
import pathlib

import nbar

STUB = pathlib.Path(nbar.__file__).with_name("__init__.pyi")


def stub_names():
    tree = ast.parse(STUB.read_text())
    names = {}
    for node in tree.body:
        if isinstance(node, ast.ClassDef):
            # Methods and properties must be on the class; annotated attributes are set per instance.
            names[node.name] = {n.name for n in node.body if isinstance(n, ast.FunctionDef)}
        elif isinstance(node, ast.FunctionDef):
            names[node.name] = set()
    return names


def test_every_stub_name_exists():
    for name, members in stub_names().items():
        assert hasattr(nbar, name), name
        obj = getattr(nbar, name)
        for m in members:
            assert hasattr(obj, m), f"{name}.{m}"


def test_public_functions_and_classes_have_docstrings():
    for name in nbar.__all__:
        obj = getattr(nbar, name)
        if inspect.isclass(obj) or inspect.isfunction(obj):
            assert inspect.getdoc(obj), name
    for name in ["solve", "dynamics", "stress", "draw", "animate", "report", "explain", "check", "from_dict"]:
        assert inspect.getdoc(getattr(nbar.Model, name)), name
    for name in ["five_point", "burmester", "function", "run", "task", "load"]:
        assert inspect.getdoc(getattr(nbar.synth, name)), name


def test_version():
    assert nbar.__version__.count(".") == 2
