"""OmniTiles: host commands and tile telemetry (``a5``, id, payload, sum)."""

from collections.abc import Iterable, Mapping
from typing import Any, Literal, Optional, Union

from ._robowire import Bytes, Decoded, StreamDecoder

Source = Literal["tile", "host", "any"]
Layouts = Union[str, Iterable[str], None]

__all__ = ["Decoder", "DatagramDecoder", "encode"]

class Decoder(StreamDecoder):
    """The OmniTiles stream decoder.

    ``source``: ``"tile"`` (telemetry only), ``"host"`` (commands only) or
    ``"any"`` (both). ``layouts``: telemetry layouts to accept, a list or a
    comma-separated string of ``pos7``, ``uwb15``, ``uwbtof17``, ``ble53``,
    ``spi45``, ``auto`` (default: ``auto``, the four the SDK documents).
    """

    def __init__(
        self,
        source: Source = "any",
        layouts: Layouts = None,
        errors: bool = False,
        lazy: bool = False,
    ) -> None: ...

class DatagramDecoder:
    """Decodes one whole datagram (a BLE notification or write, an SPI buffer) per call."""

    def __init__(
        self,
        source: Source = "any",
        layouts: Layouts = None,
        errors: bool = False,
        lazy: bool = False,
    ) -> None: ...
    def decode(self, datagram: Bytes, /) -> list[Decoded]:
        """The items of one datagram, in order."""
    @property
    def stats(self) -> dict[str, int]: ...
    @property
    def errors(self) -> bool: ...
    @property
    def lazy(self) -> bool: ...

def encode(message: Mapping[str, Any], /) -> bytes:
    """The frame of one message (a dict in the JSON-lines schema).

    Raises ``ValueError`` naming the field and its range if it is invalid.
    """
