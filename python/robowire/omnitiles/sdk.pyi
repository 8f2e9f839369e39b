"""A drop-in for the OmniTiles SDK's stream parser, decoded by robowire."""

from collections.abc import Callable
from typing import Optional, final

from .._robowire import _Bytes
from .._stats import Stats
from . import Imu

__all__ = ["StreamParser", "Telemetry"]

@final
class Telemetry:
    """One telemetry frame with the SDK's fields. Immutable, hashable, picklable."""

    @property
    def timestamp(self) -> float:
        """Receive time: the parser's clock, read once per ``feed``."""
    @property
    def m1_pos_adc(self) -> Optional[int]:
        """Raw 12-bit M1 potentiometer reading; ``None`` for 0xFFFF (the SDK keeps 65535)."""
    @property
    def m2_pos_adc(self) -> Optional[int]:
        """Raw 12-bit M2 potentiometer reading; ``None`` for 0xFFFF."""
    @property
    def m1_pos_mm(self) -> Optional[float]:
        """``m1_pos_adc / 4095 * 150``, or ``None``."""
    @property
    def m2_pos_mm(self) -> Optional[float]:
        """``m2_pos_adc / 4095 * 100``, or ``None``."""
    @property
    def m1_adcs(self) -> tuple[int, ...]:
        """The four M1 potentiometer readings, or ``()`` if not reported."""
    @property
    def m2_adcs(self) -> tuple[int, ...]:
        """The two M2 potentiometer readings, or ``()`` if not reported."""
    @property
    def uwb_mm(self) -> Optional[tuple[Optional[int], Optional[int], Optional[int], Optional[int]]]:
        """Ranges to anchors 0..3 in mm (each ``None`` when invalid), or ``None``."""
    @property
    def tof_mm(self) -> Optional[int]:
        """Time-of-flight range in mm, or ``None``."""
    @property
    def imu(self) -> Optional[Imu]:
        """The IMU sample (``ax ay az`` m/s², ``gx gy gz`` rad/s), or ``None``."""
    @property
    def raw(self) -> bytes:
        """The frame's bytes."""
    @property
    def offset(self) -> int:
        """Offset of the frame's first byte in the stream (robowire's addition)."""
    @property
    def layout(self) -> str:
        """``"pos7"``, ``"uwb15"``, ``"uwbtof17"`` or ``"ble53"`` (robowire's addition)."""
    def __hash__(self) -> int: ...

@final
class StreamParser:
    """Feed bytes in, get :class:`Telemetry` frames out (the SDK's parser's API)."""

    def __init__(
        self,
        clock: Optional[Callable[[], float]] = None,
        *,
        m1_stroke_mm: float = 150.0,
        m2_stroke_mm: float = 100.0,
        adc_max: float = 4095.0,
    ) -> None: ...
    def feed(self, data: _Bytes, /) -> list[Telemetry]:
        """The frames the new bytes complete, in stream order."""
    def settle(self) -> list[Telemetry]:
        """The line went quiet: a buffered short frame only the next byte would decide."""
    @property
    def stats(self) -> Stats:
        """Link-quality counters (robowire's addition)."""
    @property
    def buffered(self) -> int:
        """Bytes held as the start of an unfinished frame."""
