"""The Python module against the command line (same engine, same numbers), closed forms, errors,
stores, fits and Ctrl-C."""
import _thread
import math
import subprocess
import threading
import time

import numpy as np
import pytest
import yaml

import asperity


def cli(binary, *args, cwd=None):
    return subprocess.run([binary, *args], cwd=cwd, capture_output=True, text=True)


def test_run_summary_equals_the_command_line(source, binary, tmp_path):
    scene_file = source / "scenes" / "paper" / "P1.52N.yaml"
    sets = {"stop.time": 2.0, "model.eta": 80}
    r = asperity.run(asperity.load_scene(scene_file, sets))
    out = cli(binary, "run", str(scene_file), "--out", str(tmp_path / "run"), "--quiet",
              "--set", "stop.time=2.0", "--set", "model.eta=80")
    assert out.returncode == 0, out.stderr
    written = yaml.safe_load((tmp_path / "run" / "summary.yaml").read_text())
    compared = 0
    for key, value in r.summary.items():
        if key == "wall_s":
            continue
        expected = written[key]
        if isinstance(value, float) and math.isnan(value):
            assert math.isnan(expected), key
        else:
            assert value == expected, key  # %.17g round-trips: exactly equal
        compared += 1
    assert compared > 30
    assert math.isfinite(r.summary["Q_s"])


def test_series_Q_is_the_spring_force(source):
    scene = asperity.load_scene(source / "scenes" / "paper" / "P0.98N.yaml", {"stop.time": 1.0})
    r = asperity.run(scene)
    s = r.series
    experiment = yaml.safe_load((source / "data" / "standin" / "P0.98N" / "experiment.yaml").read_text())
    k_L, v = float(experiment["k_L"]), float(experiment["v"])  # PyYAML reads 1.0e-4 as text
    expected = k_L * (v * s["t"] - s["X"])
    assert len(s["t"]) == 1001
    np.testing.assert_allclose(s["Q"], expected, rtol=1e-12, atol=1e-12 * np.max(np.abs(expected)))
    assert np.all(np.diff(s["t"]) > 0)
    assert s["n_intact"][0] == r.summary["N"]


def test_bad_input_raises_the_command_lines_line(source, binary, tmp_path):
    scene_file = source / "scenes" / "paper" / "P4.00N.yaml"
    with pytest.raises(asperity.InputError) as e:
        asperity.load_scene(scene_file, {"model.epsilon": 1.5})
    assert isinstance(e.value, ValueError)
    out = cli(binary, "run", str(scene_file), "--out", str(tmp_path / "x"), "--set", "model.epsilon=1.5")
    assert out.returncode == 2
    # The same line, naming the override as Python gives it, not as the command line's `--set`.
    assert str(e.value).startswith("overrides: model.epsilon=1.5: model.epsilon:")
    assert out.stderr.strip() == str(e.value).replace("overrides: ", "--set ", 1)
    with pytest.raises(asperity.InputError, match="no-such.yaml"):
        asperity.load_scene(tmp_path / "no-such.yaml")


def test_override_values_are_data_never_yaml(source):
    # A text value given from Python is that text, whatever YAML would make of it unquoted (a
    # comment, an anchor, an alias, a map, a list, a bool, null); numbers, bools and lists too.
    scene_file = source / "scenes" / "paper" / "P0.98N.yaml"
    for name in ["lab #3", "&anchor lab", "*alias", "a: b", "[x, y]", "{z}", 'say "hi"', "back\\slash",
                 "- item", "!tag x", "yes", "null", "~", "0x10", "1e3", "ünï #cödé", "'single'"]:
        assert asperity.load_scene(scene_file, {"experiment.name": name}).experiment == name
    scene = asperity.load_scene(scene_file, {"model.eta": 80, "model.epsilon": 0.5, "stop.at_first_peak": True,
                                             "output.series": ["t", "Q"]})
    y = yaml.safe_load(scene.to_yaml())
    assert (y["model"]["eta"], y["model"]["epsilon"]) == (80, 0.5)
    assert y["stop"]["at_first_peak"] is True and y["output"]["series"] == ["t", "Q"]
    with pytest.raises(asperity.InputError, match="model.eta"):
        asperity.load_scene(scene_file, {"model.eta": "80 # a comment"})  # text, not a number


