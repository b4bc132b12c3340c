"""Every Python figure (asperity.plot, scripts/topography_study.py) drawn from a stand-in input and
from the same input that does not say it is one: the stand-in mark (asperity.STAND_IN_MARK)
exactly on the first, and each axis label's unit the one the engine's units table gives
(asperity.plot.unit: areas in mm², as the command line's figures)."""
import importlib.util
import re
import shutil

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import matplotlib.text  # noqa: E402
import pytest  # noqa: E402

import asperity  # noqa: E402


def texts(fig):
    return [t.get_text() for t in fig.findobj(matplotlib.text.Text) if t.get_text()]


def check(ax, stand_in, axes):
    """The mark exactly when `stand_in`; {axis label: column} each ending in the column's unit."""
    fig = ax.figure
    assert (asperity.STAND_IN_MARK in texts(fig)) == stand_in
    for text, column in axes.items():
        unit = asperity.plot.unit(column)[0]
        assert unit and text.endswith(f" [{unit}]"), (text, column, unit)


def experiment_as(source, tmp_path, stand_in):
    """A copy of the five-junction test experiment whose description says it is a stand-in, or not."""
    exp = tmp_path / "exp"
    shutil.copytree(source / "tests" / "data" / "scene" / "exp_small", exp)
    y = exp / "experiment.yaml"
    description = "STAND-IN, NOT A MEASUREMENT: test copy" if stand_in else "test copy, measured"
    y.write_text(re.sub(r"^description:.*$", f'description: "{description}"', y.read_text(), flags=re.M))
    scene = tmp_path / "scene.yaml"
    scene.write_text("experiment: exp/experiment.yaml\nstop: {time: 0.3}\noutput: {series: [t, Q, A]}\n")
    return scene


@pytest.mark.parametrize("stand_in", [True, False])
def test_run_figures_mark_stand_ins_and_use_the_units_table(source, tmp_path, stand_in):
    scene = asperity.load_scene(experiment_as(source, tmp_path, stand_in))
    assert scene.stand_in == stand_in
    run = asperity.run(scene)
    ax = asperity.plot.area_vs_force(run, measured=asperity.measured(scene))
    check(ax, stand_in, {ax.get_xlabel(): "Q", ax.get_ylabel(): "A"})
    ax = asperity.plot.force_vs_time(run.frame())  # the DataFrame carries stand_in too
    check(ax, stand_in, {ax.get_xlabel(): "t", ax.get_ylabel(): "Q"})
    plt.close("all")


@pytest.mark.parametrize("stand_in", [True, False])
def test_store_heatmap_marks_stand_ins_and_uses_the_units_table(source, tmp_path, stand_in):
    scene = experiment_as(source, tmp_path, stand_in)
    campaign = {"name": "marks", "scenes": [str(scene)],
                "axes": {"model.eta": [0, 100], "model.epsilon": [0.5, 0.9]}}
    store = tmp_path / "store"
    asperity.sweep(campaign, out=store, threads=1, progress=False)
    ax = asperity.plot.heatmap(store, "model.eta", "model.epsilon", "A0")
    bar = ax.figure.axes[-1]
    check(ax, stand_in, {ax.get_xlabel(): "model.eta", ax.get_ylabel(): "model.epsilon", bar.get_ylabel(): "A0"})
    plt.close("all")


def test_topography_figures_in_the_house_style(source, tmp_path, monkeypatch):
    """fig_AQ shows stand-in curves (marked), fig_ccdf synthetic surfaces only (not marked); both at
    the journal width, areas in mm²."""
    spec = importlib.util.spec_from_file_location("topography_study", source / "scripts" / "topography_study.py")
    study = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(study)
    for name in ("table.csv", "ccdf.csv", "AQ.csv"):
        shutil.copy(source / "results" / "topography" / name, tmp_path / name)
    monkeypatch.setattr(study, "HERE", str(tmp_path))
    drawn = {}
    monkeypatch.setattr(plt, "close", lambda fig=None: drawn.setdefault(len(drawn), fig))
    study.redraw(("png",))
    ccdf, aq = drawn[0], drawn[1]
    assert asperity.STAND_IN_MARK not in texts(ccdf) and asperity.STAND_IN_MARK in texts(aq)
    check(ccdf.axes[0], False, {ccdf.axes[0].get_xlabel(): "A0"})
    assert ccdf.get_size_inches()[0] == pytest.approx(asperity.plot.COLUMN_WIDTH_IN)
    assert (tmp_path / "fig_ccdf.png").exists() and (tmp_path / "fig_AQ.png").exists()
