"""Figures of runs and sweep stores with matplotlib (imported when a function draws, so that
`import asperity` needs no matplotlib). Every function draws into `ax` (a new figure's axes when
None) and returns the Axes; axis labels name the quantity and its SI unit from the engine's tables
(asperity.units)::

    run = asperity.run(scene)
    asperity.plot.area_vs_force(run, measured=asperity.measured(scene))   # A(Q)
    asperity.plot.force_vs_time(run)                                      # Q(t)
    asperity.plot.heatmap("results/x", "model.eta", "model.epsilon", "Q_s")
"""
import re as _re

__all__ = ["area_vs_force", "force_vs_time", "heatmap", "label"]

# Names of the quantities the figures show (the key itself for any other column).
_NAMES = {
    "t": "time $t$", "X": "slider position $X$", "V": "slider velocity $V$", "Q": "tangential force $Q$",
    "A": "real contact area $A$", "n_slipping": "slipping junctions", "n_intact": "intact junctions",
    "Q_s": "static friction force $Q_s$", "A_s": "contact area at the peak $A_s$", "A0": "initial contact area $A_0$",
    "t_peak": "time of the peak $t_s$", "alpha": r"area decay $\alpha$ (model)",
    "alpha_measured": r"area decay $\alpha$ (measured)", "area_drop_fraction": "area drop fraction",
    "shape_exponent": "shape exponent $n$", "ss_drop": "stick-slip force drop", "ss_period": "stick-slip period",
    "ss_cycles": "stick-slip cycles", "K0": "initial stiffness $K_0$", "wall_s": "wall time",
    "model.alpha_b": r"$\alpha_b$", "model.eta": r"damping $\eta$", "model.epsilon": r"$\epsilon$",
    "model.c_min": r"$c_{\min}$", "model.p": "$p$", "experiment.mass": "mass $m$",
    "experiment.k_L": "loading stiffness $k_L$", "experiment.v": "driving velocity $v$",
    "experiment.E": "Young's modulus $E$", "experiment.nu": r"Poisson's ratio $\nu$",
    "experiment.sigma_exp": r"$\sigma_{\mathrm{exp}}$",
}


def _mathtext_unit(unit: str) -> str:
    """"m^2/N^2" → "m$^{2}$/N$^{2}$", "m^(2p+2)" → "m$^{2p+2}$" (matplotlib's mathtext)."""
    return _re.sub(r"\^\(?([-+0-9a-zA-Z.]+)\)?", r"$^{\1}$", unit)


def label(column: str) -> str:
    """An axis label: the quantity's name and its SI unit from asperity.units (none when
    dimensionless), e.g. "tangential force $Q$ [N]"."""
    from . import units  # the package's, from the engine's tables
    unit = units(column)
    name = _NAMES.get(column, column)
    return name if unit in ("", "1") else f"{name} [{_mathtext_unit(unit)}]"


def _axes(ax):
    if ax is not None:
        return ax
    import matplotlib.pyplot as plt  # only when drawing
    return plt.subplots(figsize=(4.5, 3.2), layout="constrained")[1]


def _series(result):
    """The columns of a run: a Result's series, a DataFrame (Result.frame(), read_series) or a
    mapping of arrays."""
    return result.series if hasattr(result, "series") and not hasattr(result, "columns") else result


def _measured_columns(measured):
    """(Q, A) of a measured curve: asperity.measured's {"Q", "A"}, or a DataFrame/mapping with
    the measured CSV's columns Q_N, A_m2."""
    keys = list(measured.columns) if hasattr(measured, "columns") else list(measured.keys())
    if "Q" in keys and "A" in keys:
        return measured["Q"], measured["A"]
    if "Q_N" in keys and "A_m2" in keys:
        return measured["Q_N"], measured["A_m2"]
    raise ValueError(f"measured: expected columns Q and A (or Q_N and A_m2), got {keys}")


