"""Summaries of a sweep table: percentiles over the realisations of a Monte Carlo sweep."""

from __future__ import annotations

from typing import TYPE_CHECKING

from ..columns import SEED_COLUMNS, label
from ..force_statistics import seed_percentiles

if TYPE_CHECKING:  # pandas is imported when a table is built: keeps `import trackwheel` light
    import pandas as pd

SPEED, STIFFNESS, SEED, ERROR = (label(n) for n in ("speed", "support_stiffness", "seed",
                                                     "error"))


def summarise_seeds(df: pd.DataFrame, columns=SEED_COLUMNS, *, by=SPEED,
                    q=(5.0, 50.0, 95.0)) -> pd.DataFrame:
    """Percentiles over the realisations of a :func:`sweep` with ``seeds``: for each speed (or
    each value of ``by``, a column or a list of columns; default ``speed_m_s``), the ``q``
    percentiles [%] of ``columns`` (default :data:`~trackwheel.study.columns.SEED_COLUMNS`:
    max and min contact force [N], dynamic factor [-], contact-loss duration [s], force RMS
    [N]) over the rows, failed rows left out.

    Returns a DataFrame indexed by ``by`` with columns (column, "p<q>") and ``n_seeds`` (the
    rows that ran). Raises ValueError if a group mixes several support stiffnesses (pass
    ``by=["speed_m_s", "support_stiffness_N_m"]``) or the table has no ``seed`` values.
    """
    import pandas as pd

    if not isinstance(df, pd.DataFrame):
        raise TypeError(f"df must be a pandas DataFrame, got {type(df).__name__}")
    keys = [by] if isinstance(by, str) else list(by)
    if SEED not in df.columns or df[SEED].isna().all():
        raise ValueError("df has no seed values: summarise the table of sweep(..., seeds=[...])")
    if STIFFNESS in df.columns and STIFFNESS not in keys:
        mixed = df.groupby(keys)[STIFFNESS].nunique()
        if (mixed > 1).any():
            raise ValueError(f"the rows of one {'/'.join(keys)} hold several support "
                             f"stiffnesses; pass by=[..., {STIFFNESS!r}] or filter the table")
    # a table read back from CSV has NaN, not "", where no error was written
    ok = df[df[ERROR].isna() | (df[ERROR] == "")] if ERROR in df.columns else df
    out = seed_percentiles(ok, columns, by=by, q=q)
    out[("n_seeds", "")] = ok.groupby(by if isinstance(by, str) else keys).size()
    return out
