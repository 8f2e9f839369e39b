"""Telemetrix4RpiPico: host commands and Pico reports (LEN, id, payload)."""

from collections.abc import Mapping
from typing import Any, Literal, Optional, TypeVar, Union, final, overload

from ._robowire import Item, StreamDecoder, _Dict
from .omnitiles import FieldInfo

_Source = Literal["host", "pico", "any"]
_Dialect = Literal["mirte13", "mirte12", "upstream11"]

__all__ = ["Decoder", "encode", "field_info"]

_T_co = TypeVar("_T_co", covariant=True)

@final
class Decoder(StreamDecoder[_T_co]):
    """The Telemetrix stream decoder.

    ``source``: ``"pico"`` (reports only: what a host reads), ``"host"``
    (commands only) or ``"any"`` (both, attributing frames that read both
    ways as the tool does, with ``also``). ``dialect``: the firmware.
    ``lenient=True`` accepts report ids the dialect does not define as
    ``unknown_report`` when a valid report follows directly.
    """

    @overload
    def __new__(
        cls,
        source: _Source = "any",
        dialect: _Dialect = "mirte13",
        lenient: bool = False,
        errors: bool = False,
        lazy: Literal[False] = False,
        *,
        typed: Literal[False],
    ) -> Decoder[_Dict]: ...
    @overload
    def __new__(
        cls,
        source: _Source = "any",
        dialect: _Dialect = "mirte13",
        lenient: bool = False,
        errors: bool = False,
        lazy: bool = False,
        typed: Optional[Literal[True]] = None,
    ) -> Decoder[Item]: ...
    @overload
    def __new__(
        cls,
        source: _Source = "any",
        dialect: _Dialect = "mirte13",
        lenient: bool = False,
        errors: bool = False,
        lazy: bool = False,
        typed: Optional[bool] = None,
    ) -> Decoder[Union[Item, _Dict]]: ...

def encode(message: Mapping[str, Any], /, dialect: _Dialect = "mirte13") -> bytes:
    """The frame of one command or report (a dict in the JSON-lines schema) for ``dialect``.

    Raises ``ValueError`` naming the field and its range if it is invalid.
    """

def field_info(type: str, path: str, /) -> Optional[FieldInfo]:
    """What field ``path`` of message ``type`` means, from the library's field table."""
