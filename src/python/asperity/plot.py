"""Figures of runs and sweep stores with matplotlib (imported when a function draws, so that
`import asperity` needs no matplotlib). Every function draws into `ax` (a new figure's axes when
None) and returns the Axes; axis labels name the quantity and its SI unit from the engine's tables
(asperity.units)::

    run = asperity.run(scene)
    asperity.plot.area_vs_force(run, measured=asperity.measured(scene))   # A(Q)
    asperity.plot.force_vs_time(run)                                      # Q(t)
    asperity.plot.heatmap("results/x", "model.eta", "model.epsilon", "Q_s")

The figures share the command line's conventions: units as the engine's figures show them
(asperity.plot.unit: areas in mm², the rest SI; the same unit text as gnuplot's figures), the
journal sizes of its SVG and PDF figures (one column 8.6 cm wide, 8.5 pt text: `figure`), and
the stand-in mark (`mark_stand_in`, asperity.STAND_IN_MARK) on every figure drawn from stand-in
data, which the data say: a Result of a stand-in scene, a store whose provenance says
stand_in_data: true.
"""
import re as _re

__all__ = ["area_vs_force", "force_vs_time", "heatmap", "label", "unit", "figure", "mark_stand_in"]

COLUMN_WIDTH_IN = 8.6 / 2.54  # one journal column, as the gnuplot figures' SVG and PDF
FONT_PT = 8.5                 # their text size
_MARK_COLOUR = "#b2182b"      # the gnuplot figures' stand-in mark colour

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


def _mathtext_unit(markup: str) -> str:
    """The engine's figure markup of a unit (gnuplot enhanced text) in matplotlib's mathtext:
    "m^{2p+2} N^{-2}" → "m$^{2p+2}$ N$^{-2}$", "mm^2" → "mm$^{2}$", "s^{-1}" → "s$^{-1}$"."""
    return _re.sub(r"\^(?:\{([^}]*)\}|(.))", lambda m: "$^{" + (m.group(1) or m.group(2)) + "}$", markup)


def unit(column: str):
    """(unit text, scale) of a column as the figures show it, from the engine's table: areas (A,
    A0, A_s) in mm² (scale 1e6 from m²), the rest SI (scale 1); ("", 1) for a column without a
    unit (names, flags). Multiply the SI values by scale; the text is mathtext, as `label` writes it."""
    from . import _asperity
    u = _asperity.figure_unit(column)
    return _mathtext_unit(u["markup"]), u["scale"]


def label(column: str) -> str:
    """An axis label: the quantity's name and its unit as the figures show it (`unit`; "[1]"
    when dimensionless, as the command line's figures), e.g. "tangential force $Q$ [N]",
    "real contact area $A$ [mm$^{2}$]"."""
    text, _ = unit(column)
    name = _NAMES.get(column, column)
    return name if text == "" else f"{name} [{text}]"


def figure(ncols: int = 1, height: float = 0.7, **kwargs):
    """A new (figure, axes) in the journal style of the command line's SVG and PDF figures: one
    column (8.6 cm) wide, or two (17.8 cm) when `ncols` > 1, `height` times the width, 8.5 pt text."""
    import matplotlib.pyplot as plt  # only when drawing
    import numpy as np
    width = COLUMN_WIDTH_IN if ncols == 1 else 17.8 / 2.54
    fig, axes = plt.subplots(1, ncols, figsize=(width, width * height), layout="constrained", **kwargs)
    # Sizes set on the axes themselves: rcParams would reach only the artists made under them.
    for ax in np.atleast_1d(axes):
        ax.tick_params(labelsize=FONT_PT - 1)
        for text in (ax.title, ax.xaxis.label, ax.yaxis.label):
            text.set_fontsize(FONT_PT)
    return fig, axes


def mark_stand_in(fig, stand_in: bool = True):
    """Writes asperity.STAND_IN_MARK in the lower right corner of `fig` (a Figure, or an Axes'
    figure) when `stand_in`, once per figure, as the command line's figures. Returns the Text or None."""
    if not stand_in:
        return None
    fig = getattr(fig, "figure", fig)
    from . import _asperity
    for t in fig.texts:
        if t.get_gid() == "stand-in-mark":
            return t
    engine = fig.get_layout_engine() if hasattr(fig, "get_layout_engine") else None
    if engine is not None and hasattr(engine, "set") and "rect" in engine.get():
        engine.set(rect=(0, 0.045, 1, 0.955))  # a strip below the axes for the mark
    return fig.text(0.995, 0.005, _asperity.STAND_IN_MARK, ha="right", va="bottom", color=_MARK_COLOUR,
                    fontsize=FONT_PT - 1.5, gid="stand-in-mark")


