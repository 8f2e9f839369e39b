"""OmniTiles: host commands and tile telemetry (``a5``, id, payload, sum)."""

import sys
from collections.abc import Callable, Iterable, Iterator, Mapping
from typing import Any, ClassVar, Generic, Literal, Optional, TypedDict, TypeVar, Union, final, overload

from .._robowire import Item, StreamDecoder, _Bytes, _Dict
from .._stats import Stats

if sys.version_info >= (3, 13):
    from warnings import deprecated
else:
    from typing_extensions import deprecated

_Source = Literal["tile", "host", "any"]
_Layouts = Union[str, Iterable[str], None]
_T_co = TypeVar("_T_co", covariant=True)

__all__ = ["Decoder", "DatagramDecoder", "FieldInfo", "Imu", "Telemetry", "encode", "field_info"]

_Layout = Literal["pos7", "uwb15", "uwbtof17", "spi45", "ble53"]

class FieldInfo(TypedDict):
    """What a field means, from the library's field table."""

    unit: Optional[str]
    doc: str
    no_reading: bool
    range: Optional[tuple[int, int]]
    names: list[str]
    optional: bool

def field_info(type: str, path: str, /) -> Optional[FieldInfo]:
    """What field ``path`` (``"imu.az"``, ``"uwb.2"``) of message ``type`` means."""

@final
class Imu(Mapping[str, float]):
    """One IMU sample; each value is the wire's f32 exactly (NaN, inf included).
    A read-only mapping of the six names to their values."""

    units: ClassVar[dict[str, str]]
    """``{"ax": "m/s²", ..., "gz": "rad/s"}``."""

    @property
    def ax(self) -> float:
        """Acceleration along x, m/s²."""
    @property
    def ay(self) -> float:
        """Acceleration along y, m/s²."""
    @property
    def az(self) -> float:
        """Acceleration along z, m/s² (about +9.8 at rest)."""
    @property
    def gx(self) -> float:
        """Angular rate about x, rad/s."""
    @property
    def gy(self) -> float:
        """Angular rate about y, rad/s."""
    @property
    def gz(self) -> float:
        """Angular rate about z, rad/s."""
    def keys(self) -> list[str]: ...  # type: ignore[override]
    def values(self) -> list[float]: ...  # type: ignore[override]
    def items(self) -> list[tuple[str, float]]: ...  # type: ignore[override]
    def to_dict(self) -> dict[str, float]:
        """The dict form's ``imu`` dict."""
    def __getitem__(self, key: str, /) -> float: ...
    def __iter__(self) -> Iterator[str]: ...
    def __len__(self) -> int: ...
    def __contains__(self, key: object, /) -> bool: ...
    def __hash__(self) -> int:
        """Equal samples (the same bit patterns) hash alike; pickles and copies exactly."""

