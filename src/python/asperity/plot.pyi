# Type stubs of asperity.plot (matplotlib figures; tests/python/test_plot.py).
import os
from typing import Any, Mapping, Optional, Sequence, Union

__all__: list[str]

COLUMN_WIDTH_IN: float
FONT_PT: float

def label(column: str) -> str: ...
def unit(column: str) -> tuple[str, float]: ...
def figure(ncols: int = 1, height: float = 0.7, **kwargs: Any) -> tuple[Any, Any]: ...  # Figure, Axes
def mark_stand_in(fig: Any, stand_in: bool = True) -> Any: ...
def area_vs_force(result: Any, measured: Any = None, ax: Any = None,
                  stand_in: Optional[bool] = None) -> Any: ...  # matplotlib Axes
def force_vs_time(result: Any, ax: Any = None, stand_in: Optional[bool] = None) -> Any: ...
def heatmap(store: Union[str, os.PathLike[str], Any], x_key: str, y_key: str, field: str, ax: Any = None,
            where: Union[Mapping[str, Any], Sequence[str], None] = None, stand_in: Optional[bool] = None) -> Any: ...
