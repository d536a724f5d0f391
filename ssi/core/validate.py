"""The one validation layer of the public API: type, finiteness and range checks of user input.

Every check raises ``TypeError`` for a value of the wrong type (a string, ``None``, a complex number or a list
where a real number belongs) and ``ValueError`` for a value of the right type outside its allowed set (NaN,
infinity, out of range, an unknown option), and its message names the parameter, the value given and what is
allowed, e.g. ``h_fine must be a finite number in (0, inf), got nan``. The checks return the value
converted (``float``, ``int``, a float64 array), so a caller writes ``x = check_real("x", x)`` once.

Plain Python, called only at the public boundary (scene dataclasses, ``Section``, ``Settings``, mesh and
footing builders, analytical references); the numba kernels stay free of checks.
"""

import math
import numbers

import numpy as np

__all__ = [
    "check_array",
    "check_bool",
    "check_choice",
    "check_instance",
    "check_int",
    "check_optional_real",
    "check_real",
]


def _interval(lo, hi, lo_open, hi_open) -> str:
    left = "(" if lo_open or lo is None else "["
    right = ")" if hi_open or hi is None else "]"
    return f"{left}{'-inf' if lo is None else f'{lo:g}'}, {'inf' if hi is None else f'{hi:g}'}{right}"


def _is_real_number(value) -> bool:
    """A real scalar: Python or numpy int/float, never bool (True is not a modulus) nor complex."""
    if isinstance(value, bool | np.bool_):
        return False
    return isinstance(value, numbers.Real)


def _in_range(v, lo, hi, lo_open, hi_open) -> bool:
    if lo is not None and (v < lo or (lo_open and v == lo)):
        return False
    return not (hi is not None and (v > hi or (hi_open and v == hi)))


def check_real(
    name: str,
    value,
    lo: float | None = None,
    hi: float | None = None,
    lo_open: bool = False,
    hi_open: bool = False,
    allow_inf: bool = False,
    unit: str = "",
) -> float:
    """``value`` as a float, checked to be a real number in the interval [lo, hi] (ends open on request).

    NaN is never allowed; +-inf only with ``allow_inf`` (and then still subject to the bounds). ``unit`` is
    added to the message ("Pa", "m", "degrees").
    """
    if not _is_real_number(value):
        raise TypeError(f"{name} must be a real number{_unit(unit)}, got {value!r} ({type(value).__name__})")
    v = float(value)
    finite = "" if allow_inf else "finite "
    if math.isnan(v) or (math.isinf(v) and not allow_inf) or not _in_range(v, lo, hi, lo_open, hi_open):
        raise ValueError(
            f"{name} must be a {finite}number in {_interval(lo, hi, lo_open, hi_open)}"
            f"{_unit(unit)}, got {value!r}"
        )
    return v


def check_optional_real(name: str, value, **bounds) -> float | None:
    """``None`` passes through (the parameter's "not given"); anything else as :func:`check_real`."""
    return None if value is None else check_real(name, value, **bounds)


def check_int(name: str, value, lo: int | None = None, hi: int | None = None) -> int:
    """``value`` as an int, checked to be an integer (Python or numpy, not bool, not 2.7) in [lo, hi]."""
    if isinstance(value, bool | np.bool_) or not isinstance(value, numbers.Integral):
        raise TypeError(f"{name} must be an integer, got {value!r} ({type(value).__name__})")
    v = int(value)
    if not _in_range(v, lo, hi, False, False):
        raise ValueError(f"{name} must be an integer in {_interval(lo, hi, False, False)}, got {value!r}")
    return v


def check_bool(name: str, value) -> bool:
    """``value`` as a bool: True/False (or numpy bools) only; 0, 1, "yes" and None are refused."""
    if not isinstance(value, bool | np.bool_):
        raise TypeError(f"{name} must be True or False, got {value!r} ({type(value).__name__})")
    return bool(value)


def check_choice(name: str, value, choices):
    """``value`` must be one of ``choices`` (compared with ==, of the same type family as the choices)."""
    choices = tuple(choices)
    kinds = {type(c) for c in choices}
    if not any(isinstance(value, k) for k in kinds) or isinstance(value, bool) and bool not in kinds:
        raise TypeError(f"{name} must be one of {choices}, got {value!r} ({type(value).__name__})")
    if value not in choices:
        raise ValueError(f"{name} must be one of {choices}, got {value!r}")
    return value


