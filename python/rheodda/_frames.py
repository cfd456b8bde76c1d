"""rheodda's tables as pandas DataFrames (docs/guide/python.md)."""

import numpy as _np


def to_dataframe(columns):
    """A pandas DataFrame of a dict of equally long arrays (a history, a curve,
    contacts). Raises ImportError naming the Debian package when pandas is missing."""
    try:
        import pandas
    except ImportError as e:  # pragma: no cover - pandas is installed by scripts/install-deps.sh
        raise ImportError("to_dataframe needs pandas (apt-get install python3-pandas)") from e
    return pandas.DataFrame({k: _np.asarray(v) for k, v in columns.items()})
