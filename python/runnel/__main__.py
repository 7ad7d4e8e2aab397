# SPDX-License-Identifier: MIT
"""`python -m runnel ...`: the command-line tool installed with the package, as `runnel ...`;
`python -m runnel plot OUT` draws a command's figures with Matplotlib (runnel.plot, as `runnel-plot OUT`)."""
import os
import shutil
import subprocess
import sys
import sysconfig


def _command_line_tool():
    """The `runnel` executable this environment installed, else the one on PATH (None if neither)."""
    name = "runnel.exe" if os.name == "nt" else "runnel"
    beside = os.path.join(sysconfig.get_path("scripts"), name)
    if os.path.isfile(beside) and os.access(beside, os.X_OK):
        return beside
    return shutil.which("runnel")


def main():
    if sys.argv[1:2] == ["plot"]:
        from .plot import main as plot

        return plot(sys.argv[2:])
    tool = _command_line_tool()
    if tool is None:
        sys.stderr.write(
            "runnel: the command-line tool is not installed with this package (looked in "
            + sysconfig.get_path("scripts")
            + " and on PATH); reinstall with pip install runnel-erosion\n"
        )
        return 2
    return subprocess.call([tool, *sys.argv[1:]])


if __name__ == "__main__":
    sys.exit(main())
