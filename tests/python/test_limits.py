"""Python's limits are the command line's: thread counts from 1 to 1024, paths without a NUL byte
(InputError naming the argument), and Ctrl-C stops a sweep or a fit within a second keeping its
journal, so that the same call resumes it."""
import hashlib
import os
import signal
import subprocess
import sys
import time

import pytest

import asperity


def python(code, **kw):
    """Runs `code` in a fresh interpreter: a crash (the segfault inside TBB) fails the test there."""
    return subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120, **kw)


@pytest.mark.parametrize("threads", [10**9, -1, 0, 10**30])
def test_thread_counts_outside_the_command_lines_range_raise_input_error(source, binary, tmp_path, threads):
    campaign = source / "tests" / "data" / "campaign" / "tiny.yaml"
    fit_file = source / "tests" / "data" / "fit" / "fit.yaml"
    out = tmp_path / "out"
    r = python(
        "import asperity\n"
        "for call in (lambda: asperity.sweep(%r, out=%r, threads=%d), lambda: asperity.fit(%r, out=%r, threads=%d)):\n"
        "    try:\n"
        "        call()\n"
        "        print('accepted')\n"
        "    except asperity.InputError as e:\n"
        "        print(e)\n" % (str(campaign), str(out), threads, str(fit_file), str(out), threads))
    assert r.returncode == 0, r.stderr  # no crash
    message = f"threads: Value {threads} not in range 1 to 1024"
    assert r.stdout.splitlines() == [message, message]
    assert not out.exists()  # refused before anything is written
    # The command line's own line, for the same count, says the same after its option's name.
    if abs(threads) < 2**31:
        cli = subprocess.run([binary, "sweep", str(campaign), "--threads", str(threads), "--out", str(out)],
                             capture_output=True, text=True)
        assert cli.returncode == 2
        assert cli.stderr.strip() == f"asperity: --{message} (asperity --help)"


def test_a_nul_in_a_path_raises_input_error(source, tmp_path):
    campaign = str(source / "tests" / "data" / "campaign" / "tiny.yaml")
    fit_file = str(source / "tests" / "data" / "fit" / "fit.yaml")
    scene = str(source / "tests" / "data" / "campaign" / "tiny_scene.yaml")
    store = str(tmp_path / "store")
    # Each path would name an existing file (or a usable folder) if cut at the NUL.
    calls = {
        "campaign": lambda: asperity.sweep(campaign + "\0.bak", out=store, threads=1),
        "out": lambda: asperity.sweep(campaign, out=store + "\0/x", threads=1),
        "fit_file": lambda: asperity.fit(fit_file + "\0.bak", threads=1),
        "path": lambda: asperity.load_scene(scene + "\0.bak"),
        "overrides": lambda: asperity.load_scene(scene, ["model.eta=50\0junk"]),
    }
    for argument, call in calls.items():
        with pytest.raises(asperity.InputError) as e:
            call()
        assert str(e.value).count("\n") == 0
        assert f": {argument}: holds a NUL byte" in str(e.value), argument
        assert "\\0" in str(e.value)  # the NUL shown, not cut
    with pytest.raises(asperity.InputError, match=": out: holds a NUL byte"):
        asperity.fit(fit_file, out=str(tmp_path / "fit") + "\0x", threads=1)
    with pytest.raises(asperity.InputError, match=": path: holds a NUL byte"):
        asperity.read_series(store + "\0x", 0)
    with pytest.raises(asperity.InputError, match=": path: holds a NUL byte"):
        asperity.read_store(store + "\0x")
    assert not (tmp_path / "store").exists() and not (tmp_path / "fit").exists()


def journal_rows(path):
    """The rows of a journal (store or fit) after its header, each checked against its SHA-256."""
    lines = path.read_text().splitlines()
    assert lines and lines[0].endswith(",sha256")
    rows = []
    for line in lines[1:]:
        row, digest = line.rsplit(",", 1)
        assert hashlib.sha256(row.encode()).hexdigest() == digest, line
        rows.append(row)
    return rows


def interrupt_when(cmd, journal, enough, after=0.3):
    """Starts `cmd`, sends SIGINT `after` s once `journal` holds `enough` rows; returns (seconds
    from the signal to the end, the process's stderr, rows seen when the signal went)."""
    p = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    start = time.monotonic()
    seen = 0
    while time.monotonic() - start < 60 and p.poll() is None:
        seen = len(journal_rows(journal)) if journal.exists() else 0
        if seen >= enough:
            break
        time.sleep(0.02)
    time.sleep(after)
    assert p.poll() is None, "ended before the signal: " + p.stderr.read()
    assert seen >= enough, f"the journal held {seen} rows after 60 s"
    sent = time.monotonic()
    p.send_signal(signal.SIGINT)
    try:
        _, err = p.communicate(timeout=10)
    except subprocess.TimeoutExpired:
        p.kill()
        raise
    return time.monotonic() - sent, err, seen


def points_without_wall_time(store):
    lines = (store / "points.csv").read_text().splitlines()
    wall = lines[0].split(",").index("wall_s")
    return [",".join(f for i, f in enumerate(line.split(",")) if i != wall) for line in lines]


