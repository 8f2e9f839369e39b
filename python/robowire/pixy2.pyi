"""Pixy2: host requests and device responses (``ae c1`` / ``af c1`` frames)."""

import sys
from collections.abc import Callable, Mapping
from typing import Any, Literal, Optional, TypeVar, Union, final, overload

from ._robowire import Item, StreamDecoder, _Dict, _Fields
from .omnitiles import FieldInfo

if sys.version_info >= (3, 13):
    from warnings import deprecated
else:
    from typing_extensions import deprecated

_Source = Literal["host", "device", "any"]

__all__ = ["AnyMessage", "Decoder", "Message", "encode", "field_info"]  # and every message class

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
        clock: Optional[Callable[[], float]] = None,
    ) -> Decoder[_Dict]: ...
    @overload
    def __new__(
        cls,
        source: _Source = "any",
        checksum_only: bool = False,
        errors: Literal[False] = False,
        lazy: Literal[False] = False,
        typed: None = None,
        clock: Optional[Callable[[], float]] = None,
    ) -> Decoder[AnyMessage]: ...
    @overload
    def __new__(
        cls,
        source: _Source = "any",
        checksum_only: bool = False,
        errors: bool = False,
        lazy: Literal[False] = False,
        typed: None = None,
        clock: Optional[Callable[[], float]] = None,
    ) -> Decoder[Union[AnyMessage, Item]]: ...
    @overload
    @deprecated("typed=True is the default: drop it")
    def __new__(
        cls,
        source: _Source = "any",
        checksum_only: bool = False,
        errors: bool = False,
        lazy: Literal[False] = False,
        *,
        typed: Literal[True],
        clock: Optional[Callable[[], float]] = None,
    ) -> Decoder[Union[AnyMessage, Item]]: ...
    @overload
    @deprecated("lazy=True is deprecated: the default typed items read a field without a dict")
    def __new__(
        cls,
        source: _Source = "any",
        checksum_only: bool = False,
        errors: bool = False,
        *,
        lazy: Literal[True],
        typed: Optional[Literal[False]] = None,
        clock: Optional[Callable[[], float]] = None,
    ) -> Decoder[Item]: ...
    @overload
    def __new__(
        cls,
        source: _Source = "any",
        checksum_only: bool = False,
        errors: bool = False,
        lazy: bool = False,
        typed: Optional[bool] = None,
        clock: Optional[Callable[[], float]] = None,
    ) -> Decoder[Union[AnyMessage, Item, _Dict]]: ...

def encode(message: Mapping[str, Any], /) -> bytes:
    """The frame of one request or response (a dict in the JSON-lines schema).

    ``checksum`` (``True`` for ``af c1``) picks the frame form. Raises
    ``ValueError`` naming the field and its range if it is invalid.
    """

def field_info(type: str, path: str, /) -> Optional[FieldInfo]:
    """What field ``path`` of message ``type`` means, from the library's field table."""

# BEGIN message classes: written by python/tests/update_stubs.py

class Message(_Fields):
    """The base of every message class: a read-only mapping of the item's dict
    whose fields read as typed attributes, those only some frames carry as
    ``None`` when absent. At run time a subclass of :class:`robowire.Item`;
    the stubs leave out ``Item``'s untyped attribute fallback, so that a
    field the type does not have is an error."""

    len: int
    """The frame's length in bytes."""
    t: Optional[float]
    """The receive time given to ``feed``, or ``None``."""
    quirk: Optional[str]
    """What the device refuses about this request."""

@final
class ChangeProg(Message):
    """A ``change_prog`` message."""

    type: Literal["change_prog"]
    checksum: bool
    """Whether the frame carried a checksum (af c1 / ae c1 sync)."""
    name: Union[list[int], str]
    """The program's name ("color_connected_components", "line", …)."""
    payload_len: Optional[int]

@final
class GetResolution(Message):
    """A ``get_resolution`` message."""

    type: Literal["get_resolution"]
    checksum: bool
    """Whether the frame carried a checksum (af c1 / ae c1 sync)."""
    reserved: Optional[int]
    """The reserved byte, shown when not 0."""

@final
class GetVersion(Message):
    """A ``get_version`` message."""

    type: Literal["get_version"]
    checksum: bool
    """Whether the frame carried a checksum (af c1 / ae c1 sync)."""

@final
class SetCameraBrightness(Message):
    """A ``set_camera_brightness`` message."""

    type: Literal["set_camera_brightness"]
    checksum: bool
    """Whether the frame carried a checksum (af c1 / ae c1 sync)."""
    brightness: int
    """Camera brightness."""

@final
class SetServos(Message):
    """A ``set_servos`` message."""

    type: Literal["set_servos"]
    checksum: bool
    """Whether the frame carried a checksum (af c1 / ae c1 sync)."""
    pan: int
    """Pan servo position, 0..1000 (more is ignored)."""
    tilt: int
    """Tilt servo position, 0..1000 (more is ignored)."""

@final
class SetLed(Message):
    """A ``set_led`` message."""

    type: Literal["set_led"]
    checksum: bool
    """Whether the frame carried a checksum (af c1 / ae c1 sync)."""
    r: int
    """LED red."""
    g: int
    """LED green."""
    b: int
    """LED blue."""

