"""Results as tables: the column names of whirl's CSV files (one vocabulary for the command
line's files, read back by whirl.read_csv, and the package's results), each labelled with its
unit, "omega [rad/s]", "tip_r [m]", "tension [N]" in SI units, "omega [sqrt(g/L)]", "tip_r [L]",
"tension [M g]" in the dimensionless ones; a column without a dimension (mode, nodes, verdict,
index, ratios and counts) keeps its bare name. as_dict() of every result and of a Table gives
{label: 1-D array}; to_pandas() the same as a pandas DataFrame."""
from __future__ import annotations

from typing import Any, Dict, Mapping, Optional, Tuple

from ._lazy import numpy as np

# the kind of each column the command line writes, by its name (src/cli, src/studies)
_KINDS = {
    "rate": ("omega", "born_at", "from", "to", "freq_from", "freq_to", "at", "omega_err",
             "err_from", "err_to", "critical"),
    # a growth or decay rate, 1/s (a rate of the motion, not of the rotation)
    "growth": ("eig_growth", "sim_growth", "growth", "max_growth", "lyapunov", "re", "im"),
    "length": ("s", "r", "x", "y", "z", "tip_r", "max_r", "depth", "tip_x", "tip_y", "tip_z",
               "eps", "rms_residual", "change", "remaining", "shape_error", "dx", "dy", "dz",
               "dx_im", "dy_im", "dz_im", "constraint", "deviation", "arclength", "residual",
               "crossing_s", "tip_x_rot", "tip_y_rot", "tip_z_rot"),
    "force": ("tension", "top_tension"),
    "time": ("t", "t_end", "duration"),
    "energy": ("energy", "jacobi"),
    "momentum": ("lz",),
    "mass": ("tip_mass",),
    "angle": ("a", "b", "a_im", "b_im"),
}
KIND: Dict[str, str] = {name: kind for kind, names in _KINDS.items() for name in names}

# the unit of each kind: (SI, dimensionless)
UNIT = {"rate": ("rad/s", "sqrt(g/L)"), "growth": ("1/s", "sqrt(g/L)"), "length": ("m", "L"),
        "force": ("N", "M g"), "time": ("s", "sqrt(L/g)"), "energy": ("J", "M g L"),
        "momentum": ("kg m^2/s", "M L sqrt(g L)"), "mass": ("kg", "M"), "angle": ("rad", "rad")}


def _physical(units: Any) -> bool:
    if isinstance(units, Mapping):  # a SceneRun's units
        return bool(units.get("physical"))
    return bool(getattr(units, "physical", False))


def label(name: str, units: Any) -> str:
    """The column ``name`` with its unit in ``units`` (a whirl.Units, or a SceneRun's dict):
    "omega [rad/s]"; the bare name for a column without a dimension."""
    kind = KIND.get(name)
    if kind is None:
        return name
    return "%s [%s]" % (name, UNIT[kind][0 if _physical(units) else 1])


def labelled(columns: Mapping[str, Any], units: Any) -> Dict[str, np.ndarray]:
    """{label: 1-D array} of {name: values}: every value an array of one length (a number
    becomes an array of one); None becomes NaN."""
    out: Dict[str, np.ndarray] = {}
    for name, value in columns.items():
        a = np.atleast_1d(np.asarray(np.nan if value is None else value))
        if a.ndim != 1:
            raise ValueError("column %s is not one-dimensional: shape %s" % (name, a.shape))
        out[label(name, units)] = a
    sizes = {a.size for a in out.values()}
    if len(sizes) > 1:
        raise ValueError("the columns have different lengths %s" % sorted(sizes))
    return out


def data_frame(columns: Dict[str, np.ndarray], attrs: Optional[Dict[str, Any]] = None) -> Any:
    """A pandas DataFrame of labelled columns, ``attrs`` in its attrs."""
    try:
        import pandas
    except ImportError:
        raise ImportError("to_pandas needs pandas (Debian: python3-pandas; pip: pandas); "
                          "as_dict() gives the same columns as numpy arrays") from None
    frame = pandas.DataFrame(columns)
    frame.attrs.update(attrs or {})
    return frame


def split(fields: Mapping[str, Any]) -> Tuple[Dict[str, Any], Dict[str, Any]]:
    """A result's fields as (columns, summary): the 1-D arrays of the most common length
    above 1 are the table's columns, numbers, strings and booleans its summary (the rest,
    arrays of other shapes and objects, is left out). The rule for results that name no
    columns of their own."""
    arrays = {k: v for k, v in fields.items()
              if isinstance(v, np.ndarray) and v.ndim == 1 and v.dtype.kind in "biufcU"}
    lengths = [a.size for a in arrays.values() if a.size > 1]
    columns: Dict[str, Any] = {}
    if lengths:
        rows = max(set(lengths), key=lengths.count)
        columns = {k: a for k, a in arrays.items() if a.size == rows}
    summary = {k: v for k, v in fields.items() if k not in columns and k != "units"
               and isinstance(v, (bool, int, float, str, np.number, np.bool_))}
    if not columns:  # a result of one row: its numbers are the row
        columns, summary = summary, {}
    return columns, summary
