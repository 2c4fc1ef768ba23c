"""The record of one effect of an identified model: what the model file keeps of it.

``ReducedAxisModel.effects`` is a list of :class:`EffectRecord`. A record reads as the mapping it
is written as (``record["name"]``, ``dict(record)``; ARCHITECTURE.md, "Model file"), and has typed
attributes for its documented keys.
"""

from __future__ import annotations

import types
from collections.abc import Iterator, Mapping
from typing import Any

from vcnc.core.errors import InputError

__all__ = ["EffectRecord"]


class EffectRecord(Mapping[str, Any]):
    """One effect of a model (read-only).

    Parameters
    ----------
    data : mapping
        The record: ``name`` (an effect name, ARCHITECTURE.md "Effect names") and ``parameters``
        (the element's parameters), and after a diagnosis ``units``, ``rms_before_um``,
        ``rms_after_um``, ``validation_rms_before_um``, ``validation_rms_after_um``, ``summary``,
        ``description``, ``evidence``, ``unpinned`` and more; further keys are kept.

    Raises
    ------
    InputError
        No ``name`` string, or ``parameters`` that is not a mapping.
    """

    __slots__ = ("_data",)

    def __init__(self, data: Mapping[str, Any]) -> None:
        if isinstance(data, EffectRecord):
            data = data._data
        if not isinstance(data, Mapping) or not isinstance(data.get("name"), str):
            raise InputError("an effect record must be an object with a 'name' string and 'parameters'")
        if not isinstance(data.get("parameters", {}), Mapping):
            raise InputError(f"effect {data['name']!r}: 'parameters' must be an object")
        self._data = dict(data)

    def __getitem__(self, key: str) -> Any:
        return self._data[key]

    def __iter__(self) -> Iterator[str]:
        return iter(self._data)

    def __len__(self) -> int:
        return len(self._data)

    def __repr__(self) -> str:
        return f"EffectRecord({self._data!r})"

    @property
    def name(self) -> str:
        """The effect's name."""
        return self._data["name"]

    @property
    def parameters(self) -> Mapping[str, Any]:
        """The element's parameters (units in :attr:`units`)."""
        return types.MappingProxyType(dict(self._data.get("parameters") or {}))

    @property
    def units(self) -> Mapping[str, str]:
        """Unit of each parameter."""
        return types.MappingProxyType(dict(self._data.get("units") or {}))

    @property
    def rms_before_um(self) -> float | None:
        """RMS prediction error of the model before the effect was added [um] (identification data)."""
        return self._data.get("rms_before_um")

    @property
    def rms_after_um(self) -> float | None:
        """RMS prediction error with the effect [um] (identification data)."""
        return self._data.get("rms_after_um")

    @property
    def validation_rms_before_um(self) -> float | None:
        """Held-out RMS prediction error before the effect [um]."""
        return self._data.get("validation_rms_before_um")

    @property
    def validation_rms_after_um(self) -> float | None:
        """Held-out RMS prediction error with the effect [um]."""
        return self._data.get("validation_rms_after_um")

    @property
    def summary(self) -> str | None:
        """One line on what was found."""
        return self._data.get("summary")

    @property
    def evidence(self) -> Mapping[str, Any]:
        """What the diagnosis based the effect on."""
        return types.MappingProxyType(dict(self._data.get("evidence") or {}))

    @property
    def unpinned(self) -> Mapping[str, str]:
        """The parameters the record does not pin, each with why (``{}`` when it pins them all): the model
        simulates with their fitted values, which are not measurements (``Effect.unpinned``)."""
        return types.MappingProxyType(dict(self._data.get("unpinned") or {}))

    def to_dict(self) -> dict[str, Any]:
        """The record as a plain dict (as the model file writes it)."""
        return dict(self._data)
