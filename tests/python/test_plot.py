"""Issue 25 item 5: asperity.plot draws what the results hold (the data of every line and cell,
compared exactly), labels the axes with the quantity and the engine's unit, and
examples/calibrate_one_load.ipynb runs (nbclient) and recovers the alpha_b its curve was made at."""
import json
import math
import os
import re
import subprocess
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pytest  # noqa: E402

import asperity  # noqa: E402


def test_import_asperity_needs_no_matplotlib():
    code = ("import sys; sys.modules['matplotlib'] = None; import asperity; "
            "assert callable(asperity.plot.area_vs_force); print('ok')")
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env=os.environ.copy())
    assert r.returncode == 0 and r.stdout.strip() == "ok", r.stderr


def test_area_vs_force_and_force_vs_time_draw_the_run(source):
    scene = asperity.load_scene(source / "tests" / "data" / "scene" / "small_scene.yaml")
    run = asperity.run(scene)
    measured = asperity.measured(scene)
    ax = asperity.plot.area_vs_force(run, measured=measured)
    model, peak, points = ax.lines
    mm2 = 1e6  # areas in mm², as every figure shows them
    assert list(model.get_xdata()) == list(run.series["Q"]) and list(model.get_ydata()) == list(run.series["A"] * mm2)
    assert (peak.get_xdata()[0], peak.get_ydata()[0]) == (run.summary["Q_s"], run.summary["A_s"] * mm2)
    assert list(points.get_xdata()) == list(measured["Q"]) and list(points.get_ydata()) == list(measured["A"] * mm2)
    assert ax.get_xlabel() == "tangential force $Q$ [N]"
    assert ax.get_ylabel() == "real contact area $A$ [mm$^{2}$]"
    assert [t.get_text() for t in ax.get_legend().get_texts()] == ["model", "peak $(Q_s, A_s)$", "measured"]
    # The same from a DataFrame (Result.frame) into given axes; measured as the CSV's columns.
    fig, (a1, a2) = plt.subplots(1, 2)
    frame = run.frame()
    assert asperity.plot.area_vs_force(frame, measured={"Q_N": measured["Q"], "A_m2": measured["A"]}, ax=a1) is a1
    assert list(a1.lines[0].get_ydata()) == list(run.series["A"] * mm2) and len(a1.lines) == 2
    ax = asperity.plot.force_vs_time(run, ax=a2)
    assert ax is a2 and ax.get_xlabel() == "time $t$ [s]" and ax.get_ylabel() == "tangential force $Q$ [N]"
    assert list(ax.lines[0].get_xdata()) == list(run.series["t"]) and list(ax.lines[0].get_ydata()) == list(run.series["Q"])
    with pytest.raises(ValueError, match="measured: expected columns Q and A"):
        asperity.plot.area_vs_force(run, measured={"force": [1.0]})
    plt.close("all")


def test_labels_carry_the_engines_units():
    # The unit as the command line's figures write it (report/units.cpp unit_markup), in mathtext.
    assert asperity.plot.label("model.alpha_b") == r"$\alpha_b$ [m$^{2p+2}$ N$^{-2}$]"
    assert asperity.units("model.alpha_b") == "m^(2p+2)/N^2"
    assert asperity.plot.label("alpha") == r"area decay $\alpha$ (model) [m$^{2}$ N$^{-2}$]"
    assert asperity.plot.label("model.epsilon") == r"$\epsilon$ [1]"  # dimensionless, as gnuplot's
    assert asperity.plot.label("model.eta") == r"damping $\eta$ [s$^{-1}$]"
    assert asperity.plot.label("steps") == "steps [1]"  # a count, named by its key
    assert asperity.plot.label("A0") == "initial contact area $A_0$ [mm$^{2}$]"
    assert asperity.plot.unit("A0") == ("mm$^{2}$", 1e6) and asperity.plot.unit("Q_s") == ("N", 1.0)
    assert asperity.plot.label("experiment") == "experiment"  # a name: no unit


