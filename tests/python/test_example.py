"""examples/calibrate_alpha_b.py runs, writes its figure, fits alpha_b inside the bounds and
refuses to overwrite."""
import os
import re
import subprocess
import sys


def test_example_calibrates_and_draws(source, tmp_path):
    out = tmp_path / "fig.png"
    cmd = [sys.executable, str(source / "examples" / "calibrate_alpha_b.py"), "--load", "P0.98N", "--quick",
           "--out", str(out)]
    r = subprocess.run(cmd, capture_output=True, text=True, env=os.environ.copy())
    assert r.returncode == 0, r.stderr
    alpha = float(re.search(r"alpha_b = ([0-9.e+-]+) m\^5/N\^2", r.stdout).group(1))
    assert 0.1e-15 <= alpha <= 5.0e-15
    assert out.stat().st_size > 10_000
    assert out.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    again = subprocess.run(cmd, capture_output=True, text=True, env=os.environ.copy())
    assert again.returncode != 0 and "not overwriting" in again.stderr
