"""asperity: onset of sliding of rough elastomer contacts (Scheibert, Sahli & Peyrard 2020).

The engine of the `asperity` command line, from Python::

    import asperity
    scene = asperity.load_scene("scenes/paper/P4.00N.yaml", {"model.alpha_b": 0.6e-15})
    result = asperity.run(scene)           # GIL released; Ctrl-C interrupts it
    result.summary["Q_s"], result.series["Q"], result.series["A"]   # SI units, NumPy arrays
    fit = asperity.fit("fits/paper_alpha_b.yaml")                   # NLopt calibration
    store = asperity.sweep("sweeps/paper_exploration.yaml", out="results/x")
    df = asperity.read_store("results/x")  # pandas DataFrame, provenance and units in df.attrs
    scene = asperity.Scene.from_dict({"experiment": {"name": "lab", "mass": 0.2, ...}},
                                     areas=df_junctions)   # DataFrame: area_m2 [, x_m, y_m]

Errors in inputs raise asperity.InputError (a ValueError) with the one-line message the command
line prints, ``file:line: key: message``; a solver that cannot go on raises asperity.SolverError.
Arguments are checked as the command line's options (a thread count from 1 to 1024, a path without
a NUL byte), the message naming the argument: ``threads: Value 0 not in range 1 to 1024``.
"""
# Imports under private names: a notebook's dir(asperity) and tab completion show the API only.
import json as _json
import numbers as _numbers
import os as _os
from dataclasses import dataclass as _dataclass, field as _field
from typing import Any as _Any, Mapping as _Mapping, Optional as _Optional, Sequence as _Sequence, Union as _Union

from . import _asperity
from ._asperity import InputError, Scene, SolverError, STAND_IN_MARK
from . import plot  # figures with matplotlib (imported when a function draws)

__version__: str = _asperity.__version__  # the number `asperity --version` prints

__all__ = ["InputError", "SolverError", "Scene", "Result", "load_scene", "run", "measured", "sweep",
           "fit", "FitResult", "read_store", "read_series", "generate_junctions", "tangential_contact", "units", "version", "plot", "STAND_IN_MARK"]

_PathLike = _Union[str, _os.PathLike]


def units(column: str) -> str:
    """The SI unit of a column of a result (an observable, a series column or a scene key), from
    the engine's tables: "N", "m^2", ...; "1" when dimensionless; "" when not a number or unknown."""
    tables = _asperity.units()
    for table in ("series", "observables", "scene_keys"):
        if column in tables[table]:
            return tables[table][column]
    return ""


def _units_of(columns, first: str = "observables") -> dict:
    """{column: unit} for DataFrame attrs, looking in table `first`, then the others."""
    tables = _asperity.units()
    order = [first] + [t for t in ("observables", "series", "scene_keys") if t != first]
    out = {}
    for c in columns:
        out[c] = next((tables[t][c] for t in order if c in tables[t]), "")
    return out


def _progress(progress, what: str, unit: str):
    """(callback(finished, total), bar): `progress` True draws a tqdm bar when tqdm is importable
    (else nothing), a callable is called as is, False/None draws nothing."""
    if callable(progress):
        return progress, None
    if not progress:
        return None, None
    try:
        from tqdm.auto import tqdm as _tqdm
    except ImportError:
        return None, None
    bar = _tqdm(desc=what, unit=unit, leave=True)

    def update(finished: int, total: int) -> None:
        if total and bar.total != total:
            bar.total = total
            bar.refresh()
        bar.update(finished - bar.n)

    return update, bar


def _yaml_value(value: _Any) -> str:
    """A Python value as YAML text that reads back as that value: text is data, never YAML (a
    double-quoted scalar, so "lab #3" keeps its "#3" and "&x" is no anchor)."""
    if hasattr(value, "tolist") and not isinstance(value, (str, bytes)):
        value = value.tolist()  # NumPy scalars and arrays: their Python values
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, _numbers.Integral):
        return str(int(value))
    if isinstance(value, _numbers.Real):
        return repr(float(value))
    if isinstance(value, _Mapping):
        return "{" + ", ".join(f"{_yaml_value(str(k))}: {_yaml_value(v)}" for k, v in value.items()) + "}"
    if isinstance(value, (list, tuple)):
        return "[" + ", ".join(_yaml_value(v) for v in value) + "]"
    text = _os.fspath(value) if isinstance(value, _os.PathLike) else str(value)
    if "\0" in text:
        return text  # left as is: the engine refuses a NUL byte naming `overrides`
    return _json.dumps(text, ensure_ascii=False)  # a JSON string is a YAML double-quoted scalar


