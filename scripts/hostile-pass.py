#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""A hostile pass over the command line: every scenario parameter and every flag of every
subcommand given values a careless script or a hostile file would give, each run on a tiny terrain
for one step. A case passes when runnel exits 0, 1 or 2 without a signal within its time limit (2, refused,
where the value cannot be meant: a number parameter given nan, inf, 1e309, text or nothing, a
switch given text or nothing, any flag given nothing); on exit 1 or 2, when stderr is exactly one
line without terminal control bytes and at most 2,100 bytes; on exit 2, when the output folder it
was given was not created. Prints the counts per
category and every failing case.

    python3 scripts/hostile-pass.py [build/runnel] [--limit SECONDS]
"""
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile

runnel = os.path.abspath(
    sys.argv[1] if len(sys.argv) > 1 and not sys.argv[1].startswith("--") else "build/runnel")
limit = float(sys.argv[sys.argv.index("--limit") + 1]) if "--limit" in sys.argv else 60.0

BAD_NUMBERS = ["nan", "inf", "-inf", "-1", "1e309", "1e30", "abc", ""]
BAD_TEXT = ["", "x" * 5000, "\x1b[2J\x1b[H", "/dev/zero", "../../../../etc/passwd", "nope"]
CONTROL = re.compile(r"[\x00-\x08\x0b-\x1f\x7f]")


def parameter_keys():
    text = subprocess.run([runnel, "params"], capture_output=True, text=True).stdout
    keys = []
    for line in text.splitlines():
        m = re.match(r"^([a-z_]+(?:\.[a-z_0-9]+)+) = (.*)$", line)
        if m:
            keys.append((m.group(1), m.group(2)))
    return keys


def cases():
    base = ["run", "--generate", "plane", "--set", "terrain.size=17", "--steps", "1", "--quiet"]
    for key, default in parameter_keys():
        text = default.startswith('"')
        switch = default in ("true", "false")
        values = BAD_TEXT[:4] if text else BAD_NUMBERS
        for v in values:
            # A text parameter may take any text (an empty path is "none"): only its form is judged.
            refuse = not text and (switch or v not in ("-1", "1e30"))
            yield "parameter " + key.split(".")[0], base + ["--set", f"{key}={v}"], refuse
    flags = {
        "run": (["run", "--generate", "plane", "--set", "terrain.size=17"],
                ["--steps", "--sim-time", "--seed", "--checkpoint-every", "--keep-checkpoints",
                 "--series-every", "--particles-every", "--terrain", "--generate", "--device",
                 "--trace", "--model"]),
        "generate": (["generate", "fbm", "--size", "9"], ["--size", "--cell", "--seed", "--set", "--range"]),
        "validate": (["validate", "droplet"], ["--resolution", "--settle", "--set", "--length", "--spacing"]),
        "bench": (["bench", "sph", "--steps", "1"], ["--particles", "--steps", "--tile", "--set", "--scene"]),
        "compare": (["compare", "--generate", "plane", "--set", "terrain.size=17"],
                    ["--models", "--terrain", "--set"]),
        "sweep": (["sweep"], ["--jobs", "--member", "--time"]),
        "export": (["export", "missing.h5", "--format", "asc"], ["--format", "--range", "-o"]),
    }
    for command, (base_args, names) in flags.items():
        for name in names:
            for v in BAD_NUMBERS + BAD_TEXT[1:3]:
                yield "flag " + command, base_args + [name, v], v == ""
    for flag in ["--overwrite=2", "--quiet=7", "--steps=", "--out="]:
        yield "flag form", ["run", "--generate", "plane", "--set", "terrain.size=17", flag], True


def check(args, refuse, work):
    out = os.path.join(work, "out")
    shutil.rmtree(out, ignore_errors=True)
    full = [runnel] + args + (["--out", out] if args[0] in ("run", "compare", "sweep") else [])
    if args[0] == "sweep":
        full.insert(2, os.path.join(work, "missing.toml"))
    try:
        r = subprocess.run(full, capture_output=True, timeout=limit, cwd=work)
    except subprocess.TimeoutExpired:
        return "ran past %g s" % limit
    err = r.stderr.decode("utf-8", "replace")
    if r.returncode < 0 or r.returncode > 2:
        return "exit %d" % r.returncode
    if refuse and r.returncode != 2:
        return "exit %d where the value should be refused" % r.returncode
    if r.returncode in (1, 2):
        if len(err.strip().splitlines()) != 1:
            return "%d lines on stderr" % len(err.strip().splitlines())
        if CONTROL.search(err.rstrip("\n")):
            return "a control byte on stderr"
        if len(err) > 2100:
            return "a line of %d bytes" % len(err)
    if r.returncode == 2 and os.path.exists(out):
        return "exit 2 but the output folder was created"
    return None


def main():
    counts, failures = {}, []
    with tempfile.TemporaryDirectory() as work:
        for category, args, refuse in cases():
            problem = check(args, refuse, work)
            ok, total = counts.get(category, (0, 0))
            counts[category] = (ok + (problem is None), total + 1)
            if problem:
                failures.append((category, args, problem))
    for category, (ok, total) in sorted(counts.items()):
        print(f"{category:24s} {ok:5d} of {total:5d} pass")
    passed = sum(ok for ok, _ in counts.values())
    total = sum(t for _, t in counts.values())
    print(f"{'all':24s} {passed:5d} of {total:5d} pass")
    for category, args, problem in failures:
        print(f"FAIL {category}: {problem}: {json.dumps(args)[:200]}")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
