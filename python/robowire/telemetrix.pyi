"""Telemetrix4RpiPico: host commands and Pico reports (LEN, id, payload)."""

import sys
from collections.abc import Callable, Mapping
from typing import Any, Literal, Optional, TypeVar, Union, final, overload

from ._robowire import Item, StreamDecoder, _Dict, _Fields
from .omnitiles import FieldInfo

if sys.version_info >= (3, 13):
    from warnings import deprecated
else:
    from typing_extensions import deprecated

_Source = Literal["host", "pico", "any"]
_Dialect = Literal["mirte13", "mirte12", "upstream11"]

__all__ = ["AnyMessage", "Decoder", "Message", "encode", "field_info"]  # and every message class

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
        clock: Optional[Callable[[], float]] = None,
    ) -> Decoder[_Dict]: ...
    @overload
    def __new__(
        cls,
        source: _Source = "any",
        dialect: _Dialect = "mirte13",
        lenient: bool = False,
        errors: Literal[False] = False,
        lazy: Literal[False] = False,
        typed: None = None,
        clock: Optional[Callable[[], float]] = None,
    ) -> Decoder[AnyMessage]: ...
    @overload
    def __new__(
        cls,
        source: _Source = "any",
        dialect: _Dialect = "mirte13",
        lenient: bool = False,
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
        dialect: _Dialect = "mirte13",
        lenient: bool = False,
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
        dialect: _Dialect = "mirte13",
        lenient: bool = False,
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
        dialect: _Dialect = "mirte13",
        lenient: bool = False,
        errors: bool = False,
        lazy: bool = False,
        typed: Optional[bool] = None,
        clock: Optional[Callable[[], float]] = None,
    ) -> Decoder[Union[AnyMessage, Item, _Dict]]: ...

def encode(message: Mapping[str, Any], /, dialect: _Dialect = "mirte13") -> bytes:
    """The frame of one command or report (a dict in the JSON-lines schema) for ``dialect``.

    Raises ``ValueError`` naming the field and its range if it is invalid.
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
    """What is unusual about the frame, that the firmware does differently."""
    also: Optional[str]
    """The other direction's reading of a frame that reads both ways (``source="any"``), or ``None``."""

@final
class SerialLoopBack(Message):
    """A ``serial_loop_back`` message."""

    type: Literal["serial_loop_back"]
    byte: int

@final
class SetPinMode(Message):
    """A ``set_pin_mode`` message."""

    type: Literal["set_pin_mode"]
    pin: int
    mode: str
    report_enable: Optional[bool]
    differential: Optional[int]

@final
class DigitalWrite(Message):
    """A ``digital_write`` message."""

    type: Literal["digital_write"]
    pin: int
    value: int

@final
class PwmWrite(Message):
    """A ``pwm_write`` message."""

    type: Literal["pwm_write"]
    pins: list[dict[str, Any]]

@final
class ModifyReporting(Message):
    """A ``modify_reporting`` message."""

    type: Literal["modify_reporting"]
    action: str
    pin: Optional[int]

@final
class GetFirmwareVersion(Message):
    """A ``get_firmware_version`` message."""

    type: Literal["get_firmware_version"]

@final
class GetPicoUniqueId(Message):
    """A ``get_pico_unique_id`` message."""

    type: Literal["get_pico_unique_id"]

@final
class ServoAttach(Message):
    """A ``servo_attach`` message."""

    type: Literal["servo_attach"]
    pin: int
    min_us: Optional[int]
    max_us: Optional[int]

@final
class ServoWrite(Message):
    """A ``servo_write`` message."""

    type: Literal["servo_write"]
    pin: int
    pulse_us: int

@final
class ServoDetach(Message):
    """A ``servo_detach`` message."""

    type: Literal["servo_detach"]
    pin: int

@final
class I2cBegin(Message):
    """A ``i2c_begin`` message."""

    type: Literal["i2c_begin"]
    port: int
    """I2C or SPI port, 0 or 1."""
    sda: int
    scl: int

@final
class I2cRead(Message):
    """A ``i2c_read`` message."""

    type: Literal["i2c_read"]
    port: int
    """I2C or SPI port, 0 or 1."""
    addr: int
    """7-bit I2C address."""
    msg_id: Optional[int]
    """The request's message id, echoed."""
    reg: int
    """The register read."""
    n: int
    no_stop: int