def _override_text(key: str, value: _Any) -> str:
    """One `--set key=value` as the command line spells it, the value as data (_yaml_value)."""
    return f"{key}={_yaml_value(value)}"


def load_scene(path: _PathLike, overrides: _Union[_Mapping[str, _Any], _Sequence[str], None] = None) -> Scene:
    """Loads a scene YAML with overrides ({"model.eta": 50} or ["model.eta=50"]), checked as `--set`."""
    if overrides is None:
        sets: list[str] = []
    elif isinstance(overrides, _Mapping):
        sets = [_override_text(k, v) for k, v in overrides.items()]
    else:
        sets = list(overrides)
    return _asperity.load_scene(_os.fspath(path), sets)


@_dataclass
class Result:
    """One run: `summary` (every observable of summary.yaml, SI units), `series` (NumPy arrays
    t [s], X [m], V [m/s], Q [N], A [m²], n_slipping, n_intact), `peaks` (confirmed stick-slip
    peaks and troughs), `summary_yaml` (the text `asperity run` would write), `units` ({name:
    unit} of every summary and series entry, from the engine's tables), `stand_in` (the scene's
    experiment is a stand-in, Scene.stand_in: asperity.plot marks its figures)."""
    summary: dict
    series: dict
    peaks: list
    summary_yaml: str = _field(repr=False)
    units: dict = _field(default_factory=dict, repr=False)
    stand_in: bool = False

    def frame(self):
        """The series as a pandas DataFrame, one row per sample, units in df.attrs["units"],
        Result.stand_in in df.attrs["stand_in"]."""
        import pandas as pd  # only needed here
        df = pd.DataFrame(self.series)
        df.attrs["units"] = _units_of(df.columns, "series")
        df.attrs["stand_in"] = self.stand_in
        return df


def run(scene: _Union[Scene, str, _os.PathLike], overrides=None) -> Result:
    """Runs a scene (a Scene, or a path loaded with `overrides`)."""
    if not isinstance(scene, Scene):
        scene = load_scene(scene, overrides)
    elif overrides:
        raise ValueError("overrides apply when loading: asperity.load_scene(path, overrides)")
    r = _asperity.run(scene)
    units_ = _units_of(r["summary"], "observables")
    units_.update(_units_of(r["series"], "series"))
    return Result(r["summary"], r["series"], r["peaks"], r["summary_yaml"], units_, scene.stand_in)


def generate_junctions(heights, pixel_m: float, *, sphere_radius_m: float, load_N: float, E: float = 1.6e6,
                       nu: float = 0.5, tolerance: float = 1e-10, max_iterations: int = 5000,
                       connectivity: int = 8, threads: int = 1) -> dict:
    """Junctions from a height map given as a NumPy array, as `asperity generate` makes them from a
    recipe with a measured map (docs/topography.md): `heights` n x n [m] (row i at y = i·pixel_m,
    column j at x = j·pixel_m; larger is closer to the flat), without the sphere of radius
    `sphere_radius_m` [m] that is added; pressed with `load_N` [N] into the elastomer (E [Pa], nu).
    Returns {"area_m2", "x_m", "y_m": NumPy arrays (from the map's centre, largest first),
    "contact_area_m2", "clusters", "merges", "iterations", "rms_height_m", "rms_slope"}.
    Bad input raises InputError naming the argument; a contact that does not converge or reaches
    the map's edge raises InputError too."""
    return _asperity.generate_junctions(heights, float(pixel_m), float(sphere_radius_m), float(load_N), float(E),
                                        float(nu), float(tolerance), int(max_iterations), int(connectivity),
                                        int(threads))


def tangential_contact(heights, pixel_m: float, *, sphere_radius_m: float, load_N: float, displacements_m,
                       shear_strength_Pa: _Optional[float] = None, friction_coefficient: _Optional[float] = None,
                       E: float = 1.6e6, nu: float = 0.5, tolerance: float = 1e-10, max_iterations: int = 5000,
                       tangential_tolerance: float = 1e-8, slip_maps: bool = False, threads: int = 1) -> dict:
    """The continuum reference of the junction models (docs/continuum.md): the normal contact of a
    height map as in `generate_junctions`, then the quasi-static tangential contact on its contact
    map under the slider's displacements `displacements_m` [m] (increasing from 0), each pixel in
    contact sticking until its shear traction reaches `shear_strength_Pa` (a constant) or
    `friction_coefficient` · p (Coulomb), then slipping. nu = 0.5 only. Returns
    {"displacement_m", "force_N", "tangent_stiffness_N_per_m", "slip_area_fraction": NumPy arrays,
    "initial_stiffness_N_per_m", "full_sliding_force_N", "full_sliding_displacement_m",
    "contact_area_m2", "converged", "monotone"} and, with `slip_maps`, "slip_maps": one n x n
    uint8 array per displacement (0 outside the contact, 1 sticking, 2 slipping)."""
    return _asperity.tangential_contact(heights, float(pixel_m), float(sphere_radius_m), float(load_N),
                                        [float(d) for d in displacements_m],
                                        0.0 if shear_strength_Pa is None else float(shear_strength_Pa),
                                        0.0 if friction_coefficient is None else float(friction_coefficient),
                                        float(E), float(nu), float(tolerance), int(max_iterations),
                                        float(tangential_tolerance), bool(slip_maps), int(threads))


