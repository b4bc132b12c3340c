"""Issue 25 item 3, fits from Python: a fit spec as a dict (checked by the fit file's loader, with
its one-line errors), a Python objective driving the same NLopt machinery, the command line's
defaults."""
import inspect
import os
import signal
import time

import numpy as np
import yaml
import pytest

import asperity

ALPHA_B_TRUE = 1.3e-15  # m^5/N^2: the value the "measured" curve is generated at


def small_scene(source):
    return source / "tests" / "data" / "scene" / "small_scene.yaml"


def loading_area(frame_or_series, Q):
    """A(Q) of a run's loading branch (the samples whose Q exceeds every earlier one), linearly
    interpolated at the forces Q; A at the branch's end beyond it."""
    q, a = np.asarray(frame_or_series["Q"]), np.asarray(frame_or_series["A"])
    rising = q > np.concatenate(([-np.inf], np.maximum.accumulate(q)[:-1]))
    return np.interp(Q, q[rising], a[rising])


def generated_curve(source):
    """The "measured" A(Q): the model itself at ALPHA_B_TRUE, 40 forces up to 95 % of its Q_s."""
    run = asperity.run(asperity.load_scene(small_scene(source), {"model.alpha_b": ALPHA_B_TRUE}))
    Q = np.linspace(0, 0.95 * run.summary["Q_s"], 40)
    return Q, loading_area(run.series, Q), run.summary


def spec(**extra):
    d = {"name": "py",
         "experiments": ["small_scene.yaml"],
         "parameters": {"model.alpha_b": {"lo": 1e-16, "hi": 5e-15, "start": 0.7e-15, "scale": "log"}},
         "optimizer": {"algorithm": "LN_BOBYQA", "xtol_rel": 1e-6, "max_evaluations": 60, "initial_step": 0.1},
         "profile": False}
    d.update(extra)
    return d


def test_python_objective_recovers_alpha_b_of_a_model_generated_curve(source):
    Q, A, truth = generated_curve(source)
    calls = []

    def area_misfit(summary, frame):  # mean squared relative area difference over the curve
        calls.append(summary["experiment"])
        assert frame.attrs["units"]["A"] == "m^2" and list(frame.columns)[:5] == ["t", "X", "V", "Q", "A"]
        model = loading_area(frame, Q)
        return float(np.mean(((model - A) / summary["A0"]) ** 2))

    base = source / "tests" / "data" / "scene"
    result = asperity.fit(spec(), base=base, threads=1, objective=area_misfit, series=True, progress=False)
    (f,) = result["fits"]
    assert f["failure"] == "" and f["stop_reason"] == "XTOL_REACHED", f
    best = f["best"]["model.alpha_b"]
    print(f"python objective: alpha_b = {best!r} (truth {ALPHA_B_TRUE}), {f['evaluations']} evaluations, "
          f"relative error {best / ALPHA_B_TRUE - 1:.2e}, objective {f['objective']:.3e}")
    # Measured: relative error 5.3e-13, 18 evaluations (BOBYQA on a curve the model reproduces
    # exactly: the misfit is quadratic in log alpha_b near the truth, far inside xtol_rel 1e-6).
    assert abs(best / ALPHA_B_TRUE - 1) < 2e-12
    assert f["objective"] < 1e-12
    assert len(calls) >= f["evaluations"] and set(calls) == {"small"}
    # The best run's summary is the model's at the fitted value: its Q_s is the truth's.
    assert f["runs"]["small"]["Q_s"] == pytest.approx(truth["Q_s"], rel=1e-9)

    # A summary-only objective (no series): the model's own alpha of the curve, matched.
    target = truth["alpha"]
    result = asperity.fit(spec(), base=base, threads=1, progress=False,
                          objective=lambda s: (s["alpha"] / target - 1.0) ** 2)
    best = result["fits"][0]["best"]["model.alpha_b"]
    print(f"summary objective: alpha_b = {best!r}, relative error {best / ALPHA_B_TRUE - 1:.2e}")
    assert abs(best / ALPHA_B_TRUE - 1) < 1e-11  # measured 2.5e-12


