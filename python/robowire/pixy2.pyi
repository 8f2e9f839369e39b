"""Pixy2: host requests and device responses (``ae c1`` / ``af c1`` frames)."""

from collections.abc import Mapping
from typing import Any, Literal, Optional, TypeVar, Union, final, overload

from ._robowire import Item, StreamDecoder, _Dict
from .omnitiles import FieldInfo

_Source = Literal["host", "device", "any"]

__all__ = ["Decoder", "encode", "field_info"]

_T_co = TypeVar("_T_co", covariant=True)

@final
class Decoder(StreamDecoder[_T_co]):
    """The Pixy2 stream decoder.

    ``source``: ``"device"`` (responses only: what a host reads), ``"host"``
    (requests only, held to the device's 64-byte receive limit) or ``"any"``.
    ``checksum_only=True`` accepts only the checksum form (``af c1``), as a
    Pixy2 always answers.
    """

    @overload
    def __new__(
        cls,
        source: _Source = "any",
        checksum_only: bool = False,
        errors: bool = False,
        lazy: Literal[False] = False,
        *,
        typed: Literal[False],
    ) -> Decoder[_Dict]: ...
    @overload
    def __new__(
        cls,
        source: _Source = "any",
        checksum_only: bool = False,
        errors: bool = False,
        lazy: bool = False,
        typed: Optional[Literal[True]] = None,
    ) -> Decoder[Item]: ...
    @overload
    def __new__(
        cls,
        source: _Source = "any",
        checksum_only: bool = False,
        errors: bool = False,
        lazy: bool = False,
        typed: Optional[bool] = None,
    ) -> Decoder[Union[Item, _Dict]]: ...

def encode(message: Mapping[str, Any], /) -> bytes:
    """The frame of one request or response (a dict in the JSON-lines schema).

    ``checksum`` (``True`` for ``af c1``) picks the frame form. Raises
    ``ValueError`` naming the field and its range if it is invalid.
    """

def field_info(type: str, path: str, /) -> Optional[FieldInfo]:
    """What field ``path`` of message ``type`` means, from the library's field table."""
