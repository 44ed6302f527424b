"""Vantage: next-best-view planning in cluttered 3D scenes (Potthast & Sukhatme).

Python bindings of the C++ library. Poses are 4 x 4 rigid transforms T_world_sensor (sensor
frame: x forward, y left, z up), point clouds N x 3 arrays [m], grid arrays indexed [i, j, k].
Errors raise ValueError for bad arguments and malformed files, OSError for files that cannot be
read or written, MemoryError for a grid larger than the memory available (checked before it is
allocated), TypeError for an argument of the wrong type (one line naming the argument) and
RuntimeError otherwise, with the library's one-line messages.
"""

import functools as _functools
import numbers as _numbers
import os as _os
import re as _re

from . import _vantage
from ._vantage import *  # noqa: F401,F403
from .env import ActionSpace, ExploreEnv, bench_policy, random_policy  # noqa: F401

# NOTE: a call that matches no signature makes pybind11 raise a TypeError of 3-9 lines (every
# signature, then the arguments' reprs). Every function and method of the module is wrapped so that
# such a call raises one line instead, naming the first argument whose type does not fit (issue
# 39); what the library itself raises passes through unchanged.
_INCOMPATIBLE = ("incompatible function arguments", "incompatible constructor arguments")
_SIGNATURE = _re.compile(r"^\s*\d+\.\s*[\w.]*\((.*)\)(?:\s*->.*)?$", _re.MULTILINE)


def _parameters(text):
    """[(name, type)] of a pybind11 signature's parameter list 'a: float, b: int = 1'."""
    params, depth, current = [], 0, ""
    for char in text + ",":
        if char in "[(":
            depth += 1
        elif char in "])":
            depth -= 1
        if char == "," and depth == 0:
            name, _, kind = current.strip().partition(":")
            params.append((name.strip(), kind.split("=")[0].strip()))
            current = ""
        else:
            current += char
    return [(n, k) for n, k in params if n and n != "self" and not n.startswith("*")]


def _fits(value, kind):
    """Whether `value` can be what pybind11 calls `kind`; True when the kind is not known here."""
    optional = _re.fullmatch(r"Optional\[(.*)\]", kind)
    if optional:
        return value is None or _fits(value, optional.group(1))
    if kind == "float":
        return isinstance(value, _numbers.Real) and not isinstance(value, bool)
    if kind == "int":
        return isinstance(value, _numbers.Integral) and not isinstance(value, bool)
    if kind == "bool":
        return isinstance(value, bool)
    if kind == "str":
        return isinstance(value, str)
    if "PathLike" in kind or kind == "os.PathLike":
        return isinstance(value, (str, _os.PathLike))
    if kind.startswith("numpy.ndarray") or kind.startswith("list[") or kind.startswith(
            "tuple[") or kind.startswith("Sequence") or kind.startswith("Annotated"):
        return not isinstance(value, (str, bytes, dict)) and (
            hasattr(value, "__len__") or hasattr(value, "__array__"))
    match = _re.fullmatch(r"(?:vantage\.)?_vantage\.(\w+)", kind) or _re.fullmatch(
        r"vantage\._vantage\.(\w+)", kind)
    if match and hasattr(_vantage, match.group(1)):
        return isinstance(value, getattr(_vantage, match.group(1)))
    return True


def _one_line(name, doc, args, kwargs):
    """The one-line TypeError for a call of `name` that matched none of the signatures in `doc`."""
    signatures = [_parameters(m.group(1)) for m in _SIGNATURE.finditer(doc or "")]
    for params in signatures[:1]:
        for k, (param, kind) in enumerate(params):
            if k < len(args):
                value = args[k]
            elif param in kwargs:
                value = kwargs[param]
            else:
                continue
            if not _fits(value, kind):
                shown = kind.replace("vantage._vantage.", "vantage.")
                return f"{name}(): argument '{param}' must be {shown}, got {type(value).__name__}"
        unknown = [key for key in kwargs if key not in {p for p, _ in params}]
        if unknown:
            return f"{name}(): no argument named '{unknown[0]}'"
    shown = ", ".join(f"{p}: {k}".replace("vantage._vantage.", "vantage.")
                      for p, k in (signatures[0] if signatures else []))
    given = ", ".join([type(a).__name__ for a in args] +
                      [f"{k}={type(v).__name__}" for k, v in kwargs.items()])
    return f"{name}() takes ({shown}), got ({given})"


def _wrap(function, name, doc_of):
    @_functools.wraps(function)
    def call(*args, **kwargs):
        try:
            return function(*args, **kwargs)
        except TypeError as error:
            message = str(error)
            if not any(text in message.split("\n", 1)[0] for text in _INCOMPATIBLE):
                raise
            shown_args = args[1:] if doc_of is not None else args
            raise TypeError(_one_line(name, message, shown_args, kwargs)) from None

    return call


def _wrap_module():
    for attribute in dir(_vantage):
        if attribute.startswith("_"):
            continue
        value = getattr(_vantage, attribute)
        if isinstance(value, type):
            for method in list(vars(value)):
                if method.startswith("__") and method != "__init__":
                    continue
                member = vars(value)[method]
                if type(member).__name__ != "instancemethod":
                    continue
                label = attribute if method == "__init__" else f"{attribute}.{method}"
                setattr(value, method, _wrap(member, label, value))
        elif type(value).__name__ == "builtin_function_or_method":
            globals()[attribute] = _wrap(value, attribute, None)


_wrap_module()