@final
class Telemetry(Mapping[str, Any]):
    """One telemetry frame (a decoder's default item). ``None``: no reading
    (0xFFFF), or a group the layout does not carry (``"tof" in t`` tells them
    apart). A read-only mapping of the dict form's keys (``len(t)`` counts
    them; the frame's length is ``t.len``), with tuples for its lists."""

    @property
    def offset(self) -> int:
        """Offset of the frame's first byte in the stream."""
    @property
    def t(self) -> Optional[float]:
        """The receive time given to the call that returned the item, or ``None``."""
    @property
    def len(self) -> int:
        """The frame's length: 7, 15, 17, 45 or 53."""
    @property
    def raw(self) -> bytes:
        """The frame's bytes as received, start byte to checksum."""
    @property
    def type(self) -> Literal["telemetry"]: ...
    @property
    def layout(self) -> _Layout: ...
    @property
    def m1_pos(self) -> Optional[int]:
        """M1 position, raw 0..4095."""
    @property
    def m2_pos(self) -> Optional[int]:
        """M2 position, raw 0..4095."""
    @property
    def m1_pos_mm(self) -> Optional[float]:
        """M1 position in mm, ``m1_pos / 4095 * 150`` (the SDK's formula)."""
    @property
    def m2_pos_mm(self) -> Optional[float]:
        """M2 position in mm, ``m2_pos / 4095 * 100`` (the SDK's formula)."""
    units: ClassVar[dict[str, str]]
    """The unit of each field that has one (``{"m1_pos": "ADC counts", "uwb": "mm", ...}``)."""
    @property
    def uwb(self) -> Optional[tuple[Optional[int], Optional[int], Optional[int], Optional[int]]]:
        """UWB ranges to anchors 0..3 in mm (15, 17 and 53-byte layouts)."""
    @property
    def tof(self) -> Optional[int]:
        """ToF range in mm (17, 45 and 53-byte layouts)."""
    @property
    def imu(self) -> Optional[Imu]:
        """IMU sample (45 and 53-byte layouts)."""
    @property
    def m1_adcs(self) -> Optional[tuple[int, int, int, int]]:
        """M1's four potentiometer channels, raw 0..4095 (45 and 53-byte layouts)."""
    @property
    def m2_adcs(self) -> Optional[tuple[int, int]]:
        """M2's two potentiometer channels, raw 0..4095 (45 and 53-byte layouts)."""
    def keys(self) -> list[str]:  # type: ignore[override]
        """The keys of the dict form (groups the layout carries only)."""
    def values(self) -> list[Any]: ...  # type: ignore[override]
    def items(self) -> list[tuple[str, Any]]: ...  # type: ignore[override]
    def __iter__(self) -> Iterator[str]: ...
    def __len__(self) -> int: ...
    def get(self, key: str, default: Any = None, /) -> Any: ...
    def to_dict(self) -> dict[str, Any]:
        """The dict a ``typed=False`` decoder returns for this frame."""
    def __getitem__(self, key: str, /) -> Any: ...
    def __contains__(self, key: object, /) -> bool: ...
    def __hash__(self) -> int:
        """Equal items (the same offset and bytes) hash alike; pickles and copies exactly."""

@final
class Decoder(StreamDecoder[_T_co]):
    """The OmniTiles stream decoder, generic in its items: ``Decoder[Telemetry]``
    for ``source="tile"``, ``Decoder[Item]`` for ``"host"``, ``Decoder[dict[str,
    Any]]`` with ``typed=False``; rejections (``errors=True``) are :class:`Item`.

    ``source``: ``"tile"`` (telemetry only), ``"host"`` (commands only) or
    ``"any"`` (both). ``layouts``: telemetry layouts to accept, a list or a
    comma-separated string of ``pos7``, ``uwb15``, ``uwbtof17``, ``ble53``,
    ``spi45``, ``auto`` (default: ``auto``, the four the SDK documents).
    """

    @overload
    def __new__(
        cls,
        source: Literal["tile"],
        layouts: _Layouts = None,
        errors: Literal[False] = False,
        lazy: Literal[False] = False,
        typed: None = None,
        clock: Optional[Callable[[], float]] = None,
    ) -> Decoder[Telemetry]: ...
    @overload
    def __new__(
        cls,
        source: Literal["host"],
        layouts: _Layouts = None,
        errors: bool = False,
        lazy: Literal[False] = False,
        typed: None = None,
        clock: Optional[Callable[[], float]] = None,
    ) -> Decoder[Item]: ...
    @overload
    def __new__(
        cls,
        source: _Source = "any",
        layouts: _Layouts = None,
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
        layouts: _Layouts = None,
        errors: bool = False,
        lazy: Literal[False] = False,
        typed: None = None,
        clock: Optional[Callable[[], float]] = None,
    ) -> Decoder[Union[Telemetry, Item]]: ...
    @overload
    @deprecated("typed=True is the default: drop it")
    def __new__(
        cls,
        source: _Source = "any",
        layouts: _Layouts = None,
        errors: bool = False,
        lazy: Literal[False] = False,
        *,
        typed: Literal[True],
        clock: Optional[Callable[[], float]] = None,
    ) -> Decoder[Union[Telemetry, Item]]: ...
    @overload
    @deprecated("lazy=True is deprecated: the default typed items read a field without a dict")
    def __new__(
        cls,
        source: _Source = "any",
        layouts: _Layouts = None,
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
        layouts: _Layouts = None,
        errors: bool = False,
        lazy: bool = False,
        typed: Optional[bool] = None,
        clock: Optional[Callable[[], float]] = None,
    ) -> Decoder[Union[Telemetry, Item, _Dict]]: ...

