"""The type stubs describe the module: every public name, the same signatures' parameter
names, and `simulate`'s defaults are the Rust `SimulationOptions` defaults."""

from __future__ import annotations

import ast
import inspect
from pathlib import Path

import rspose

STUB = Path(__file__).resolve().parents[1] / "rspose.pyi"


def stub_tree() -> ast.Module:
    return ast.parse(STUB.read_text())


def stub_functions() -> dict[str, ast.FunctionDef]:
    return {n.name: n for n in stub_tree().body if isinstance(n, ast.FunctionDef)}


def test_every_public_name_is_in_the_stub():
    names = {n.name for n in stub_tree().body if isinstance(n, (ast.FunctionDef, ast.ClassDef))}
    public = {n for n in dir(rspose) if not n.startswith("_") and not inspect.ismodule(getattr(rspose, n))}
    assert public - names == set()
    assert {n for n in names if n[0].islower()} <= public


def test_function_parameters_match():
    for name, node in stub_functions().items():
        runtime = inspect.signature(getattr(rspose, name))
        a = node.args
        stub = [x.arg for x in a.posonlyargs + a.args + a.kwonlyargs]
        stub += [a.vararg.arg] if a.vararg else []
        stub += [a.kwarg.arg] if a.kwarg else []
        assert sorted(stub) == sorted(runtime.parameters), name


def test_simulate_defaults_in_the_stub_are_the_rust_defaults():
    node = stub_functions()["simulate"]
    defaults = {
        arg.arg: ast.literal_eval(default)
        for arg, default in zip(node.args.kwonlyargs, node.args.kw_defaults)
        if default is not None
    }
    assert rspose.simulate(**defaults).to_json() == rspose.simulate().to_json()
    # And they matter: one changed value changes the pair.
    assert rspose.simulate(**{**defaults, "gyro_noise": 0.2}).to_json() != rspose.simulate().to_json()


def test_docstrings():
    for name in dir(rspose):
        obj = getattr(rspose, name)
        if not name.startswith("_") and callable(obj):
            assert (obj.__doc__ or "").strip(), name