def test_heatmap_of_a_store(source, tmp_path):
    store = tmp_path / "store"
    asperity.sweep(source / "tests" / "data" / "campaign" / "tiny.yaml", out=store, threads=1, progress=False)
    df = asperity.read_store(store)
    with pytest.raises(ValueError, match=r"3 points share one \(model.eta, model.epsilon\) cell"):
        asperity.plot.heatmap(store, "model.eta", "model.epsilon", "Q_s")  # the mass grid too
    with pytest.raises(KeyError, match="no column 'Qs'"):
        asperity.plot.heatmap(df, "model.eta", "model.epsilon", "Qs")
    grid = df[df["grid"] == "eta_eps"]
    ax = asperity.plot.heatmap(grid, "model.eta", "model.epsilon", "Q_s")
    cells = ax.collections[0].get_array().reshape(3, 3)  # rows: epsilon, columns: eta
    for _, row in grid.iterrows():
        i = [0.5, 0.7, 0.9].index(row["model.epsilon"])
        j = [0, 100, 250].index(row["model.eta"])
        assert cells[i, j] == row["Q_s"]  # exactly the store's number
    assert [t.get_text() for t in ax.get_xticklabels()] == ["0", "100", "250"]
    assert [t.get_text() for t in ax.get_yticklabels()] == ["0.5", "0.7", "0.9"]
    assert ax.get_xlabel() == r"damping $\eta$ [s$^{-1}$]" and ax.get_ylabel() == r"$\epsilon$ [1]"
    colorbar = ax.figure.axes[-1]
    assert colorbar.get_ylabel() == "static friction force $Q_s$ [N]"
    # where= picks the same slice from the whole store, as a dict or as --where strings.
    for where in ({"grid": "eta_eps"}, ["grid=eta_eps"]):
        picked = asperity.plot.heatmap(store, "model.eta", "model.epsilon", "Q_s", where=where)
        assert (picked.collections[0].get_array().reshape(3, 3) == cells).all()
    with pytest.raises(KeyError, match="where: no column 'model.mass'"):
        asperity.plot.heatmap(store, "model.eta", "model.epsilon", "Q_s", where={"model.mass": 1})
    with pytest.raises(ValueError, match="where: no point matches"):
        asperity.plot.heatmap(store, "model.eta", "model.epsilon", "Q_s", where={"grid": "none"})
    plt.close("all")


def run_notebook(path, monkeypatch):
    """The text the notebook's code cells print, run by nbclient in a kernel (Debian
    python3-nbclient, scripts/setup.sh), or without it each code cell in order by exec()."""
    # The kernel inherits the environment: Agg (no display, no inline images), no debugger notes.
    monkeypatch.setenv("MPLBACKEND", "Agg")
    monkeypatch.setenv("PYDEVD_DISABLE_FILE_VALIDATION", "1")
    try:
        import nbclient
        import nbformat
    except ImportError:
        import contextlib
        import io
        cells = json.loads(path.read_text())["cells"]
        monkeypatch.chdir(path.parent)
        out, scope = io.StringIO(), {"__name__": "__main__"}
        with contextlib.redirect_stdout(out):
            for c in cells:
                if c["cell_type"] == "code":
                    exec(compile("".join(c["source"]), str(path), "exec"), scope)
        plt.close("all")
        return out.getvalue()
    nb = nbformat.read(path, as_version=4)
    nbclient.NotebookClient(nb, timeout=120, kernel_name="python3",
                            resources={"metadata": {"path": str(path.parent)}}).execute()
    return "".join(o.get("text", "") for c in nb.cells if c.cell_type == "code" for o in c.outputs)


def test_notebook_calibrates_one_load(source, monkeypatch):
    text = run_notebook(source / "examples" / "calibrate_one_load.ipynb", monkeypatch)
    truth = float(re.search(r"generated at alpha_b = ([0-9.e+-]+)", text).group(1))
    fitted = float(re.search(r"fitted alpha_b = ([0-9.e+-]+)", text).group(1))
    drawn = json.loads(re.search(r"drawn: (\{.*\})", text).group(1))
    print(f"notebook: alpha_b {fitted!r} fitted, {truth!r} generating, relative error {fitted / truth - 1:.2e}")
    assert truth == 0.9e-15
    assert abs(fitted / truth - 1) < 5e-13  # measured 9.8e-14 (16 evaluations, xtol_rel 1e-6)
    assert drawn["area_lines"] == 3 and drawn["force_points"] > 100  # model, peak, curve; Q(t) samples
    assert math.isclose(drawn["Q_s"], drawn["Q_s_lab"], rel_tol=1e-6)