@final
class I2cWrite(Message):
    """A ``i2c_write`` message."""

    type: Literal["i2c_write"]
    port: int
    """I2C or SPI port, 0 or 1."""
    addr: int
    """7-bit I2C address."""
    msg_id: Optional[int]
    """The request's message id, echoed."""
    no_stop: int
    data: list[int]
    """The bytes read."""

@final
class SonarNew(Message):
    """A ``sonar_new`` message."""

    type: Literal["sonar_new"]
    trig: int
    echo: int

@final
class DhtNew(Message):
    """A ``dht_new`` message."""

    type: Literal["dht_new"]
    pin: int

@final
class StopAllReports(Message):
    """A ``stop_all_reports`` message."""

    type: Literal["stop_all_reports"]

@final
class EnableAllReports(Message):
    """A ``enable_all_reports`` message."""

    type: Literal["enable_all_reports"]

@final
class ResetData(Message):
    """A ``reset_data`` message."""

    type: Literal["reset_data"]

@final
class ResetBoard(Message):
    """A ``reset_board`` message."""

    type: Literal["reset_board"]

@final
class InitializeNeoPixels(Message):
    """A ``initialize_neo_pixels`` message."""

    type: Literal["initialize_neo_pixels"]
    pin: int
    count: int
    r: int
    g: int
    b: int

@final
class ShowNeoPixels(Message):
    """A ``show_neo_pixels`` message."""

    type: Literal["show_neo_pixels"]

@final
class SetNeoPixel(Message):
    """A ``set_neo_pixel`` message."""

    type: Literal["set_neo_pixel"]
    index: int
    r: int
    g: int
    b: int
    auto_show: bool

@final
class ClearAllNeoPixels(Message):
    """A ``clear_all_neo_pixels`` message."""

    type: Literal["clear_all_neo_pixels"]
    auto_show: Optional[bool]

@final
class FillNeoPixels(Message):
    """A ``fill_neo_pixels`` message."""

    type: Literal["fill_neo_pixels"]
    r: int
    g: int
    b: int
    auto_show: bool

@final
class SpiInit(Message):
    """A ``spi_init`` message."""

    type: Literal["spi_init"]
    port: int
    """I2C or SPI port, 0 or 1."""
    pin_a: int
    pin_b: int
    clk: int
    freq_hz: int
    cs_pins: list[int]

@final
class SpiWriteBlocking(Message):
    """A ``spi_write_blocking`` message."""

    type: Literal["spi_write_blocking"]
    port: int
    """I2C or SPI port, 0 or 1."""
    data: list[int]
    """The bytes read."""

@final
class SpiReadBlocking(Message):
    """A ``spi_read_blocking`` message."""

    type: Literal["spi_read_blocking"]
    port: int
    """I2C or SPI port, 0 or 1."""
    n: int
    tx_fill: int

@final
class SpiSetFormat(Message):
    """A ``spi_set_format`` message."""

    type: Literal["spi_set_format"]
    port: int
    """I2C or SPI port, 0 or 1."""
    data_bits: int
    cpol: int
    cpha: int

@final
class SpiCsControl(Message):
    """A ``spi_cs_control`` message."""

    type: Literal["spi_cs_control"]
    cs_pin: int
    level: int

@final
class SetScanDelay(Message):
    """A ``set_scan_delay`` message."""

    type: Literal["set_scan_delay"]
    delay_ms: int
    """Scan period. Unit: ms."""

@final
class EncoderNew(Message):
    """A ``encoder_new`` message."""

    type: Literal["encoder_new"]
    kind: str
    pin_a: int
    pin_b: int
    pulls: Optional[dict[str, Any]]

@final
class SensorNew(Message):
    """A ``sensor_new`` message."""

    type: Literal["sensor_new"]
    subtype: str
    sensor_num: Optional[int]
    """The sensor's number, in the order of SENSOR_NEW."""
    sensor_type: Union[int, str]
    """The sensor's type, by name (its number if unknown)."""
    settings: Optional[list[int]]

@final
class Ping(Message):
    """A ``ping`` message."""

    type: Literal["ping"]
    counter: int

