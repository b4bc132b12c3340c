"""The `asperity` command of a pip install (pyproject.toml's [project.scripts]): it replaces the
Python process by the command-line binary shipped in the package (asperity/bin/asperity, copied
from the CMake build by setup.py), with the same arguments; its output, exit status and signals
are the binary's own."""
import os
import pathlib
import signal
import sys


def main() -> None:
    binary = pathlib.Path(__file__).resolve().parent / "bin" / "asperity"
    # Python ignores SIGPIPE and SIGXFSZ, and an ignored signal stays ignored across exec: give the
    # binary the dispositions a shell would (as subprocess's restore_signals does).
    for name in ("SIGPIPE", "SIGXFSZ"):
        if hasattr(signal, name):
            signal.signal(getattr(signal, name), signal.SIG_DFL)
    try:
        os.execv(binary, ["asperity", *sys.argv[1:]])
    except OSError as e:  # 127, as a shell's for a command it cannot run: none of asperity's codes
        print(f"asperity: cannot run the command line {binary}: {e.strerror} (reinstall the package "
              "with pip install .)", file=sys.stderr)
        sys.exit(127)