@final
class DatagramDecoder(Generic[_T_co]):
    """Decodes one whole datagram (a BLE notification or write, an SPI buffer) per call;
    its items as for :class:`Decoder`."""

    @overload
    def __new__(
        cls,
        source: Literal["tile"],
        layouts: _Layouts = None,
        errors: Literal[False] = False,
        lazy: Literal[False] = False,
        typed: None = None,
        clock: Optional[Callable[[], float]] = None,
    ) -> DatagramDecoder[Telemetry]: ...
    @overload
    def __new__(
        cls,
        source: Literal["host"],
        layouts: _Layouts = None,
        errors: bool = False,
        lazy: Literal[False] = False,
        typed: None = None,
        clock: Optional[Callable[[], float]] = None,
    ) -> DatagramDecoder[Item]: ...
    @overload
    def __new__(
        cls,
        source: _Source = "any",
        layouts: _Layouts = None,
        errors: bool = False,
        lazy: Literal[False] = False,
        *,
        typed: Literal[False],
        clock: Optional[Callable[[], float]] = None,
    ) -> DatagramDecoder[_Dict]: ...
    @overload
    def __new__(
        cls,
        source: _Source = "any",
        layouts: _Layouts = None,
        errors: bool = False,
        lazy: Literal[False] = False,
        typed: None = None,
        clock: Optional[Callable[[], float]] = None,
    ) -> DatagramDecoder[Union[Telemetry, Item]]: ...
    @overload
    @deprecated("typed=True is the default: drop it")
    def __new__(
        cls,
        source: _Source = "any",
        layouts: _Layouts = None,
        errors: bool = False,
        lazy: Literal[False] = False,
        *,
        typed: Literal[True],
        clock: Optional[Callable[[], float]] = None,
    ) -> DatagramDecoder[Union[Telemetry, Item]]: ...
    @overload
    @deprecated("lazy=True is deprecated: the default typed items read a field without a dict")
    def __new__(
        cls,
        source: _Source = "any",
        layouts: _Layouts = None,
        errors: bool = False,
        *,
        lazy: Literal[True],
        typed: Optional[Literal[False]] = None,
        clock: Optional[Callable[[], float]] = None,
    ) -> DatagramDecoder[Item]: ...
    @overload
    def __new__(
        cls,
        source: _Source = "any",
        layouts: _Layouts = None,
        errors: bool = False,
        lazy: bool = False,
        typed: Optional[bool] = None,
        clock: Optional[Callable[[], float]] = None,
    ) -> DatagramDecoder[Union[Telemetry, Item, _Dict]]: ...
    def decode(self, datagram: _Bytes, /, t: Optional[float] = None) -> list[_T_co]:
        """The items of one datagram, in order."""
    @property
    def stats(self) -> Stats: ...
    @property
    def errors(self) -> bool: ...
    @property
    def lazy(self) -> bool: ...
    @property
    def typed(self) -> bool: ...

def encode(message: Union[Mapping[str, Any], Telemetry], /) -> bytes:
    """The frame of one message (a dict in the JSON-lines schema).

    Raises ``ValueError`` naming the field and its range if it is invalid.
    """
