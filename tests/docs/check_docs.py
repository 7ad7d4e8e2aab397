#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""What the README and docs/ promise, checked on the build: every relative link and image exists, and
every `runnel` command line of the README runs as shown (on a small terrain and for a few steps, so the
check stays quick: a run's length and output folder are the only things changed).

Usage: check_docs.py SOURCE_DIR RUNNEL_BINARY [PYTHONPATH PYTHON]"""
import os
import pathlib
import re
import shlex
import subprocess
import sys
import tempfile

source = pathlib.Path(sys.argv[1])
runnel = sys.argv[2]
pythonpath = sys.argv[3] if len(sys.argv) > 3 else ""
python = sys.argv[4] if len(sys.argv) > 4 else sys.executable
failures = []


def check_links():
    files = [source / "README.md", source / "CONTRIBUTING.md", source / "CHANGELOG.md",
             *sorted((source / "docs").glob("*.md"))]
    link = re.compile(r"\]\(([^)\s]+)\)")
    checked = 0
    for f in files:
        for target in link.findall(f.read_text()):
            if re.match(r"[a-z]+:", target) or target.startswith("#"):
                continue  # a web address or an anchor of the same page
            path = (f.parent / target.split("#")[0]).resolve()
            checked += 1
            if not path.exists():
                failures.append(f"{f.relative_to(source)}: link to {target}: no such file")
    print(f"links: {checked} relative links checked")


def quick(args, out_root):
    """The command with a run's length cut to two steps and --out moved under out_root."""
    args = list(args)
    sub = args[1] if len(args) > 1 else ""
    for flag in ("--steps", "--sim-time"):
        while flag in args:
            i = args.index(flag)
            del args[i:i + 2]
    if sub == "run":
        args += ["--steps", "2"]
    if sub == "compare":  # every model for a tenth of a second, or two iterations
        args += ["--set", "run.sim_time=0.1", "--set", "run.iterations=2"]
    if "--out" in args:
        i = args.index("--out")
        args[i + 1] = str(out_root / args[i + 1])
    return args + (["--quiet"] if sub in ("run", "compare") else [])


def check_commands():
    readme = (source / "README.md").read_text()
    lines = [l.strip() for l in readme.splitlines() if l.strip().startswith("build/runnel ")]
    with tempfile.TemporaryDirectory() as tmp:
        out_root = pathlib.Path(tmp)
        for line in lines:
            args = shlex.split(line.split("  #")[0])
            args[0] = runnel
            result = subprocess.run(quick(args, out_root), cwd=source, capture_output=True,
                                    text=True, timeout=900)
            status = "ok" if result.returncode == 0 else f"exit {result.returncode}"
            print(f"command: {line}: {status}")
            if result.returncode != 0:
                failures.append(f"README: {line}: exit {result.returncode}: {result.stderr.strip()}")
    viewer = [l for l in readme.splitlines() if l.strip().startswith("build/runnel-viewer")]
    for line in viewer:
        print(f"command: {line.strip()}: not run here (the viewer's own tests run it under Xvfb)")


def check_python():
    blocks = re.findall(r"```python\n(.*?)```", (source / "README.md").read_text(), re.S)
    if not pythonpath or not (pathlib.Path(pythonpath) / "runnel").exists():
        print("python: skipped, the Python module is not built (RUNNEL_BUILD_PYTHON)")
        return
    if subprocess.run([python, "-c", "import numpy"], capture_output=True).returncode != 0:
        print(f"python: skipped, {python} has no numpy (scripts/setup-python.sh makes one that has)")
        return
    for block in blocks:
        env = dict(os.environ, PYTHONPATH=pythonpath)
        result = subprocess.run([python, "-c", block], cwd=source, capture_output=True,
                                text=True, timeout=900, env=env)
        print(f"python: the README's example: {'ok' if result.returncode == 0 else 'failed'}")
        if result.returncode != 0:
            failures.append(f"README: the Python example failed: {result.stderr.strip()[-500:]}")


check_links()
check_commands()
check_python()
for f in failures:
    print("FAILED:", f)
sys.exit(1 if failures else 0)
