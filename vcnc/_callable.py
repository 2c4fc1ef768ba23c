"""Modules that can be called like the facade function of the same name.

``vcnc.machine("fadal-pid")`` and ``vcnc.sweep(...)`` are facade functions, but ``vcnc.machine``
and ``vcnc.sweep`` are also modules. Once a submodule is imported, Python binds its name on the
parent package to the module, hiding the function. Making the module itself callable keeps
``vcnc.machine(...)`` working whichever was imported first.
"""

from __future__ import annotations

import sys
import types
from collections.abc import Callable
from typing import Any

__all__ = ["make_callable"]


def make_callable(module_name: str, func: Callable[..., Any]) -> None:
    """Make ``sys.modules[module_name]`` callable: calling it calls ``func``."""
    module = sys.modules[module_name]
    cls = type(
        "CallableModule",
        (types.ModuleType,),
        {"__call__": staticmethod(func), "__doc__": f"Module that calls {func.__qualname__} when called."},
    )
    module.__class__ = cls
