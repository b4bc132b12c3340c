# Type stubs of asperity.plot (matplotlib figures; tests/python/test_plot.py).
import os
from typing import Any, Mapping, Optional, Sequence, Union

__all__: list[str]

def label(column: str) -> str: ...
def area_vs_force(result: Any, measured: Any = None, ax: Any = None) -> Any: ...  # matplotlib Axes
def force_vs_time(result: Any, ax: Any = None) -> Any: ...
def heatmap(store: Union[str, os.PathLike[str], Any], x_key: str, y_key: str, field: str, ax: Any = None,
            where: Union[Mapping[str, Any], Sequence[str], None] = None) -> Any: ...