def test_dict_spec_gives_the_yaml_specs_fit_exactly(source, tmp_path, monkeypatch):
    d = spec(objective="area_curve")
    d["optimizer"]["xtol_rel"] = 1e-4
    fit_file = tmp_path / "py.yaml"
    scene = small_scene(source)
    # The same keys in a file (the experiment by its absolute path: the file is elsewhere).
    fit_file.write_text(
        "name: py\nobjective: area_curve\n"
        f"experiments: [{scene}]\n"
        "parameters: {model.alpha_b: {lo: 1e-16, hi: 5e-15, start: 0.7e-15, scale: log}}\n"
        "optimizer: {algorithm: LN_BOBYQA, xtol_rel: 1e-4, max_evaluations: 60, initial_step: 0.1}\n"
        "profile: false\n")
    from_file = asperity.fit(fit_file, threads=1, progress=False)
    from_dict = asperity.fit(d, base=scene.parent, threads=1, progress=False)
    monkeypatch.chdir(scene.parent)  # relative to the working directory without `base`
    from_cwd = asperity.fit(d, threads=1, progress=False)
    a, b, c = from_file["fits"][0], from_dict["fits"][0], from_cwd["fits"][0]
    assert a["evaluations"] > 3
    for other in (b, c):
        assert other["best"]["model.alpha_b"] == a["best"]["model.alpha_b"]  # exactly
        assert (other["objective"], other["evaluations"], other["stop_reason"]) == (
            a["objective"], a["evaluations"], a["stop_reason"])
        assert other["runs"]["small"]["Q_s"] == a["runs"]["small"]["Q_s"]
    assert "fit_file: \"\"" in from_dict["fit_yaml"] or "fit_file: ''" in from_dict["fit_yaml"]


def test_dict_spec_errors_are_the_fit_files_lines(source, tmp_path):
    base = source / "tests" / "data" / "scene"

    def both(mutate, yaml_text):
        """(the dict's message, the same spec's message from a file), locations cut."""
        d = spec(objective="area_curve")
        mutate(d)
        with pytest.raises(asperity.InputError) as from_dict:
            asperity.fit(d, base=base, threads=1, progress=False)
        f = tmp_path / "bad.yaml"
        f.write_text(yaml_text)
        with pytest.raises(asperity.InputError) as from_file:
            asperity.fit(f, threads=1, progress=False)
        a, b = str(from_dict.value), str(from_file.value)
        assert a.startswith("asperity.fit: ") and b.startswith(str(f) + ":")
        assert "\n" not in a
        return a[len("asperity.fit: "):], b.split(": ", 1)[1]

    head = f"name: py\nobjective: area_curve\nexperiments: [{base / 'small_scene.yaml'}]\n"
    params = "parameters: {model.alpha_b: {lo: 1e-16, hi: 5e-15, start: 0.7e-15, scale: log}}\n"
    a, b = both(lambda d: d["optimizer"].update(xtol=1e-3), head + params + "optimizer: {xtol: 1e-3}\n")
    assert a == b and a.startswith("optimizer.xtol: unknown key"), a
    a, b = both(lambda d: d["parameters"]["model.alpha_b"].update(start=9e-15),
                head + "parameters: {model.alpha_b: {lo: 1e-16, hi: 5e-15, start: 9e-15, scale: log}}\n")
    assert a == b == "parameters.model.alpha_b.start: must be in [lo, hi] = [1e-16, 5e-15], got 9e-15"
    a, b = both(lambda d: d.update(objective="area"), head.replace("area_curve", "area") + params)
    assert a == b and a.startswith("objective: "), a
    a, b = both(lambda d: d.update(colour="red"), head + params + "colour: red\n")
    assert a == b and a.startswith("colour: unknown key"), a

    # A Python objective: the spec has none of its own; series needs it.
    with pytest.raises(asperity.InputError, match=r"^asperity.fit: objective: the objective is the caller's own"):
        asperity.fit(spec(objective="area_curve"), base=base, objective=lambda s: 0.0, progress=False)
    with pytest.raises(asperity.InputError, match=r"^series: "):
        asperity.fit(spec(objective="area_curve"), base=base, series=True, progress=False)
    with pytest.raises(asperity.InputError, match=r"^base: is for a dict spec"):
        asperity.fit(tmp_path / "bad.yaml", base=base, progress=False)
    with pytest.raises(TypeError, match="objective: expected a callable"):
        asperity.fit(spec(), base=base, objective=1.5, progress=False)


def test_python_objectives_exceptions_and_ctrl_c_propagate(source):
    base = source / "tests" / "data" / "scene"
    calls = []

    def boom(summary):
        calls.append(1)
        if len(calls) == 3:
            raise ValueError("boom from the objective")
        return (summary["Q_s"] - 0.05) ** 2

    with pytest.raises(ValueError, match="boom from the objective"):
        asperity.fit(spec(), base=base, threads=1, progress=False, objective=boom)
    assert len(calls) == 3  # the fit stopped at the raise: no evaluation after it

    with pytest.raises(TypeError, match="objective: must return a float, got str"):
        asperity.fit(spec(), base=base, threads=1, progress=False, objective=lambda s: "small")

    # Ctrl-C (SIGINT to this process, from the objective's worker thread) stops the fit: the main
    # thread's poll (every 0.1 s) raises KeyboardInterrupt while the objective sleeps without the
    # GIL, and no evaluation starts after it.
    calls.clear()

    def interrupt(summary):
        calls.append(1)
        if len(calls) == 3:
            os.kill(os.getpid(), signal.SIGINT)
            time.sleep(1.0)
        return (summary["Q_s"] - 0.05) ** 2

    with pytest.raises(KeyboardInterrupt):
        asperity.fit(spec(), base=base, threads=1, progress=False, objective=interrupt)
    assert len(calls) == 3, len(calls)