@final
class ModuleNew(Message):
    """A ``module_new`` message."""

    type: Literal["module_new"]
    subtype: str
    module_type: Union[int, str]
    """The module's type, by name (its number if unknown)."""
    module_num: Optional[int]
    """The module's number, in the order of MODULE_NEW."""
    init: Optional[dict[str, Any]]

@final
class ModuleData(Message):
    """A ``module_data`` message."""

    type: Literal["module_data"]
    module_num: int
    """The module's number, in the order of MODULE_NEW."""
    data: Optional[list[int]]
    """The bytes read."""
    module_type: Optional[str]
    """The module's type, by name (its number if unknown)."""
    message: Optional[dict[str, Any]]
    """The module's message, by the module's type."""

@final
class GetId(Message):
    """A ``get_id`` message."""

    type: Literal["get_id"]

@final
class SetId(Message):
    """A ``set_id`` message."""

    type: Literal["set_id"]
    id: int

@final
class FeatureRequest(Message):
    """A ``feature_request`` message."""

    type: Literal["feature_request"]
    msg_type: int

@final
class BootloaderReset(Message):
    """A ``bootloader_reset`` message."""

    type: Literal["bootloader_reset"]

@final
class SerialLoopBackReport(Message):
    """A ``serial_loop_back_report`` message."""

    type: Literal["serial_loop_back_report"]
    byte: int
    """The byte echoed back."""

@final
class DigitalReport(Message):
    """A ``digital_report`` message."""

    type: Literal["digital_report"]
    pin: int
    """GPIO."""
    value: int
    """Level: 1 high, 0 low (another byte only with its quirk)."""

@final
class AnalogReport(Message):
    """A ``analog_report`` message."""

    type: Literal["analog_report"]
    pin: int
    """GPIO 26..=30 (ADC 0..=4 in older dialects)."""
    value: int
    """12-bit reading. Unit: ADC counts."""

@final
class FirmwareVersion(Message):
    """A ``firmware_version`` message."""

    type: Literal["firmware_version"]
    major: int
    """Firmware major version."""
    minor: int
    """Firmware minor version."""

@final
class PicoUniqueId(Message):
    """A ``pico_unique_id`` message."""

    type: Literal["pico_unique_id"]
    id: list[int]
    """The board's unique id bytes."""

@final
class I2cWriteReport(Message):
    """A ``i2c_write_report`` message."""

    type: Literal["i2c_write_report"]
    port: int
    """I2C or SPI port, 0 or 1."""
    msg_id: int
    """The request's message id, echoed."""
    result: int
    """Bytes written, or −1 (error), −2 (timeout). Unit: B."""

@final
class I2cWriteFailed(Message):
    """A ``i2c_write_failed`` message."""

    type: Literal["i2c_write_failed"]
    port: int
    """I2C or SPI port, 0 or 1."""
    addr: int
    """7-bit I2C address."""
    stale: int
    """A byte without meaning."""

@final
class I2cReadFailed(Message):
    """A ``i2c_read_failed`` message."""

    type: Literal["i2c_read_failed"]
    port: int
    """I2C or SPI port, 0 or 1."""
    addr: int
    """7-bit I2C address."""
    stale: int
    """A byte without meaning."""

@final
class I2cReadReport(Message):
    """A ``i2c_read_report`` message."""

    type: Literal["i2c_read_report"]
    port: int
    """I2C or SPI port, 0 or 1."""
    msg_id: Optional[int]
    """The request's message id, echoed."""
    reg: int
    """The register read."""
    data: list[int]
    """The bytes read."""
    addr: Optional[int]
    """7-bit I2C address."""

@final
class SonarDistance(Message):
    """A ``sonar_distance`` message."""

    type: Literal["sonar_distance"]
    trig: int
    """Trigger GPIO."""
    echo: Optional[int]
    """Echo GPIO (mirte 1.3)."""
    cm: Union[int, str]
    """Distance (echo µs / 58), or no_echo, out_of_range (over 30 ms), stale. Unit: cm."""
    m: Optional[int]
    """Whole metres (mirte 1.2 form)."""
    hundredths: Optional[int]
    """Hundredths of a centimetre (upstream form)."""

@final
class DhtReport(Message):
    """A ``dht_report`` message."""

    type: Literal["dht_report"]
    pin: int
    """GPIO."""
    hum_int: int
    """Relative humidity, whole percent."""
    hum_hundredths: int
    """Relative humidity, hundredths of a percent."""
    temp_int: int
    """Temperature, whole degrees. Unit: °C."""
    temp_hundredths: int
    """Temperature, hundredths of a degree."""

