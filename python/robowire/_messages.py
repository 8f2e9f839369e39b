"""The message classes of a protocol module made in Rust (Telemetrix, Pixy2)."""

from __future__ import annotations

from types import ModuleType
from typing import Any, Union


def classes(native: ModuleType) -> dict[str, type]:
    """The class of every message ``type`` in ``native`` (``analog_report``:
    ``AnalogReport``), in the library's order of the types."""
    base = native.Message
    return {
        name: value
        for name, value in vars(native).items()
        if isinstance(value, type) and issubclass(value, base) and value is not base
    }


def union(found: dict[str, type]) -> Any:
    """``Union`` of the classes, as the stubs' ``AnyMessage``."""
    return Union[tuple(found.values())]