def measured(scene: Scene):
    """The experiment's measured A(Q) as {"Q": [N], "A": [m²]} NumPy arrays, or None."""
    return _asperity.measured(scene)


def sweep(campaign: _Union[_PathLike, _Mapping[str, _Any]], out: _PathLike = "", threads: _Optional[int] = None,
          shard: str = "0/1", progress=True, base: _Optional[_PathLike] = None) -> dict:
    """Runs (or resumes) a campaign into a store, as `asperity sweep`; returns its counts.
    `campaign`: a campaign YAML file, or a dict of the same keys; a dict needs `out` (the store
    keeps it as its campaign.yaml, with its scene paths made absolute against `base`, default the
    working directory) and is checked by the same loader, whose one-line errors then name that
    file. The same dict again resumes the store; another is refused.
    `threads`: 1 to 1024, as `--threads` (None: every hardware thread). Ctrl-C raises
    KeyboardInterrupt within a second; the store's journal keeps every finished point, so the
    same call again resumes. `progress`: a tqdm bar of points when tqdm is installed (False:
    none; a callable: called as progress(finished, total) every 0.1 s and at the end)."""
    callback, bar = _progress(progress, "sweep", "point")
    try:
        spec = dict(campaign) if isinstance(campaign, _Mapping) else _os.fspath(campaign)
        return _asperity.sweep(spec, _os.fspath(out), threads, shard, callback,
                               None if base is None else _os.fspath(base))
    finally:
        if bar is not None:
            bar.close()


def _objective_term(objective, series: bool):
    """The user's objective as the engine calls it: term(summary, columns) -> float, `columns`
    the series as {column: array} (None unless `series`), given to the user as a DataFrame."""
    def term(summary, columns):
        if series:
            import pandas as pd  # only needed here
            frame = pd.DataFrame(columns)
            frame.attrs["units"] = _units_of(frame.columns, "series")
            value = objective(summary, frame)
        else:
            value = objective(summary)
        try:
            return float(value)
        except (TypeError, ValueError):
            raise TypeError(f"objective: must return a float, got {type(value).__name__}") from None
    return term


def _scene_file(scene: Scene) -> str:
    """A Scene given where a fit takes a scene file, as a file: its to_yaml() text (every value
    explicit, numbers exact) in a folder of the temporary directory private to this user, named
    by the text's SHA-256. The same scene is the same file, so a fit journaled in `out` resumes;
    another scene is another file, so it does not."""
    import hashlib  # only needed here
    import stat
    import tempfile
    text = scene.to_yaml()
    folder = _os.path.join(tempfile.gettempdir(), f"asperity-scenes-{_os.getuid()}")
    try:
        _os.mkdir(folder, 0o700)
    except FileExistsError:
        pass
    st = _os.lstat(folder)
    if not stat.S_ISDIR(st.st_mode) or st.st_uid != _os.getuid() or st.st_mode & 0o077:
        raise InputError(f"{folder}: not a folder private to this user (a symlink, another owner or open "
                         "permissions); remove it to let asperity.fit write Scene objects there")
    path = _os.path.join(folder, hashlib.sha256(text.encode()).hexdigest()[:32] + ".yaml")
    try:
        with open(path, encoding="utf-8") as f:
            if f.read() == text:
                return path
    except FileNotFoundError:
        pass
    fd, tmp = tempfile.mkstemp(dir=folder, suffix=".tmp")
    with _os.fdopen(fd, "w", encoding="utf-8") as f:
        f.write(text)
    _os.replace(tmp, path)
    return path