def test_defaults_are_the_command_lines():
    # `asperity fit`: every hardware thread, the profile and error-bar refits unless --no-profile,
    # --no-error-bars.
    p = inspect.signature(asperity.fit).parameters
    assert p["threads"].default is None and p["profile"].default is True and p["error_bars"].default is True


def test_fit_result_tables_match_its_dict(source):
    """FitResult's DataFrames repeat the dict's numbers. area_curve is not a chi-square, so its
    certified optimum (two starts agree) gets no intervals: sigma and the interval are NaN."""
    base = source / "tests" / "data" / "scene"
    d = spec(objective="area_curve", profile={"parameter": "model.alpha_b", "span": 0.1, "points": 5})
    d["optimizer"] = {"algorithm": "LN_BOBYQA", "xtol_rel": 1e-6, "max_evaluations": 60, "initial_step": 0.1,
                      "starts": 2}
    result = asperity.fit(d, base=base, threads=1, progress=False)
    assert isinstance(result, asperity.FitResult) and isinstance(result, dict)
    (f,) = result["fits"]
    assert f["converged"] == "yes" and not f["uncertainty"]["computed"]
    params = result.parameters
    assert list(params["parameter"]) == ["model.alpha_b"] and list(params["fit"]) == [f["label"]]
    assert params["value"][0] == f["best"]["model.alpha_b"] and params["objective"][0] == f["objective"]
    assert params["converged"][0] == "yes"
    assert np.isnan(params["sigma"][0]) and np.isnan(params["lo95"][0]) and np.isnan(params["hi95"][0])
    prof = result.profiles
    assert len(prof) == 5 and set(prof["parameter"]) == {"model.alpha_b"}
    assert prof["factor"].tolist() == pytest.approx([0.9, 0.95, 1.0, 1.05, 1.1])
    assert prof["value"].tolist() == pytest.approx((prof["factor"] * f["best"]["model.alpha_b"]).tolist(), rel=1e-12)
    centre = prof[prof["factor"] == 1.0]["objective"].iloc[0]
    assert centre == pytest.approx(f["objective"], rel=1e-9)  # the profile passes through the optimum
    assert prof["objective"].min() == pytest.approx(f["objective"], rel=1e-9)
    runs = result.runs
    assert list(runs["experiment"]) == ["small"] and runs["Q_s"][0] == f["runs"]["small"]["Q_s"]
    assert runs.attrs["units"]["Q_s"] == "N"


def chi_square_spec(source, tmp_path, **extra):
    """An area_and_force fit of the small scene against 40 samples of the model's own Q(t) at
    ALPHA_B_TRUE, two starts: (spec, base)."""
    run = asperity.run(asperity.load_scene(small_scene(source), {"model.alpha_b": ALPHA_B_TRUE}))
    t, Q = np.asarray(run.series["t"]), np.asarray(run.series["Q"])
    pick = np.linspace(0, len(t) - 1, 40).astype(int)
    force = tmp_path / "Qt.csv"
    force.write_text("t_s,Q_N\n" + "".join(f"{t[i]!r},{Q[i]!r}\n" for i in pick))
    d = spec(objective="area_and_force", noise={"area": 0.002, "force": 0.002},
             experiments=[{"scene": str(small_scene(source)), "force": str(force)}], **extra)
    d["optimizer"]["starts"] = 2
    return d, source / "tests" / "data" / "scene"


def test_fit_result_intervals_at_a_certified_chi_square(source, tmp_path):
    """A chi-square objective (area_and_force, against a Q(t) the model made) at a certified
    optimum: sigma is the Hessian's, and a second method, the parabola through the profile,
    agrees with it (measured 4 % apart); the 95 % interval is value -+ 1.96 sigma."""
    d, base = chi_square_spec(source, tmp_path, profile={"parameter": "model.alpha_b", "span": 0.1, "points": 5})
    result = asperity.fit(d, base=base, threads=1, progress=False)
    (f,) = result["fits"]
    assert f["converged"] == "yes" and f["uncertainty"]["computed"], f
    params = result.parameters
    value, sigma = params["value"][0], params["sigma"][0]
    assert sigma == f["uncertainty"]["sigma"]["model.alpha_b"] and 0 < sigma < 0.2 * value
    assert params["lo95"][0] == pytest.approx(value - 1.96 * sigma, rel=1e-12)
    assert params["hi95"][0] == pytest.approx(value + 1.96 * sigma, rel=1e-12)
    assert params["reduced_chi2"][0] == f["uncertainty"]["reduced_chi2"] > 0
    (profile,) = f["profiles"]
    assert profile["parabola_sigma"] == pytest.approx(sigma, rel=0.15)
    lo, hi = profile["interval"]
    assert lo < value < hi
    assert np.isnan(params["bootstrap_sigma"][0]) and f["uncertainty"]["bootstrap_sigma"] == {}  # none asked