def area_vs_force(result, measured=None, ax=None):
    """A(Q): the run's contact area against its tangential force (a line), the peak (Q_s, A_s)
    marked when the result has a summary, and the measured curve (points) when given
    (asperity.measured(scene), or a DataFrame with Q_N, A_m2). Returns the Axes."""
    ax = _axes(ax)
    s = _series(result)
    ax.plot(s["Q"], s["A"], "-", lw=1.2, label="model")
    summary = getattr(result, "summary", None)
    if summary and summary.get("peak_found"):
        ax.plot([summary["Q_s"]], [summary["A_s"]], "o", ms=4, color="C0", label="peak $(Q_s, A_s)$")
    if measured is not None:
        q, a = _measured_columns(measured)
        ax.plot(q, a, ".", ms=3, color="C1", label="measured")
    ax.set_xlabel(label("Q"))
    ax.set_ylabel(label("A"))
    ax.legend(loc="best", frameon=False)
    return ax


def force_vs_time(result, ax=None):
    """Q(t): the run's tangential force against time. Returns the Axes."""
    ax = _axes(ax)
    s = _series(result)
    ax.plot(s["t"], s["Q"], "-", lw=1.2)
    ax.set_xlabel(label("t"))
    ax.set_ylabel(label("Q"))
    return ax


def _where(store, where):
    """The rows of `store` matching every `column=value` of `where` (a dict, or strings as the
    command line's --where); numbers compare to 1e-12 relative."""
    import numpy as np
    items = where.items() if hasattr(where, "items") else (w.split("=", 1) for w in where)
    for key, value in items:
        key = key.strip()
        if key not in store.columns:
            raise KeyError(f"where: no column {key!r} in the store (columns: {', '.join(store.columns)})")
        column = store[key]
        if np.issubdtype(column.dtype, np.number):
            keep = np.isclose(column.to_numpy(dtype=float), float(value), rtol=1e-12, atol=0)
        else:
            keep = (column.astype(str) == str(value).strip()).to_numpy()
        store = store[keep]
    if store.empty:
        raise ValueError(f"where: no point matches {dict(where) if hasattr(where, 'items') else list(where)}")
    return store


def heatmap(store, x_key, y_key, field, ax=None, where=None):
    """`field` (an observable of the store's points.csv, e.g. "Q_s") over the grid of two swept
    keys, one cell per (x, y) point, a colour bar labelled with the field's quantity and unit;
    failed points are blank. `store`: a store folder or asperity.read_store's DataFrame. When the
    store varies other keys too, `where` picks one slice, as the command line's --where: a dict
    {"model.eta": 100} or strings ["model.eta=100"]. Returns the Axes."""
    import numpy as np
    if not hasattr(store, "columns"):
        from . import read_store
        store = read_store(store)
    for key in (x_key, y_key, field):
        if key not in store.columns:
            raise KeyError(f"heatmap: no column {key!r} in the store (columns: {', '.join(store.columns)})")
    if where:
        store = _where(store, where)
    cells = store.groupby([y_key, x_key]).size()
    if (cells > 1).any():
        raise ValueError(f"heatmap: {int(cells.max())} points share one ({x_key}, {y_key}) cell: the store varies "
                         "other keys too; pick one slice with where={key: value}")
    grid = store.pivot(index=y_key, columns=x_key, values=field)
    xs, ys = list(grid.columns), list(grid.index)
    ax = _axes(ax)
    values = np.ma.masked_invalid(grid.to_numpy(dtype=float))
    mesh = ax.pcolormesh(np.arange(len(xs) + 1) - 0.5, np.arange(len(ys) + 1) - 0.5, values, shading="flat")
    ax.set_xticks(range(len(xs)), [f"{v:.3g}" for v in xs])
    ax.set_yticks(range(len(ys)), [f"{v:.3g}" for v in ys])
    ax.set_xlabel(label(x_key))
    ax.set_ylabel(label(y_key))
    ax.figure.colorbar(mesh, ax=ax, label=label(field))
    return ax
