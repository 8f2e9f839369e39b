"""Telemetrix4RpiPico: host commands and Pico reports (LEN, id, payload)."""

from collections.abc import Mapping
from typing import Any, Literal

from ._robowire import Bytes, Decoded, StreamDecoder

Source = Literal["host", "pico", "any"]
Dialect = Literal["mirte13", "mirte12", "upstream11"]

__all__ = ["Decoder", "encode"]

class Decoder(StreamDecoder):
    """The Telemetrix stream decoder.

    ``source``: ``"pico"`` (reports only: what a host reads), ``"host"``
    (commands only) or ``"any"`` (both, attributing frames that read both
    ways as the tool does, with ``also``). ``dialect``: the firmware.
    ``lenient=True`` accepts report ids the dialect does not define as
    ``unknown_report`` when a valid report follows directly.
    """

    def __init__(
        self,
        source: Source = "any",
        dialect: Dialect = "mirte13",
        lenient: bool = False,
        errors: bool = False,
        lazy: bool = False,
    ) -> None: ...

def encode(message: Mapping[str, Any], /, dialect: Dialect = "mirte13") -> bytes:
    """The frame of one command or report (a dict in the JSON-lines schema) for ``dialect``.

    Raises ``ValueError`` naming the field and its range if it is invalid.
    """