def test_ctrl_c_stops_a_sweep_within_a_second_and_the_same_call_resumes(source, tmp_path):
    # Three short points (~0.2 s each), then three long ones (~1.6 s each): the signal comes while
    # a long point runs, so the sweep must interrupt it, not wait for it.
    campaign = tmp_path / "slow.yaml"
    campaign.write_text(
        "name: slow\nscenes: [" + str(source / "tests" / "data" / "campaign" / "tiny_scene.yaml") + "]\n"
        "set: {output.series: [], output.every: 0.02, model.eta: 50}\n"
        "grids:\n"
        "  - {name: short, axes: {stop.time: [1500, 1501, 1502]}}\n"
        "  - {name: long, axes: {stop.time: [15000, 15001, 15002]}}\n")
    store = tmp_path / "store"
    code = f"import asperity; asperity.sweep({str(campaign)!r}, out={str(store)!r}, threads=1)"
    elapsed, err, seen = interrupt_when([sys.executable, "-c", code], store / "journal.csv", enough=3)
    print(f"sweep: {elapsed:.3f} s from SIGINT to exit, {seen} points journaled")
    assert elapsed < 1.0, elapsed
    assert err.rstrip().endswith("KeyboardInterrupt"), err
    rows = journal_rows(store / "journal.csv")  # every line whole, its digest right
    assert seen <= len(rows) < 6
    assert sorted(int(r.split(",")[0]) for r in rows) == list(range(len(rows)))  # the points done, in order
    assert all(",ok," in r for r in rows)
    # The same call resumes: only the points not journaled run, and the store is the one an
    # uninterrupted sweep writes.
    report = asperity.sweep(campaign, out=store, threads=1)
    assert report["skipped"] == len(rows) and report["ran"] == 6 - len(rows) and report["ok"] == 6
    whole = tmp_path / "whole"
    assert asperity.sweep(campaign, out=whole, threads=1)["ran"] == 6
    assert points_without_wall_time(store) == points_without_wall_time(whole)


def test_ctrl_c_stops_a_fit_within_a_second_and_the_same_call_resumes(source, tmp_path):
    # Three separate fits, a profile and error-bar refits: ~125 evaluations, a few seconds.
    fit_file = source / "tests" / "data" / "fit" / "fit.yaml"
    out = tmp_path / "fit"
    code = (f"import asperity; asperity.fit({str(fit_file)!r}, out={str(out)!r}, threads=1, profile=True, "
            "error_bars=True)")
    elapsed, err, seen = interrupt_when([sys.executable, "-c", code], out / "journal.csv", enough=20, after=0.1)
    print(f"fit: {elapsed:.3f} s from SIGINT to exit, {seen} evaluations journaled")
    assert elapsed < 1.0, elapsed
    assert err.rstrip().endswith("KeyboardInterrupt"), err
    rows = journal_rows(out / "journal.csv")
    assert len(rows) >= seen
    assert not (out / "fit.yaml").exists()  # unfinished: no results yet
    # The same call replays every journaled evaluation and ends as an uninterrupted fit.
    resumed = asperity.fit(fit_file, out=out, threads=1, profile=True, error_bars=True)
    assert resumed["replayed"] == len(rows)
    whole = asperity.fit(fit_file, out=tmp_path / "whole", threads=1, profile=True, error_bars=True)
    assert whole["replayed"] == 0 and resumed["computed"] == whole["computed"] - len(rows)
    for a, b in zip(resumed["fits"], whole["fits"], strict=True):
        assert (a["label"], a["best"], a["objective"], a["evaluations"]) == (b["label"], b["best"], b["objective"],
                                                                           b["evaluations"])
    assert len(journal_rows(out / "journal.csv")) == len(journal_rows(tmp_path / "whole" / "journal.csv"))


def test_a_run_in_a_child_forked_after_an_openmp_run_completes(source):
    """libgomp's pool does not survive fork(): the child of a process whose run used an OpenMP team
    (two threads, 294 junctions on the reference solver) runs single-threaded instead of hanging,
    to the same numbers."""
    scene = str(source / "scenes" / "paper" / "P0.98N.yaml")
    code = (
        "import os, sys, asperity\n"
        "scene = asperity.load_scene(%r, ['solver.method=reference', 'solver.Ct=200', 'stop.time=0.01'])\n"
        "parent = asperity.run(scene).series['Q']\n"
        "r, w = os.pipe()\n"
        "pid = os.fork()\n"
        "if pid == 0:\n"
        "    os.close(r)\n"
        "    q = asperity.run(scene).series['Q']\n"
        "    os.write(w, repr([float(x) for x in q]).encode())\n"
        "    os._exit(0)\n"
        "os.close(w)\n"
        "data = b''\n"
        "while chunk := os.read(r, 1 << 20):\n"
        "    data += chunk\n"
        "_, status = os.waitpid(pid, 0)\n"
        "print(os.waitstatus_to_exitcode(status), len(parent), eval(data.decode()) == [float(x) for x in parent],\n"
        "      float(parent[-1]))\n" % scene)
    r = python(code, env=dict(os.environ, OMP_NUM_THREADS="2"))  # a team even on a one-core machine
    assert r.returncode == 0, r.stderr
    status, samples, same, last_q = r.stdout.split()
    assert status == "0"
    assert int(samples) > 5
    assert same == "True"  # the child's Q(t), sample for sample
    assert float(last_q) > 0