def test_sweep_and_read_store(source, tmp_path):
    store = tmp_path / "store"
    report = asperity.sweep(source / "tests" / "data" / "campaign" / "tiny.yaml", out=store, threads=1)
    assert report["points"] == 11 and report["ok"] == 11 and report["ran"] == 11
    df = asperity.read_store(store)
    assert len(df) == 11
    assert list(df["index"]) == list(range(11))
    assert df.attrs["provenance"]["campaign"] == "tiny"
    assert df.attrs["provenance"]["provenance"]["command_line"].startswith("python: asperity.sweep(")
    # The values are the store's bytes, parsed: compare one column with the CSV text.
    rows = (store / "points.csv").read_text().splitlines()
    col = rows[0].split(",").index("Q_s")
    assert [float(r.split(",")[col]) for r in rows[1:]] == list(df["Q_s"])
    # A resume runs nothing.
    assert asperity.sweep(source / "tests" / "data" / "campaign" / "tiny.yaml", out=store, threads=1)["ran"] == 0


def test_sweep_of_a_dict_campaign_equals_the_file(source, tmp_path):
    """A campaign as a dict: the same points as the file's (values equal to the bit), kept in the
    store as its campaign.yaml; the same dict resumes, another is refused, errors name the file."""
    data = source / "tests" / "data" / "campaign"
    campaign = {"name": "tiny", "scenes": ["tiny_scene.yaml"], "set": {"stop.time": 0.3},
                "grids": [{"name": "eta_eps", "axes": {"model.eta": [0, 100, 250],
                                                       "model.epsilon": {"linspace": [0.5, 0.9, 3]}}},
                          {"name": "mass", "combine": "zip",
                           "axes": {"experiment.mass": [0.05, 0.1],
                                    "model.alpha_b": {"logspace": [0.3e-15, 1.2e-15, 2]}}}]}
    from_dict = asperity.sweep(campaign, out=tmp_path / "d", threads=1, base=data, progress=False)
    from_file = asperity.sweep(data / "tiny.yaml", out=tmp_path / "f", threads=1, progress=False)
    assert from_dict["ok"] == from_file["ok"] == 11
    a, b = asperity.read_store(tmp_path / "d"), asperity.read_store(tmp_path / "f")
    for column in ("index", "model.eta", "Q_s", "A_s", "t_peak"):
        assert list(a[column]) == list(b[column]), column
    kept = (tmp_path / "d" / "campaign.yaml").read_text()
    assert str(data / "tiny_scene.yaml") in kept  # the scene path made absolute
    assert asperity.sweep(campaign, out=tmp_path / "d", threads=1, base=data, progress=False)["ran"] == 0
    other = dict(campaign, set={"stop.time": 0.2})
    with pytest.raises(asperity.InputError, match="another campaign"):
        asperity.sweep(other, out=tmp_path / "d", threads=1, base=data, progress=False)
    assert (tmp_path / "d" / "campaign.yaml").read_text() == kept  # nothing written
    with pytest.raises(asperity.InputError, match="out="):
        asperity.sweep(campaign, threads=1, base=data, progress=False)
    bad = dict(campaign, grids=[{"axes": {"model.etaa": [1, 2]}}])
    with pytest.raises(asperity.InputError, match=r"campaign\.yaml:\d+: .*model\.etaa"):
        asperity.sweep(bad, out=tmp_path / "bad", threads=1, base=data, progress=False)