def _with_scene_files(spec: dict) -> dict:
    """The fit spec with every Scene object among its experiments (an entry, or an entry's
    "scene") replaced by _scene_file's path."""
    experiments = spec.get("experiments")
    if not isinstance(experiments, (list, tuple)):
        return spec
    out = []
    for e in experiments:
        if isinstance(e, Scene):
            e = _scene_file(e)
        elif isinstance(e, _Mapping) and isinstance(e.get("scene"), Scene):
            e = {**e, "scene": _scene_file(e["scene"])}
        out.append(e)
    return {**spec, "experiments": out}


def _callable_id(objective) -> str:
    """An identity of the caller's objective for a fit's journal: the SHA-256 of its source
    (inspect.getsource), else of its code object (a callable without source file, e.g. typed at a
    prompt), with a warning that an edit of what it reads (its data, globals) is not detected."""
    import hashlib
    import inspect
    import marshal
    import warnings
    try:
        text = inspect.getsource(objective).encode()
    except (OSError, TypeError):
        code = getattr(objective, "__code__", None) or getattr(getattr(objective, "__call__", None), "__code__", None)
        if code is None:
            raise TypeError("objective: a fit with out= journals its evaluations under the callable's source or "
                            f"code, and {type(objective).__name__} has neither; leave out empty") from None
        text = marshal.dumps(code)
        warnings.warn("objective: no source found, so the journal is keyed by its code object; an edit of "
                      "the data it reads is not detected", stacklevel=3)
    return "sha256:" + hashlib.sha256(text).hexdigest()


class FitResult(dict):
    """What `fit` returns: the dict described there, plus its tables as pandas DataFrames (one row
    per fit and parameter, profile point or experiment; the fit's label in column "fit").
    Intervals are given only for a fit whose optimum is certified (two starts or more in its best
    basin) and whose Hessian was computed: elsewhere sigma and the interval are NaN."""

    @property
    def parameters(self):
        """value, sigma (marginal), lo95 and hi95 (value -+ 1.96 sigma), bootstrap_sigma (the
        spread of the parametric bootstrap's refits, `intervals: {bootstrap: N}`; else NaN), the
        fit's objective, converged and reduced_chi2, one row per fit and free parameter."""
        import pandas as pd  # only needed here
        rows = []
        for f in self["fits"]:
            u = f.get("uncertainty", {})
            for key, value in f["best"].items():
                sigma = u.get("sigma", {}).get(key, float("nan")) if u.get("computed") else float("nan")
                boot = u.get("bootstrap_sigma", {}).get(key, float("nan"))
                rows.append({"fit": f["label"], "parameter": key, "value": value, "sigma": sigma,
                             "lo95": value - 1.96 * sigma, "hi95": value + 1.96 * sigma, "bootstrap_sigma": boot,
                             "objective": f["objective"], "converged": f["converged"],
                             "reduced_chi2": u.get("reduced_chi2", float("nan"))})
        return pd.DataFrame(rows, columns=["fit", "parameter", "value", "sigma", "lo95", "hi95", "bootstrap_sigma",
                                           "objective", "converged", "reduced_chi2"])

    @property
    def profiles(self):
        """The objective through each fit's optimum along each profiled parameter (the others at
        the optimum): fit, parameter, factor (value / optimum), value, objective."""
        import pandas as pd  # only needed here
        frames = [pd.DataFrame({"fit": f["label"], "parameter": p["parameter"], "factor": p["factor"],
                                "value": p["value"], "objective": p["objective"]})
                  for f in self["fits"] for p in f.get("profiles", [])]
        columns = ["fit", "parameter", "factor", "value", "objective"]
        return pd.concat(frames, ignore_index=True) if frames else pd.DataFrame(columns=columns)

    @property
    def runs(self):
        """Each fit's best run of each experiment: fit, experiment and every observable (the
        summary's fields; units in .attrs["units"])."""
        import pandas as pd  # only needed here
        rows = [{"fit": f["label"], "experiment": name, **summary}
                for f in self["fits"] for name, summary in f["runs"].items()]
        frame = pd.DataFrame(rows)
        frame.attrs["units"] = _units_of(frame.columns, "observables")
        return frame


