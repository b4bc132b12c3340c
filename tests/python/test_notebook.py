"""Issue 25, Python for notebooks: scenes from Python objects (checked by the scene loader, as a
file is), the version, a clean namespace, units on results, type stubs and progress bars."""
import ast
import math
import pathlib
import re
import subprocess
import sys

import numpy as np
import pandas as pd
import pytest
import yaml

import asperity

EXPERIMENT_KEYS = ("name", "description", "mass", "k_L", "v", "E", "nu", "sigma_exp")


def small(source):
    """The small test scene as a dict, its experiment given whole, and its data as DataFrames."""
    folder = source / "tests" / "data" / "scene"
    scene = yaml.safe_load((folder / "small_scene.yaml").read_text())
    experiment = yaml.safe_load((folder / "exp_small" / "experiment.yaml").read_text())
    # PyYAML reads 1.0e-4 as text: the loader parses it as a file's, so pass it on as it is.
    scene["experiment"] = {k: experiment[k] for k in EXPERIMENT_KEYS}
    junctions = pd.read_csv(folder / "exp_small" / "junctions.csv", comment="#", float_precision="round_trip")
    measured = pd.read_csv(folder / "exp_small" / "measured.csv", float_precision="round_trip")
    return scene, junctions, measured


def assert_same_summary(a, b):
    compared = 0
    for key, value in a.summary.items():
        if key == "wall_s":
            continue
        other = b.summary[key]
        if isinstance(value, float) and math.isnan(value):
            assert math.isnan(other), key
        else:
            assert value == other, key  # exactly
        compared += 1
    assert compared > 30


def test_scene_from_arrays_equals_the_yaml_scene(source):
    from_file = asperity.load_scene(source / "tests" / "data" / "scene" / "small_scene.yaml")
    d, junctions, measured = small(source)
    from_arrays = asperity.Scene.from_dict(d, areas=junctions["area_m2"].to_numpy(), x=junctions["x_m"].to_numpy(),
                                           y=list(junctions["y_m"]), measured=measured)
    from_frame = asperity.Scene.from_dict(d, areas=junctions, measured={"Q_N": measured["Q_N"], "A_m2": measured["A_m2"]})
    assert from_arrays.junctions == from_file.junctions == 5
    assert from_arrays.file == "" and from_file.file.endswith("small_scene.yaml")
    assert "from memory" in repr(from_arrays)
    assert from_frame.to_yaml() == from_arrays.to_yaml()
    # The same scene: every value but where the experiment's data are (a file, or inline).
    def values(text):
        return [l for l in text.splitlines() if not l.startswith(("  file:", "  junctions:", "  measured:", "      "))]
    assert values(from_file.to_yaml()) == values(from_arrays.to_yaml())
    a, b = asperity.run(from_file), asperity.run(from_arrays)
    assert_same_summary(a, b)
    assert math.isfinite(a.summary["alpha_measured"])  # the measured curve came along
    for column in a.series:
        assert list(a.series[column]) == list(b.series[column]), column


def test_to_yaml_loads_back_to_the_same_scene(source, tmp_path):
    d, junctions, measured = small(source)
    scene = asperity.Scene.from_dict(d, areas=junctions, measured=measured)
    text = scene.to_yaml()
    assert "junctions: {area_m2: [" in text and "file:" not in text
    again = asperity.Scene.from_yaml(text)
    assert again.to_yaml() == text
    (tmp_path / "s.yaml").write_text(text)
    from_file = asperity.load_scene(tmp_path / "s.yaml")  # a scene file may hold its data inline too
    assert from_file.to_yaml() == text
    assert_same_summary(asperity.run(scene), asperity.run(again))
    # And a scene loaded from a file: its text names the experiment file and loads back as well.
    paper = asperity.load_scene(source / "tests" / "data" / "scene" / "small_scene.yaml")
    assert asperity.Scene.from_yaml(paper.to_yaml()).to_yaml() == paper.to_yaml()


def test_from_dict_takes_an_experiment_path_relative_to_the_working_directory(source, monkeypatch):
    monkeypatch.chdir(source / "tests" / "data" / "scene")
    scene = asperity.Scene.from_dict({"experiment": "exp_small/experiment.yaml", "model": {"eta": 50}})
    assert scene.junctions == 5 and scene.experiment == "small"


def message(call):
    with pytest.raises(asperity.InputError) as e:
        call()
    assert isinstance(e.value, ValueError)
    return str(e.value)


