"""asperity: onset of sliding of rough elastomer contacts (Scheibert, Sahli & Peyrard 2020).

The engine of the `asperity` command line, from Python::

    import asperity
    scene = asperity.load_scene("scenes/paper/P4.00N.yaml", {"model.alpha_b": 0.6e-15})
    result = asperity.run(scene)           # GIL released; Ctrl-C interrupts it
    result.summary["Q_s"], result.series["Q"], result.series["A"]   # SI units, NumPy arrays
    fit = asperity.fit("fits/paper_alpha_b.yaml")                   # NLopt calibration
    store = asperity.sweep("sweeps/paper_exploration.yaml", out="results/x")
    df = asperity.read_store("results/x")  # pandas DataFrame, provenance in df.attrs

Errors in inputs raise asperity.InputError (a ValueError) with the one-line message the command
line prints, ``file:line: key: message``; a solver that cannot go on raises asperity.SolverError.
Arguments are checked as the command line's options (a thread count from 1 to 1024, a path without
a NUL byte), the message naming the argument: ``threads: Value 0 not in range 1 to 1024``.
"""
from __future__ import annotations

import os
from dataclasses import dataclass, field
from typing import Any, Mapping, Optional, Sequence, Union

from . import _asperity
from ._asperity import InputError, Scene, SolverError

__all__ = ["InputError", "SolverError", "Scene", "Result", "load_scene", "run", "measured", "sweep",
           "fit", "read_store", "version"]


def _override_text(key: str, value: Any) -> str:
    """One `--set key=value` as the command line spells it (YAML scalars and lists)."""
    if isinstance(value, bool):
        text = "true" if value else "false"
    elif isinstance(value, (list, tuple)):
        text = "[" + ", ".join(str(v) for v in value) + "]"
    else:
        text = repr(value) if isinstance(value, float) else str(value)
    return f"{key}={text}"


def load_scene(path: Union[str, os.PathLike], overrides: Union[Mapping[str, Any], Sequence[str], None] = None) -> Scene:
    """Loads a scene YAML with overrides ({"model.eta": 50} or ["model.eta=50"]), checked as `--set`."""
    if overrides is None:
        sets: list[str] = []
    elif isinstance(overrides, Mapping):
        sets = [_override_text(k, v) for k, v in overrides.items()]
    else:
        sets = list(overrides)
    return _asperity.load_scene(os.fspath(path), sets)


@dataclass
class Result:
    """One run: `summary` (every observable of summary.yaml, SI units), `series` (NumPy arrays
    t [s], X [m], V [m/s], Q [N], A [m²], n_slipping, n_intact), `peaks` (confirmed stick-slip
    peaks and troughs), `summary_yaml` (the text `asperity run` would write)."""
    summary: dict
    series: dict
    peaks: list
    summary_yaml: str = field(repr=False)


def run(scene: Union[Scene, str, os.PathLike], overrides=None) -> Result:
    """Runs a scene (a Scene, or a path loaded with `overrides`)."""
    if not isinstance(scene, Scene):
        scene = load_scene(scene, overrides)
    elif overrides:
        raise ValueError("overrides apply when loading: asperity.load_scene(path, overrides)")
    r = _asperity.run(scene)
    return Result(r["summary"], r["series"], r["peaks"], r["summary_yaml"])


def measured(scene: Scene):
    """The experiment's measured A(Q) as {"Q": [N], "A": [m²]} NumPy arrays, or None."""
    return _asperity.measured(scene)


def sweep(campaign: Union[str, os.PathLike], out: Union[str, os.PathLike] = "", threads: Optional[int] = None,
          shard: str = "0/1") -> dict:
    """Runs (or resumes) a campaign into a store, as `asperity sweep`; returns its counts.
    `threads`: 1 to 1024, as `--threads` (None: every hardware thread). Ctrl-C raises
    KeyboardInterrupt within a second; the store's journal keeps every finished point, so the
    same call again resumes."""
    return _asperity.sweep(os.fspath(campaign), os.fspath(out), threads, shard)


def fit(fit_file: Union[str, os.PathLike], out: Union[str, os.PathLike] = "", threads: Optional[int] = 2,
        profile: bool = False, error_bars: bool = False) -> dict:
    """Runs a calibration (as `asperity fit`); writes its results folder when `out` is given,
    journaling every evaluation there as it finishes (Ctrl-C raises KeyboardInterrupt within a
    second; the same call again resumes). `threads`: 1 to 1024, as `--threads` (None: all).
    Returns {"name", "fits": [{"label", "best": {key: value}, "objective", "evaluations",
    "stop_reason", "failure", "runs": {experiment: summary}}], "wall_s", "replayed", "computed",
    "fit_yaml"} (replayed: evaluations answered from the journal in `out`; computed: run now)."""
    return _asperity.fit(os.fspath(fit_file), os.fspath(out), threads, profile, error_bars)


def read_store(path: Union[str, os.PathLike]):
    """A sweep store's points.csv as a pandas DataFrame; provenance.yaml (parsed when PyYAML is
    installed, else its text) in df.attrs["provenance"], the store path in df.attrs["store"]."""
    path = os.fspath(path)
    _asperity.check_no_nul(path, "path")
    import pandas as pd  # only needed here

    # round_trip: the shortest round-trip decimals of the store read back to the same doubles
    # (pandas' default fast parser may be off in the last bit).
    df = pd.read_csv(os.path.join(path, "points.csv"), float_precision="round_trip")
    prov_file = os.path.join(path, "provenance.yaml")
    provenance: Any = None
    if os.path.exists(prov_file):
        with open(prov_file, encoding="utf-8") as f:
            text = f.read()
        try:
            import yaml
            provenance = yaml.safe_load(text)
        except ImportError:
            provenance = text
    df.attrs["provenance"] = provenance
    df.attrs["store"] = path
    return df


def read_series(path: Union[str, os.PathLike], index: int):
    """The sampled series of one point of a sweep store (campaign `series: true`) as a pandas
    DataFrame, one row per sample; KeyError when the store holds none for that point (not stored,
    failed, or no series). Read from the store's series.csv by the point's scene hash, as
    `asperity` writes and merges it (or from series/HASH.csv in a store written before it)."""
    import io

    texts = _asperity.store_series(os.fspath(path), [int(index)])
    if int(index) not in texts:
        raise KeyError(f"no series of point {index} in {os.fspath(path)}")
    import pandas as pd  # only needed here
    return pd.read_csv(io.StringIO(texts[int(index)]), float_precision="round_trip")


def version() -> str:
    """The build: version, git commit, build type, compiler."""
    return _asperity.version()
