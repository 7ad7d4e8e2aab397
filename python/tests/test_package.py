# SPDX-License-Identifier: MIT
"""The package behaves like a scientific Python package: numpydoc docstrings and named arguments on
every public call, type stubs, Ctrl-C that stops advance() with the model left to go on, a progress
callback, run() that returns a dict."""
import inspect
import os
import pathlib
import re
import signal
import subprocess
import sys
import textwrap

import pytest

import runnel

PUBLIC_CLASSES = (runnel.Model, runnel.Terrain)


def public_callables():
    for name in runnel.__all__:
        value = getattr(runnel, name)
        if inspect.isclass(value) and issubclass(value, BaseException):
            continue
        yield name, value
    for cls in PUBLIC_CLASSES:
        for name in vars(cls):
            if not name.startswith("_"):
                yield f"{cls.__name__}.{name}", getattr(cls, name)


def arguments(value, doc):
    """The argument names, less self: from the signature of a Python function, from the signature
    line of a native one ("f(self: T, a: int = 1) -> R")."""
    if inspect.isfunction(value):
        return [n for n in inspect.signature(value).parameters if n != "self"]
    first = doc.splitlines()[0]
    if not re.match(r"^\w+\(.*\)( -> .*)?$", first):
        return []
    inside = first.split("(", 1)[1].rsplit(")", 1)[0]
    names = re.findall(r"(?:^|,\s*)(\w+)\s*:", inside)
    return [n for n in names if n != "self"]


@pytest.mark.parametrize("name, value", list(public_callables()), ids=lambda v: v if isinstance(v, str) else "")
def test_every_public_call_is_documented_with_named_arguments(name, value):
    doc = inspect.getdoc(value)
    assert doc and len(doc) > 10, f"{name} has no docstring"
    assert "arg0" not in doc, f"{name} has unnamed arguments"
    if callable(value) and not isinstance(value, property):
        for argument in arguments(value, doc):
            assert re.search(rf"^({argument}|.*, {argument}|{argument},.*) :", doc, re.M), \
                f"{name}: {argument} undocumented"


def test_the_stubs_cover_the_native_module():
    package = pathlib.Path(runnel.__file__).parent
    assert (package / "py.typed").exists()
    stubs = (package / "_runnel.pyi").read_text()
    for name, value in public_callables():
        if getattr(value, "__module__", None) == "runnel":
            continue  # defined in Python, typed where it is written
        short = name.split(".")[-1]
        assert f"def {short}(" in stubs or f"class {short}" in stubs or f"{short}:" in stubs, name


def test_advance_reports_its_progress():
    model = runnel.Model("pipe", runnel.generate("fbm", 33, 33, 1.0))
    seen = []
    model.advance(0.5, progress=lambda elapsed, total: seen.append((elapsed, total)))
    assert len(seen) == model.steps and seen[-1] == pytest.approx((0.5, 0.5), rel=1e-12)
    assert all(a[0] < b[0] for a, b in zip(seen, seen[1:]))


CTRL_C = textwrap.dedent("""
    import sys
    import runnel
    model = runnel.Model("pipe", runnel.generate("fbm", 65, 65, 1.0))
    def started(elapsed, total):
        if elapsed > 0.1 and not getattr(started, "told", False):
            started.told = True
            print("running", flush=True)
    try:
        model.advance(1e6, progress=started)
        print("finished")
    except KeyboardInterrupt:
        time = model.time
        balance = model.mass_balance()["residual_quanta"]
        model.advance(0.25)  # the model goes on from where it stopped
        print("interrupted", time > 0.1, balance, abs(model.time - time - 0.25) < 1e-9)
""")


def test_ctrl_c_stops_advance_and_leaves_the_model_to_go_on():
    env = dict(os.environ)
    child = subprocess.Popen([sys.executable, "-c", CTRL_C], stdout=subprocess.PIPE, text=True, env=env)
    try:
        assert child.stdout.readline().strip() == "running"  # waits for the event, not a time
        child.send_signal(signal.SIGINT)
        out, _ = child.communicate(timeout=300)
    finally:
        if child.poll() is None:
            child.kill()
    assert out.strip() == "interrupted True 0 True"