def fit(spec: _Union[_PathLike, _Mapping[str, _Any]], out: _PathLike = "", threads: _Optional[int] = None,
        profile: bool = True, error_bars: bool = True, progress=True, objective=None, series: bool = False,
        base: _Optional[_PathLike] = None) -> FitResult:
    """Runs a calibration (as `asperity fit`, with its defaults: every hardware thread, the
    profile and the error-bar refits the spec asks for). `spec`: a fit YAML file, or a dict of
    the same keys checked by the same loader (one-line errors naming the key, located at
    "asperity.fit"; scene paths relative to `base`, default the working directory). An
    experiment may be a Scene object (from load_scene or Scene.from_dict), alone or as the
    "scene" of an entry: it is passed as its to_yaml() text in a file named by its SHA-256 in a
    private folder of the temporary directory, which error messages then name.
    `objective`: your own objective, a callable given each run's summary (a dict of every
    observable, plus "experiment": its name) -- and with `series=True` the run's series as a
    DataFrame too -- returning a float; the fit minimises the sum over the experiments with the
    same NLopt machinery (the spec then has no `objective` key; the scene's own stop applies).
    It is called from the fit's worker threads holding the GIL; an exception it raises stops the
    fit and is raised. Writes the results folder when `out` is given, journaling every evaluation
    there as it finishes (Ctrl-C raises KeyboardInterrupt within a second; the same call again
    resumes). With `objective`, the journal is keyed by the SHA-256 of the callable's source
    (inputs.txt, "objective"): an edited callable is refused there (InputError naming
    "objective"), but the data it reads (arrays, globals) are not covered: change `out` when they
    change. `threads`: 1 to 1024, as `--threads` (None: all).
    Returns a FitResult: the dict {"name", "fits": [{"label", "best": {key: value}, "objective",
    "evaluations", "stop_reason", "failure", "converged", "starts", "in_best_basin", "spread",
    "runs": {experiment: summary}, "profiles": [{"parameter", "factor", "value", "objective",
    "interval", "parabola_sigma"}], "uncertainty": {"computed", "failure", "residuals",
    "reduced_chi2", "sigma": {key: sigma}, "bootstrap_sigma": {key: sigma}, "bootstrap_failure"}}],
    "wall_s", "replayed", "computed", "fit_yaml"}
    (replayed: evaluations answered from the journal in `out`; computed: run now), whose
    .parameters, .profiles and .runs are DataFrames.
    `progress`: a tqdm counter of the optimizations' evaluations when tqdm is installed (False:
    none; a callable: called as progress(evaluations, 0) every 0.1 s and at the end)."""
    if isinstance(spec, _Mapping):
        spec = _with_scene_files(dict(spec))
    else:
        spec = _os.fspath(spec)
    if objective is not None and not callable(objective):
        raise TypeError(f"objective: expected a callable, got {type(objective).__name__}")
    term = None if objective is None else _objective_term(objective, series)
    callback, bar = _progress(progress, "fit", "evaluation")
    try:
        objective_id = _callable_id(objective) if objective is not None and _os.fspath(out) else ""
        return FitResult(_asperity.fit(spec, _os.fspath(out), threads, profile, error_bars, callback, term, series,
                                       None if base is None else _os.fspath(base), objective_id))
    finally:
        if bar is not None:
            bar.close()


def read_store(path: _PathLike):
    """A sweep store's points.csv as a pandas DataFrame; provenance.yaml (parsed when PyYAML is
    installed, else its text) in df.attrs["provenance"], the store path in df.attrs["store"],
    {column: unit} in df.attrs["units"]."""
    path = _os.fspath(path)
    _asperity.check_no_nul(path, "path")
    import pandas as pd  # only needed here

    # round_trip: the shortest round-trip decimals of the store read back to the same doubles
    # (pandas' default fast parser may be off in the last bit).
    df = pd.read_csv(_os.path.join(path, "points.csv"), float_precision="round_trip")
    prov_file = _os.path.join(path, "provenance.yaml")
    provenance: _Any = None
    if _os.path.exists(prov_file):
        with open(prov_file, encoding="utf-8") as f:
            text = f.read()
        try:
            import yaml
            provenance = yaml.safe_load(text)
        except ImportError:
            provenance = text
    df.attrs["provenance"] = provenance
    df.attrs["store"] = path
    df.attrs["units"] = _units_of(df.columns, "observables")
    return df


def read_series(path: _PathLike, index: int):
    """The sampled series of one point of a sweep store (campaign `series: true`) as a pandas
    DataFrame, one row per sample; KeyError when the store holds none for that point (not stored,
    failed, or no series). Read from the store's series.csv by the point's scene hash, as
    `asperity` writes and merges it (or from series/HASH.csv in a store written before it);
    {column: unit} in df.attrs["units"]."""
    import io

    texts = _asperity.store_series(_os.fspath(path), [int(index)])
    if int(index) not in texts:
        raise KeyError(f"no series of point {index} in {_os.fspath(path)}")
    import pandas as pd  # only needed here
    df = pd.read_csv(io.StringIO(texts[int(index)]), float_precision="round_trip")
    df.attrs["units"] = _units_of(df.columns, "series")
    return df


def version() -> str:
    """The build: version, git commit, build type, compiler."""
    return _asperity.version()