def check_instance(name: str, value, cls, optional: bool = False):
    """``value`` must be an instance of ``cls`` (or ``None`` if ``optional``)."""
    if value is None and optional:
        return None
    if not isinstance(value, cls):
        names = cls.__name__ if isinstance(cls, type) else " or ".join(c.__name__ for c in cls)
        raise TypeError(
            f"{name} must be a {names}{' or None' if optional else ''}, got {value!r} "
            f"({type(value).__name__})"
        )
    return value


def check_array(
    name: str,
    value,
    shape: tuple | None = None,
    ndim: int | None = None,
    lo: float | None = None,
    hi: float | None = None,
    lo_open: bool = False,
    hi_open: bool = False,
    min_size: int = 0,
    allow_inf: bool = False,
    dtype=np.float64,
) -> np.ndarray:
    """``value`` as a C-contiguous array of ``dtype`` (float64 or int64), every entry checked like
    :func:`check_real`. ``shape`` entries of ``None`` match any length."""
    arr = _as_numeric_array(name, value, dtype)
    if ndim is not None and arr.ndim != ndim:
        raise ValueError(f"{name} must be a {ndim}-D array, got shape {arr.shape}")
    if shape is not None and (
        arr.ndim != len(shape) or any(s is not None and s != n for s, n in zip(shape, arr.shape))
    ):
        want = (
            "("
            + ", ".join("n" if s is None else str(s) for s in shape)
            + ("," if len(shape) == 1 else "")
            + ")"
        )
        raise ValueError(f"{name} must have shape {want}, got {arr.shape}")
    if arr.size < min_size:
        raise ValueError(f"{name} must have at least {min_size} entries, got {arr.size}")
    bad = np.isnan(arr) if arr.dtype.kind == "f" else np.zeros(arr.shape, bool)
    if arr.dtype.kind == "f" and not allow_inf:
        bad |= np.isinf(arr)
    if lo is not None:
        bad |= (arr < lo) | ((arr == lo) if lo_open else False)
    if hi is not None:
        bad |= (arr > hi) | ((arr == hi) if hi_open else False)
    if np.any(bad):
        i = tuple(int(k) for k in np.argwhere(np.atleast_1d(bad))[0])
        if arr.ndim == 0:
            raise ValueError(
                f"{name} must be a {'' if allow_inf else 'finite '}number in "
                f"{_interval(lo, hi, lo_open, hi_open)}, got {arr.item()!r}"
            )
        finite = "" if allow_inf or arr.dtype.kind != "f" else "finite "
        raise ValueError(
            f"{name} must hold {finite}numbers in {_interval(lo, hi, lo_open, hi_open)}, got "
            f"{arr[i].item()!r} at index {i if len(i) > 1 else i[0]}"
        )
    return arr if arr.flags.c_contiguous else arr.copy(order="C")  # (np.ascontiguousarray makes 0-d 1-d)


def _as_numeric_array(name, value, dtype):
    if isinstance(value, str | bytes) or value is None:
        raise TypeError(f"{name} must be an array of numbers, got {value!r} ({type(value).__name__})")
    try:
        raw = np.asarray(value)
    except ValueError as err:  # ragged nested lists
        raise ValueError(f"{name} must be a rectangular array of numbers, got {value!r}") from err
    if raw.dtype.kind not in "iuf" or (raw.dtype.kind == "b"):
        if raw.dtype.kind == "O":
            raise TypeError(f"{name} must be an array of real numbers, got {value!r}")
        raise TypeError(f"{name} must be an array of real numbers, got dtype {raw.dtype} ({value!r})")
    if np.dtype(dtype).kind == "i":
        if raw.dtype.kind == "f" and (np.any(~np.isfinite(raw)) or np.any(raw != np.round(raw))):
            raise ValueError(f"{name} must hold integers, got {value!r}")
        return raw.astype(np.int64)
    return raw.astype(np.float64)


def _unit(unit: str) -> str:
    return f" [{unit}]" if unit else ""