def test_read_series_of_a_store_point(source, tmp_path):
    # A series campaign: every point's samples in the store's series.csv, read back per point.
    (tmp_path / "c.yaml").write_text(
        "name: s\nscenes: [" + str(source / "tests" / "data" / "campaign" / "tiny_scene.yaml") + "]\n"
        "series: true\naxes: {model.eta: [50, 100]}\n")
    store = tmp_path / "store"
    assert asperity.sweep(tmp_path / "c.yaml", out=store, threads=1)["ok"] == 2
    df = asperity.read_store(store)
    for index in (0, 1):
        s = asperity.read_series(store, index)
        assert list(s.columns) == ["t", "Q", "A"]
        assert len(s) == 301  # 0.3 s sampled every 1 ms
        assert s["t"].iloc[-1] == df["t_end"][index]
        # The same point run alone gives the same samples, to the last bit.
        run = asperity.run(source / "tests" / "data" / "campaign" / "tiny_scene.yaml",
                           {"model.eta": [50, 100][index]})
        assert list(s["Q"]) == list(run.series["Q"])
    # The whole file is one CSV to pandas (block trailers are comments).
    import pandas as pd
    whole = pd.read_csv(store / "series.csv", comment="#")
    assert list(whole.groupby("index").size()) == [301, 301]
    with pytest.raises(KeyError):
        asperity.read_series(store, 5)


def test_fit_equals_the_command_line(source, binary, tmp_path):
    fit_file = tmp_path / "f.yaml"
    fit_file.write_text(
        "name: small\nobjective: area_curve\nexperiments: [" + str(source / "tests" / "data" / "scene" / "small_scene.yaml") + "]\n"
        "parameters: {model.alpha_b: {lo: 1e-16, hi: 5e-15, start: 1e-15, scale: log}}\n")
    result = asperity.fit(fit_file, threads=1, profile=False, error_bars=False)  # as --no-profile --no-error-bars
    out = cli(binary, "fit", str(fit_file), "--out", str(tmp_path / "fit"), "--threads", "1", "--quiet",
              "--no-profile", "--no-error-bars")
    assert out.returncode in (0, 1), out.stderr
    written = yaml.safe_load((tmp_path / "fit" / "fit.yaml").read_text())["fits"][0]
    (ours,) = result["fits"]
    # The same optimization, evaluation for evaluation: identical numbers.
    assert ours["evaluations"] == written["evaluations"] > 3
    assert ours["objective"] == written["objective"]
    assert ours["best"]["model.alpha_b"] == written["parameters"]["model.alpha_b"]["value"]
    assert 1e-16 <= ours["best"]["model.alpha_b"] <= 5e-15
    assert ours["runs"]["small"]["Q_s"] == written["runs"]["small"]["Q_s"]


def test_ctrl_c_interrupts_a_long_run(source):
    # About 10 s uninterrupted (reference solver, C_t = 1e4, 0.3 s simulated on 1,201 junctions).
    scene = asperity.load_scene(source / "scenes" / "paper" / "P4.00N.yaml",
                                {"solver.method": "reference", "stop.time": 0.3})
    timer = threading.Timer(0.5, _thread.interrupt_main)
    start = time.monotonic()
    timer.start()
    with pytest.raises(KeyboardInterrupt):
        asperity.run(scene)
    elapsed = time.monotonic() - start
    timer.cancel()
    assert elapsed - 0.5 < 1.0, elapsed  # stopped within 1 s of the Ctrl-C (measured ~0.1 s)