def test_fit_result_bootstrap_sigma_is_fit_yaml_s(source, tmp_path):
    """intervals: {bootstrap: N}: the spread of N refits of synthetic data drawn at the optimum
    (its agreement with the Hessian where the objective is quadratic is tested in C++,
    tests/unit/fit/test_fit_joint.cpp) reaches Python as written in fit.yaml, per parameter."""
    d, base = chi_square_spec(source, tmp_path, intervals={"bootstrap": 4, "bootstrap_seed": 3})
    result = asperity.fit(d, base=base, threads=1, progress=False)
    (f,) = result["fits"]
    assert f["uncertainty"]["computed"] and f["uncertainty"]["bootstrap_failure"] == "", f
    (written,) = yaml.safe_load(result["fit_yaml"])["fits"]
    boot = written["uncertainty"]["bootstrap"]
    assert boot["draws"] == boot["succeeded"] == 4 and boot["seed"] == 3
    sigma = boot["parameters"]["model.alpha_b"]["sigma"]
    assert sigma > 0 and f["uncertainty"]["bootstrap_sigma"]["model.alpha_b"] == sigma
    assert result.parameters["bootstrap_sigma"][0] == sigma


def area_term(summary):  # a Python objective with a source file: journaled under its digest
    return (summary["alpha"] / 2.0e-7 - 1.0) ** 2


def area_term_edited(summary):
    return (summary["alpha"] / 2.1e-7 - 1.0) ** 2


def test_python_objective_is_journaled_under_its_source(source, tmp_path):
    """fit(out=..., objective=...) journals every evaluation; the same call resumes from the journal
    alone, and an edited callable (another source) is refused by the journal's inputs check."""
    base = source / "tests" / "data" / "scene"
    out = tmp_path / "o"
    first = asperity.fit(spec(), base=base, out=out, threads=1, objective=area_term, progress=False)
    f = first["fits"][0]
    assert f["failure"] == "" and first["computed"] > 0  # (a point NLopt asks for twice is replayed)
    inputs = (out / "inputs.txt").read_text()
    assert "objective sha256:" in inputs
    again = asperity.fit(spec(), base=base, out=out, threads=1, objective=area_term, progress=False)
    assert again["computed"] == 0 and again["replayed"] == first["computed"] + first["replayed"]
    assert again["fits"][0]["best"] == f["best"] and again["fits"][0]["objective"] == f["objective"]
    with pytest.raises(asperity.InputError, match=r"inputs.txt:\d+: objective: the journal was computed with another"):
        asperity.fit(spec(), base=base, out=out, threads=1, objective=area_term_edited, progress=False)
    assert (out / "inputs.txt").read_text() == inputs  # nothing rewritten


def test_scene_objects_fit_as_their_files(source, tmp_path):
    """A Scene object where a fit takes a scene file (alone, or as an entry's "scene"): the same
    optimum, to the last bit, as the file it was loaded from; the same Scene resumes a journal
    in `out`, and a Scene that differs is refused by the journal's inputs check."""
    base = source / "tests" / "data" / "scene"
    by_file = asperity.fit(spec(), base=base, threads=1, objective=area_term, progress=False)
    scene = asperity.load_scene(small_scene(source))
    for entry in (scene, {"scene": scene}):
        by_object = asperity.fit(spec(experiments=[entry]), base=base, threads=1, objective=area_term,
                                 progress=False)
        assert by_object["fits"][0]["best"] == by_file["fits"][0]["best"]
        assert by_object["fits"][0]["objective"] == by_file["fits"][0]["objective"]
    out = tmp_path / "o"
    first = asperity.fit(spec(experiments=[scene]), base=base, out=out, threads=1, objective=area_term,
                         progress=False)
    again = asperity.fit(spec(experiments=[scene]), base=base, out=out, threads=1, objective=area_term,
                         progress=False)
    assert first["computed"] > 0 and again["computed"] == 0
    assert again["replayed"] == first["computed"] + first["replayed"]
    other = asperity.load_scene(small_scene(source), {"model.eta": 60})
    with pytest.raises(asperity.InputError, match="inputs.txt"):
        asperity.fit(spec(experiments=[other]), base=base, out=out, threads=1, objective=area_term, progress=False)