def _stand_in_of(data) -> bool:
    """Whether `data` says it comes from stand-ins: a Result's or DataFrame's stand_in, a store
    DataFrame's provenance (stand_in_data: true)."""
    if getattr(data, "stand_in", None) is not None and not hasattr(data, "columns"):
        return bool(data.stand_in)
    attrs = getattr(data, "attrs", {}) or {}
    if "stand_in" in attrs:
        return bool(attrs["stand_in"])
    provenance = attrs.get("provenance")
    if isinstance(provenance, dict):
        return provenance.get("stand_in_data") is True
    return isinstance(provenance, str) and _re.search(r"^stand_in_data:\s*true", provenance, _re.M) is not None


def _axes(ax):
    return ax if ax is not None else figure()[1]


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


def _scaled(values, column):
    """`values` (SI) in the column's figure unit."""
    import numpy as np
    return np.asarray(values, dtype=float) * unit(column)[1]


def area_vs_force(result, measured=None, ax=None, stand_in=None):
    """A(Q): the run's contact area (mm²) against its tangential force (a line), the peak (Q_s,
    A_s) marked when the result has a summary, and the measured curve (points) when given
    (asperity.measured(scene), or a DataFrame with Q_N, A_m2). The stand-in mark when `stand_in`
    (None: as the result says: Result.stand_in, a frame's attrs["stand_in"]). Returns the Axes."""
    ax = _axes(ax)
    s = _series(result)
    ax.plot(_scaled(s["Q"], "Q"), _scaled(s["A"], "A"), "-", lw=1.2, label="model")
    summary = getattr(result, "summary", None)
    if summary and summary.get("peak_found"):
        ax.plot(_scaled([summary["Q_s"]], "Q_s"), _scaled([summary["A_s"]], "A_s"), "o", ms=4, color="C0",
                label="peak $(Q_s, A_s)$")
    if measured is not None:
        q, a = _measured_columns(measured)
        ax.plot(_scaled(q, "Q"), _scaled(a, "A"), ".", ms=3, color="C1", label="measured")
    ax.set_xlabel(label("Q"))
    ax.set_ylabel(label("A"))
    ax.legend(loc="best", frameon=False, fontsize=FONT_PT - 1)
    mark_stand_in(ax, _stand_in_of(result) if stand_in is None else stand_in)
    return ax


def force_vs_time(result, ax=None, stand_in=None):
    """Q(t): the run's tangential force against time; the stand-in mark as area_vs_force. Returns
    the Axes."""
    ax = _axes(ax)
    s = _series(result)
    ax.plot(_scaled(s["t"], "t"), _scaled(s["Q"], "Q"), "-", lw=1.2)
    ax.set_xlabel(label("t"))
    ax.set_ylabel(label("Q"))
    mark_stand_in(ax, _stand_in_of(result) if stand_in is None else stand_in)
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


def heatmap(store, x_key, y_key, field, ax=None, where=None, stand_in=None):
    """`field` (an observable of the store's points.csv, e.g. "Q_s") over the grid of two swept
    keys, one cell per (x, y) point, a colour bar labelled with the field's quantity and unit;
    failed points are blank. `store`: a store folder or asperity.read_store's DataFrame. When the
    store varies other keys too, `where` picks one slice, as the command line's --where: a dict
    {"model.eta": 100} or strings ["model.eta=100"]. The stand-in mark when `stand_in` (None: as
    the store's provenance says). Returns the Axes."""
    import numpy as np
    if not hasattr(store, "columns"):
        from . import read_store
        store = read_store(store)
    if stand_in is None:
        stand_in = _stand_in_of(store)
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
    values = np.ma.masked_invalid(grid.to_numpy(dtype=float) * unit(field)[1])
    mesh = ax.pcolormesh(np.arange(len(xs) + 1) - 0.5, np.arange(len(ys) + 1) - 0.5, values, shading="flat")
    ax.set_xticks(range(len(xs)), [f"{v * unit(x_key)[1]:.3g}" for v in xs])
    ax.set_yticks(range(len(ys)), [f"{v * unit(y_key)[1]:.3g}" for v in ys])
    ax.set_xlabel(label(x_key))
    ax.set_ylabel(label(y_key))
    bar = ax.figure.colorbar(mesh, ax=ax)
    bar.set_label(label(field), fontsize=FONT_PT)
    bar.ax.tick_params(labelsize=FONT_PT - 1)
    mark_stand_in(ax, stand_in)
    return ax