def test_from_dict_errors_are_the_loaders_lines(source, binary, tmp_path):
    d, junctions, _ = small(source)
    areas = junctions["area_m2"].to_numpy()
    x, y = junctions["x_m"].to_numpy(), junctions["y_m"].to_numpy()
    from_dict = lambda d=d, **kw: asperity.Scene.from_dict(d, **{"areas": areas, "x": x, "y": y, **kw})  # noqa: E731

    # A value out of its range: the command line's message, after the location.
    bad = dict(d, model={"epsilon": 1.5})
    ours = message(lambda: from_dict(bad))
    assert ours == "Scene.from_dict: model.epsilon: must be in (0, 1], got 1.5"
    theirs = message(lambda: asperity.load_scene(source / "tests" / "data" / "scene" / "small_scene.yaml",
                                                 {"model.epsilon": 1.5}))
    assert theirs.endswith(": model.epsilon: must be in (0, 1], got 1.5")
    typo = message(lambda: from_dict(dict(d, modle={})))
    assert typo.startswith("Scene.from_dict: ") and "'modle'" in typo and "did you mean 'model'" in typo
    assert message(lambda: from_dict(dict(d, experiment={k: v for k, v in d["experiment"].items() if k != "mass"}))) \
        == "Scene.from_dict: experiment.mass: missing required key"
    assert message(lambda: from_dict(dict(d, model={"eta": "1.6 MPa"}))).startswith(
        "Scene.from_dict: model.eta: expected a plain number")

    # Junction values: the CSV reader's words, naming the value.
    csv = tmp_path / "j.csv"
    csv.write_text("area_m2\n1e-8\n1e-8\n-1e-08\n")
    (tmp_path / "e.yaml").write_text("name: e\nmass: 0.1\nk_L: 9200\nv: 1e-4\nE: 1.6e6\nnu: 0.5\n"
                                     "sigma_exp: 0.23e6\njunctions: j.csv\n")
    (tmp_path / "s.yaml").write_text("experiment: e.yaml\n")
    csv_line = message(lambda: asperity.load_scene(tmp_path / "s.yaml"))
    assert csv_line.endswith("area_m2: junction area must be in [1e-20, 1] m^2, got -1e-08")
    bad_areas = areas.copy()
    bad_areas[2] = -1e-8
    assert message(lambda: from_dict(areas=bad_areas)) == \
        "Scene.from_dict: experiment.junctions.area_m2[2]: junction area must be in [1e-20, 1] m^2, got -1e-08"
    for value in (2.0, 1e-21):
        bad_areas[2] = value
        assert "junction area must be in [1e-20, 1] m^2" in message(lambda: from_dict(areas=bad_areas))
    bad_areas[2] = np.nan
    assert message(lambda: from_dict(areas=bad_areas)) == \
        "Scene.from_dict: experiment.junctions.area_m2[2]: must be a finite number, got 'nan'"
    far = x.copy()
    far[4] = 2e9
    assert message(lambda: from_dict(x=far)) == \
        "Scene.from_dict: experiment.junctions.x_m[4]: junction centre must be within +-1e+09 m, got 2e+09"
    far[4] = -np.inf
    assert "x_m[4]: must be a finite number" in message(lambda: from_dict(x=far))
    assert message(lambda: from_dict(y=None)) == \
        "Scene.from_dict: experiment.junctions.y_m: x_m and y_m must be given together (or neither)"
    assert message(lambda: from_dict(x=x[:4])) == \
        "Scene.from_dict: experiment.junctions.x_m: has 4 values, area_m2 has 5 (one per junction)"
    assert "at least one" in message(lambda: from_dict(areas=[], x=None, y=None))
    assert message(lambda: from_dict(areas=junctions.assign(z_m=0.0), x=None, y=None)) == \
        "Scene.from_dict: areas: unknown column 'z_m' (did you mean 'x_m'?); valid: area_m2, x_m, y_m"
    assert "experiment.junctions: unknown key 'junctions'" in message(
        lambda: from_dict(dict(d, experiment=dict(d["experiment"], file="e.yaml"))))  # the file has the data
    assert "force must be >= 0, got -1" in message(lambda: from_dict(measured={"Q_N": [-1.0], "A_m2": [1e-8]}))
    with pytest.raises(TypeError):
        from_dict(areas=["a", "b"])


def test_version_is_the_command_lines(binary):
    out = subprocess.run([binary, "--version"], capture_output=True, text=True).stdout
    number = re.match(r"asperity (\S+) \(", out).group(1)
    assert asperity.__version__ == number
    assert asperity.version().startswith("asperity " + number + " (")


def test_namespace_is_the_api():
    public = sorted(n for n in dir(asperity) if not n.startswith("_"))
    assert public == sorted(asperity.__all__)
    assert "read_series" in asperity.__all__
    for leaked in ("Any", "os", "dataclass", "field", "annotations", "Union", "Optional"):
        assert leaked not in dir(asperity)