@final
class SpiReport(Message):
    """A ``spi_report`` message."""

    type: Literal["spi_report"]
    port: int
    """I2C or SPI port, 0 or 1."""
    data: list[int]
    """The bytes read."""

@final
class EncoderReport(Message):
    """A ``encoder_report`` message."""

    type: Literal["encoder_report"]
    pin_a: int
    """The encoder's A GPIO."""
    steps: int
    """Steps since the last report. Unit: steps."""

@final
class SensorReport(Message):
    """A ``sensor_report`` message."""

    type: Literal["sensor_report"]
    sensor_num: int
    """The sensor's number, in the order of SENSOR_NEW."""
    sensor_type: str
    """The sensor's type, by name (its number if unknown)."""
    reading: dict[str, Any]
    """The reading, by the sensor's type."""

@final
class SensorMainReport(Message):
    """A ``sensor_main_report`` message."""

    type: Literal["sensor_main_report"]
    sensor_type: Union[int, str]
    """The sensor's type, by name (its number if unknown)."""
    supported: bool
    """Whether the firmware supports it."""

@final
class Pong(Message):
    """A ``pong`` message."""

    type: Literal["pong"]
    counter: int
    """The ping's counter, echoed."""
    boot_id: int
    """A number the firmware draws at boot, 0..99."""

@final
class ModuleMainReport(Message):
    """A ``module_main_report`` message."""

    type: Literal["module_main_report"]
    module_type: Union[int, str]
    """The module's type, by name (its number if unknown)."""
    supported: bool
    """Whether the firmware supports it."""

@final
class ModuleReport(Message):
    """A ``module_report`` message."""

    type: Literal["module_report"]
    module_num: int
    """The module's number, in the order of MODULE_NEW."""
    module_type: str
    """The module's type, by name (its number if unknown)."""
    message: dict[str, Any]
    """The module's message, by the module's type."""

@final
class GetIdReport(Message):
    """A ``get_id_report`` message."""

    type: Literal["get_id_report"]
    id: int
    """The saved id."""

@final
class SetIdReport(Message):
    """A ``set_id_report`` message."""

    type: Literal["set_id_report"]
    id: int
    """The id saved."""

@final
class FeatureCheck(Message):
    """A ``feature_check`` message."""

    type: Literal["feature_check"]
    msg_type: int
    """The command id asked about."""
    ok: bool
    """Whether the firmware has it."""
    extras: list[int]
    """Bytes after the answer."""

@final
class DebugPrint(Message):
    """A ``debug_print`` message."""

    type: Literal["debug_print"]
    id: int
    """The firmware's debug message id."""
    value: int
    """Its value."""

@final
class UnknownReport(Message):
    """A ``unknown_report`` message."""

    type: Literal["unknown_report"]
    id: int
    payload: list[int]

AnyMessage = Union[SerialLoopBack, SetPinMode, DigitalWrite, PwmWrite, ModifyReporting, GetFirmwareVersion, GetPicoUniqueId, ServoAttach, ServoWrite, ServoDetach, I2cBegin, I2cRead, I2cWrite, SonarNew, DhtNew, StopAllReports, EnableAllReports, ResetData, ResetBoard, InitializeNeoPixels, ShowNeoPixels, SetNeoPixel, ClearAllNeoPixels, FillNeoPixels, SpiInit, SpiWriteBlocking, SpiReadBlocking, SpiSetFormat, SpiCsControl, SetScanDelay, EncoderNew, SensorNew, Ping, ModuleNew, ModuleData, GetId, SetId, FeatureRequest, BootloaderReset, SerialLoopBackReport, DigitalReport, AnalogReport, FirmwareVersion, PicoUniqueId, I2cWriteReport, I2cWriteFailed, I2cReadFailed, I2cReadReport, SonarDistance, DhtReport, SpiReport, EncoderReport, SensorReport, SensorMainReport, Pong, ModuleMainReport, ModuleReport, GetIdReport, SetIdReport, FeatureCheck, DebugPrint, UnknownReport]
"""Every message class, as a union a ``type`` check narrows: what a decoder's items are."""
# END message classes
