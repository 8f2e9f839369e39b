"""OmniTiles: host commands and tile telemetry (``a5``, id, payload, sum)."""

from collections.abc import Iterable, Mapping
from typing import Any, Literal, Union

from typing_extensions import Self, TypeAlias, final

from ._robowire import StreamDecoder, _Bytes, _Decoded

_Source: TypeAlias = Literal["tile", "host", "any"]
_Layouts: TypeAlias = Union[str, Iterable[str], None]

__all__ = ["Decoder", "DatagramDecoder", "encode"]

@final
class Decoder(StreamDecoder):
    """The OmniTiles stream decoder.

    ``source``: ``"tile"`` (telemetry only), ``"host"`` (commands only) or
    ``"any"`` (both). ``layouts``: telemetry layouts to accept, a list or a
    comma-separated string of ``pos7``, ``uwb15``, ``uwbtof17``, ``ble53``,
    ``spi45``, ``auto`` (default: ``auto``, the four the SDK documents).
    """

    def __new__(
        cls,
        source: _Source = "any",
        layouts: _Layouts = None,
        errors: bool = False,
        lazy: bool = False,
    ) -> Self: ...

@final
class DatagramDecoder:
    """Decodes one whole datagram (a BLE notification or write, an SPI buffer) per call."""

    def __new__(
        cls,
        source: _Source = "any",
        layouts: _Layouts = None,
        errors: bool = False,
        lazy: bool = False,
    ) -> Self: ...
    def decode(self, datagram: _Bytes, /) -> list[_Decoded]:
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