def test_units_come_from_the_engines_tables(source, tmp_path):
    # docs/units.md is generated from the same C++ tables: every row agrees.
    rows = re.findall(r"^\| `([^`]+)` \| ([^|]+) \|$", (source / "docs" / "units.md").read_text(), re.M)
    assert len(rows) > 40
    for column, unit in rows:
        unit = unit.strip()
        assert asperity.units(column) == ("" if unit == "(text or true/false)" else unit), column
    assert asperity.units("Q_s") == "N" and asperity.units("A") == "m^2" and asperity.units("t") == "s"

    r = asperity.run(source / "tests" / "data" / "scene" / "small_scene.yaml")
    assert r.units["Q_s"] == "N" and r.units["A0"] == "m^2" and r.units["peak_found"] == ""
    df = r.frame()
    assert df.attrs["units"] == {"t": "s", "X": "m", "V": "m/s", "Q": "N", "A": "m^2", "n_slipping": "1",
                                 "n_intact": "1"}
    assert list(df["Q"]) == list(r.series["Q"])

    store = tmp_path / "store"
    asperity.sweep(source / "tests" / "data" / "campaign" / "tiny.yaml", out=store, threads=1, progress=False)
    points = asperity.read_store(store)
    u = points.attrs["units"]
    assert set(u) == set(points.columns)
    assert u["Q_s"] == "N" and u["model.eta"] == "1/s" and u["model.epsilon"] == "1" and u["status"] == ""


def test_type_stubs_match_the_package():
    stub = pathlib.Path(asperity.__file__).with_name("__init__.pyi")
    assert stub.exists() and stub.with_name("py.typed").exists()  # installed next to the package
    tree = ast.parse(stub.read_text())
    names, scene_methods = set(), set()
    for node in tree.body:
        if isinstance(node, (ast.FunctionDef, ast.ClassDef)):
            names.add(node.name)
        elif isinstance(node, ast.AnnAssign) and isinstance(node.target, ast.Name):
            names.add(node.target.id)
        elif isinstance(node, ast.ImportFrom) and node.level == 1:  # `from . import plot as plot`: a re-export
            names.update(a.name for a in node.names if a.asname == a.name)
        if isinstance(node, ast.ClassDef) and node.name == "Scene":
            scene_methods = {n.name for n in node.body if isinstance(n, ast.FunctionDef)}
    public = {n for n in names if not n.startswith("_")}
    assert public == set(asperity.__all__)
    assert {"__version__", "__all__"} <= names
    assert scene_methods == {n for n in dir(asperity.Scene) if not n.startswith("_")}
    plot_stub = ast.parse(stub.with_name("plot.pyi").read_text())
    assert {n.name for n in plot_stub.body if isinstance(n, ast.FunctionDef)} == set(asperity.plot.__all__)


def test_sweep_and_fit_report_progress(source, tmp_path):
    calls = []
    report = asperity.sweep(source / "tests" / "data" / "campaign" / "tiny.yaml", out=tmp_path / "s", threads=1,
                            progress=lambda done, total: calls.append((done, total)))
    assert calls and calls[-1] == (11, 11) == (report["points"], report["points"])
    assert all(a[0] <= b[0] for a, b in zip(calls, calls[1:]))

    fit_file = tmp_path / "f.yaml"
    fit_file.write_text(
        "name: small\nobjective: area_curve\nexperiments: [" + str(source / "tests" / "data" / "scene" / "small_scene.yaml") + "]\n"
        "parameters: {model.alpha_b: {lo: 1e-16, hi: 5e-15, start: 1e-15, scale: log}}\n")
    calls = []
    result = asperity.fit(fit_file, threads=1, profile=False, progress=lambda done, total: calls.append((done, total)))
    # Every evaluation (the optimization's, the best point's re-run) against the budget given from
    # the start; the finished fit adds what it left unused, so the count ends at the budget.
    done, total = calls[-1]
    assert done == total > result["fits"][0]["evaluations"] > 3
    assert all(t == total for _, t in calls) and all(a[0] <= b[0] for a, b in zip(calls, calls[1:]))

    def boom(done, total):
        raise RuntimeError("from the progress callback")
    with pytest.raises(RuntimeError, match="progress callback"):
        asperity.sweep(source / "tests" / "data" / "campaign" / "tiny.yaml", out=tmp_path / "s2", threads=1,
                       progress=boom)


def test_tqdm_bar_when_importable_and_nothing_without(source, tmp_path, capfd, monkeypatch):
    campaign = source / "tests" / "data" / "campaign" / "tiny.yaml"
    pytest.importorskip("tqdm")
    asperity.sweep(campaign, out=tmp_path / "a", threads=1)
    assert "11/11" in capfd.readouterr().err
    monkeypatch.setitem(sys.modules, "tqdm", None)  # import tqdm now raises ImportError
    monkeypatch.setitem(sys.modules, "tqdm.auto", None)
    assert asperity.sweep(campaign, out=tmp_path / "b", threads=1)["ok"] == 11
    assert capfd.readouterr().err == ""


def test_overlapping_junctions_from_arrays_name_the_key(source):
    """An overlap is found once the scene is whole: named as Scene.from_dict's experiment.junctions."""
    d, _, _ = small(source)
    d["model"] = dict(d.get("model") or {}, interactions="elastic")
    with pytest.raises(asperity.InputError) as e:
        asperity.Scene.from_dict(d, areas=[1e-8, 1e-8], x=[0.0, 1e-5], y=[0.0, 0.0])
    assert str(e.value).startswith("Scene.from_dict: experiment.junctions: junctions 1 and 2 overlap (centres 1e-05 m")