@final
class SetLamp(Message):
    """A ``set_lamp`` message."""

    type: Literal["set_lamp"]
    checksum: bool
    """Whether the frame carried a checksum (af c1 / ae c1 sync)."""
    upper: int
    """Upper lamps on (not 0)."""
    lower: int
    """Lower lamp on (not 0)."""

@final
class GetFps(Message):
    """A ``get_fps`` message."""

    type: Literal["get_fps"]
    checksum: bool
    """Whether the frame carried a checksum (af c1 / ae c1 sync)."""

@final
class GetBlocks(Message):
    """A ``get_blocks`` message."""

    type: Literal["get_blocks"]
    checksum: bool
    """Whether the frame carried a checksum (af c1 / ae c1 sync)."""
    sigmap: int
    """Signatures asked for, one bit each (255: all)."""
    max_blocks: int
    """The most blocks to return."""

@final
class GetFeatures(Message):
    """A ``get_features`` message."""

    type: Literal["get_features"]
    checksum: bool
    """Whether the frame carried a checksum (af c1 / ae c1 sync)."""
    scope: int
    """0: the main features, 1: all."""
    features: int
    """Feature types asked for: 1 vectors, 2 intersections, 4 barcodes."""

@final
class SetMode(Message):
    """A ``set_mode`` message."""

    type: Literal["set_mode"]
    checksum: bool
    """Whether the frame carried a checksum (af c1 / ae c1 sync)."""
    mode: int
    """Line-tracking mode flags."""

@final
class SetVector(Message):
    """A ``set_vector`` message."""

    type: Literal["set_vector"]
    checksum: bool
    """Whether the frame carried a checksum (af c1 / ae c1 sync)."""
    index: int
    """The vector to track, by index."""

@final
class SetNextTurn(Message):
    """A ``set_next_turn`` message."""

    type: Literal["set_next_turn"]
    checksum: bool
    """Whether the frame carried a checksum (af c1 / ae c1 sync)."""
    angle: int
    """Turn at the next intersection (0 up, +90 left). Unit: °."""

@final
class SetDefaultTurn(Message):
    """A ``set_default_turn`` message."""

    type: Literal["set_default_turn"]
    checksum: bool
    """Whether the frame carried a checksum (af c1 / ae c1 sync)."""
    angle: int
    """Turn when no next turn is set (0 up, +90 left). Unit: °."""

@final
class ReverseVector(Message):
    """A ``reverse_vector`` message."""

    type: Literal["reverse_vector"]
    checksum: bool
    """Whether the frame carried a checksum (af c1 / ae c1 sync)."""

@final
class GetRgb(Message):
    """A ``get_rgb`` message."""

    type: Literal["get_rgb"]
    checksum: bool
    """Whether the frame carried a checksum (af c1 / ae c1 sync)."""
    x: int
    """Pixel column. Unit: px."""
    y: int
    """Pixel row. Unit: px."""
    saturate: int
    """Scale the colour to saturation (not 0)."""

@final
class Result(Message):
    """A ``result`` message."""

    type: Literal["result"]
    checksum: bool
    """Whether the frame carried a checksum (af c1 / ae c1 sync)."""
    value: int
    """The request's result (getFPS: frames/s; getRGB: 0x00RRGGBB)."""

@final
class Error(Message):
    """A ``error`` message."""

    type: Literal["error"]
    checksum: bool
    """Whether the frame carried a checksum (af c1 / ae c1 sync)."""
    code: Union[int, str]
    """The device's error, by name (its number if unknown)."""

@final
class Resolution(Message):
    """A ``resolution`` message."""

    type: Literal["resolution"]
    checksum: bool
    """Whether the frame carried a checksum (af c1 / ae c1 sync)."""
    width: int
    """Frame width. Unit: px."""
    height: int
    """Frame height. Unit: px."""

@final
class Version(Message):
    """A ``version`` message."""

    type: Literal["version"]
    checksum: bool
    """Whether the frame carried a checksum (af c1 / ae c1 sync)."""
    hardware: int
    """Hardware version."""
    firmware_major: int
    """Firmware major version."""
    firmware_minor: int
    """Firmware minor version."""
    firmware_build: int
    """Firmware build number."""
    firmware_type: Union[list[int], str]
    """Firmware type ("general")."""

@final
class Blocks(Message):
    """A ``blocks`` message."""

    type: Literal["blocks"]
    checksum: bool
    """Whether the frame carried a checksum (af c1 / ae c1 sync)."""
    blocks: list[dict[str, Any]]
    """The blocks detected, largest first."""

@final
class Features(Message):
    """A ``features`` message."""

    type: Literal["features"]
    checksum: bool
    """Whether the frame carried a checksum (af c1 / ae c1 sync)."""
    sections: list[dict[str, Any]]
    """The feature sections in wire order."""

AnyMessage = Union[ChangeProg, GetResolution, GetVersion, SetCameraBrightness, SetServos, SetLed, SetLamp, GetFps, GetBlocks, GetFeatures, SetMode, SetVector, SetNextTurn, SetDefaultTurn, ReverseVector, GetRgb, Result, Error, Resolution, Version, Blocks, Features]
"""Every message class, as a union a ``type`` check narrows: what a decoder's items are."""
# END message classes
