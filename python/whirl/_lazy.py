"""numpy for whirl's modules, imported at its first use rather than at ``import whirl``.

numpy's import costs about a tenth of a second, most of ``import whirl``; a script that only
asks for the version, or the command line's helper whirl.explore, need not pay it. Every whirl
module takes ``from ._lazy import numpy as np`` (with ``from __future__ import annotations``, so
that the annotations naming np.ndarray are not evaluated): the first attribute asked of ``np``
imports numpy, and each attribute is then kept on the proxy itself, where the next look-up finds
it as a plain attribute (no call through __getattr__ on the hot paths). Type checkers see numpy
itself."""
import importlib
from typing import TYPE_CHECKING, Any


class LazyModule:
    """The module ``name``, imported when an attribute is first asked of it."""

    def __init__(self, name: str) -> None:
        self.__dict__["_LazyModule__name"] = name

    def __getattr__(self, attr: str) -> Any:
        # called only for an attribute not yet kept: import (once; later, a dictionary look-up
        # in sys.modules), then keep the attribute on the proxy
        value = getattr(importlib.import_module(self.__name), attr)
        self.__dict__[attr] = value
        return value

    def __repr__(self) -> str:
        return "<lazy module %r>" % self.__name


if TYPE_CHECKING:
    import numpy as numpy
else:
    numpy = LazyModule("numpy")