def test_generate_junctions_from_numpy(binary, tmp_path):
    """Heights from NumPy give the junctions `asperity generate` makes of the same map in a CSV
    (a second path: file, recipe, command line), and a smooth sphere one junction of Hertz's area."""
    rng = np.random.default_rng(7)
    n, pixel = 64, 5e-3 / 64
    # A rough surface: smoothed noise, 40 µm rms (several clusters under the sphere).
    noise = rng.standard_normal((n, n))
    k = np.fft.fftfreq(n)
    kk = np.hypot(*np.meshgrid(k, k))
    heights = np.real(np.fft.ifft2(np.fft.fft2(noise) * np.exp(-(kk / 0.06) ** 2)))
    heights *= 4e-5 / heights.std()
    j = asperity.generate_junctions(heights, pixel, sphere_radius_m=0.01, load_N=1.0)
    assert j["clusters"] >= 3 and len(j["area_m2"]) >= 2
    assert math.isclose(j["area_m2"].sum(), j["contact_area_m2"], rel_tol=1e-12)
    np.savetxt(tmp_path / "map.csv", heights, delimiter=",", fmt="%.17g")
    (tmp_path / "topo.yaml").write_text(
        "name: numpy-test\ntopography:\n  file: map.csv\n  pixel_m: %r\nsphere_radius_m: 0.01\nE: 1.6e6\nnu: 0.5\n"
        "load_N: 1\ncontact:\n  tolerance: 1e-10\n  max_iterations: 5000\n  connectivity: 8\n" % pixel)
    out = cli(binary, "generate", "--recipe", "topo.yaml", "--out", "gen", "--quiet", cwd=tmp_path)
    assert out.returncode == 0, out.stderr
    rows = [line.split(",") for line in (tmp_path / "gen" / "junctions.csv").read_text().splitlines()
            if line and not line.startswith("#") and not line.startswith("area")]
    table = np.array(rows, dtype=float)
    assert np.array_equal(table[:, 0], j["area_m2"])
    assert np.array_equal(table[:, 1], j["x_m"]) and np.array_equal(table[:, 2], j["y_m"])
    # A smooth sphere: one junction whose area is Hertz's π a², first order in the pixel (the
    # command line's test measures +0.83 % at 128² on this case).
    smooth = asperity.generate_junctions(np.zeros((128, 128)), 5e-3 / 128, sphere_radius_m=0.01, load_N=1.0)
    a = (3 * 1.0 * 0.01 / (4 * 1.6e6 / 0.75)) ** (1 / 3)
    assert len(smooth["area_m2"]) == 1
    assert abs(smooth["area_m2"][0] / (math.pi * a * a) - 1) < 0.015
    # Bad input names the argument.
    with pytest.raises(asperity.InputError, match="heights"):
        asperity.generate_junctions(np.zeros((4, 5)), pixel, sphere_radius_m=0.01, load_N=1.0)
    with pytest.raises(asperity.InputError, match="load_N"):
        asperity.generate_junctions(heights, pixel, sphere_radius_m=0.01, load_N=float("nan"))
    bad = heights.copy()
    bad[3, 5] = np.inf
    with pytest.raises(asperity.InputError, match=r"heights\[3, 5\]"):
        asperity.generate_junctions(bad, pixel, sphere_radius_m=0.01, load_N=1.0)


def test_tangential_contact_follows_cattaneo_mindlin():
    """A smooth sphere with Coulomb friction through the Python call: Q(δ) against
    Cattaneo–Mindlin, Q/μP = 1 − (1 − δ/δ*)^(3/2), δ* = 3μP(2 − ν)/(16Ga), and its slip maps."""
    n, R, P, mu, E = 64, 0.01, 1.0, 0.5, 1.6e6
    a = (3 * P * R / (4 * E / 0.75)) ** (1 / 3)
    G = E / 3
    d_star = 3 * mu * P * 1.5 / (16 * G * a)
    fractions = [0.2, 0.5, 0.8]
    c = asperity.tangential_contact(np.zeros((n, n)), 2.6 * a / n, sphere_radius_m=R, load_N=P,
                                    displacements_m=[f * d_star for f in fractions], friction_coefficient=mu,
                                    slip_maps=True)
    assert c["converged"] and c["monotone"]
    assert math.isclose(c["full_sliding_force_N"], mu * P, rel_tol=1e-10)
    q = c["force_N"] / (mu * P)
    exact = 1 - (1 - np.array(fractions)) ** 1.5
    assert np.max(np.abs(q - exact)) < 1e-4   # 3.1e-5 at 64² in the C++ test of the same case
    for m, s in zip(c["slip_maps"], c["slip_area_fraction"]):
        assert m.shape == (n, n) and m.dtype == np.uint8
        assert math.isclose((m == 2).sum() / (m > 0).sum(), s, rel_tol=1e-12)
    with pytest.raises(asperity.InputError, match="shear_strength_Pa"):
        asperity.tangential_contact(np.zeros((n, n)), 2.6 * a / n, sphere_radius_m=R, load_N=P,
                                    displacements_m=[1e-6], friction_coefficient=mu, shear_strength_Pa=1e5)
    with pytest.raises(asperity.InputError, match="displacements_m"):
        asperity.tangential_contact(np.zeros((n, n)), 2.6 * a / n, sphere_radius_m=R, load_N=P,
                                    displacements_m=[2e-6, 1e-6], friction_coefficient=mu)
