"""Shared helpers: the sample captures and the command-line tool's lines for them."""

from __future__ import annotations

import json
import math
import os
import struct
import subprocess
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Callable, Optional

import pytest

from robowire import omnitiles, pixy2, telemetrix

REPO = Path(__file__).resolve().parents[2]
DATA = REPO / "tests" / "data"
GOLDEN = Path(__file__).resolve().parent / "golden"


def read_hex(text: str) -> bytes:
    """Hex text as the tool's ``--hex`` reads it (whitespace, commas and
    ``0x`` prefixes ignored)."""
    cleaned = text.replace(",", " ").replace("0x", " ").replace("0X", " ")
    return bytes.fromhex("".join(cleaned.split()))


@dataclass(frozen=True)
class Case:
    """One sample capture decoded one way: the tool's arguments and the
    Python decoder that must give the same lines."""

    name: str
    file: str
    args: tuple[str, ...]
    make: Callable[..., Any]
    kwargs: dict[str, Any] = field(default_factory=dict)
    hex: bool = False
    datagrams: bool = False

    def input(self) -> bytes:
        raw = (DATA / self.file).read_bytes()
        return read_hex(raw.decode()) if self.hex else raw

    def datagram_list(self) -> list[bytes]:
        lines = (DATA / self.file).read_text().splitlines()
        return [read_hex(line) for line in lines if line.strip()]

    def decoder(self, errors: bool = True, lazy: bool = False, typed: bool = False) -> Any:
        if lazy:  # deprecated: tested as long as it exists
            with pytest.warns(DeprecationWarning, match="lazy=True is deprecated"):
                return self.make(errors=errors, lazy=True, **self.kwargs)
        if typed:  # the default
            return self.make(errors=errors, **self.kwargs)
        return self.make(errors=errors, typed=False, **self.kwargs)

    def cli_args(self) -> list[str]:
        protocol = {omnitiles: "omnitiles", pixy2: "pixy2", telemetrix: "telemetrix"}[
            _module_of(self.make)
        ]
        args = ["decode", protocol, *self.args, "--errors"]
        if self.hex and not self.datagrams:
            args.append("--hex")
        if self.datagrams:
            args.append("--datagrams")
        return [*args, str(DATA / self.file)]


def _module_of(make: Callable[..., Any]) -> Any:
    for module in (omnitiles, pixy2, telemetrix):
        if make in (getattr(module, "Decoder"), getattr(module, "DatagramDecoder", None)):
            return module
    raise AssertionError(make)


O, P, T = omnitiles, pixy2, telemetrix
CASES = [
    Case("omni_ble_any", "ble_telemetry.bin", (), O.Decoder),
    Case("omni_ble_tile", "ble_telemetry.bin", ("--from", "tile", "--layout", "ble53"), O.Decoder,
         {"source": "tile", "layouts": ["ble53"]}),
    Case("omni_ble_mixed", "ble_telemetry.bin", ("--from", "tile", "--layout", "pos7,uwb15,ble53,spi45"),
         O.Decoder, {"source": "tile", "layouts": "pos7,uwb15,ble53,spi45"}),
    Case("omni_host_any", "host_commands.bin", (), O.Decoder),
    Case("omni_host_host", "host_commands.bin", ("--from", "host"), O.Decoder, {"source": "host"}),
    Case("omni_spi_tile", "spi_telemetry.bin", ("--from", "tile", "--layout", "spi45"), O.Decoder,
         {"source": "tile", "layouts": ["spi45"]}),
    Case("omni_spi_auto", "spi_telemetry.bin", ("--layout", "auto,spi45"), O.Decoder,
         {"layouts": ["auto", "spi45"]}),
    Case("omni_notifications_stream", "ble_notifications.hex", (), O.Decoder, hex=True),
    Case("omni_notifications", "ble_notifications.hex", (), O.DatagramDecoder, hex=True, datagrams=True),
    Case("omni_notifications_tile", "ble_notifications.hex", ("--from", "tile"), O.DatagramDecoder,
         {"source": "tile"}, hex=True, datagrams=True),
    Case("omni_spi_commands", "spi_commands.hex", ("--from", "host"), O.DatagramDecoder,
         {"source": "host"}, hex=True, datagrams=True),
    Case("pixy2_any", "pixy2_conversation.hex", (), P.Decoder, hex=True),
    Case("pixy2_device", "pixy2_conversation.hex", ("--from", "device"), P.Decoder,
         {"source": "device"}, hex=True),
    Case("pixy2_host", "pixy2_conversation.hex", ("--from", "host"), P.Decoder, {"source": "host"}, hex=True),
    Case("pixy2_checksum_only", "pixy2_conversation.hex", ("--checksum-only",), P.Decoder,
         {"checksum_only": True}, hex=True),
    Case("tmx_reports_pico", "telemetrix_reports.bin", ("--from", "pico"), T.Decoder, {"source": "pico"}),
    Case("tmx_reports_any", "telemetrix_reports.bin", (), T.Decoder),
    Case("tmx_reports_pico_lenient", "telemetrix_reports.bin", ("--from", "pico", "--lenient"), T.Decoder,
         {"source": "pico", "lenient": True}),
    Case("tmx_reports_any_lenient", "telemetrix_reports.bin", ("--from", "any", "--lenient"), T.Decoder,
         {"source": "any", "lenient": True}),
    Case("tmx_reports_mirte12", "telemetrix_reports.bin", ("--from", "pico", "--dialect", "mirte12", "--allow-noise"),
         T.Decoder, {"source": "pico", "dialect": "mirte12"}),
    Case("tmx_commands_host", "telemetrix_commands.hex", ("--from", "host"), T.Decoder,
         {"source": "host"}, hex=True),
    Case("tmx_commands_any", "telemetrix_commands.hex", (), T.Decoder, hex=True),
]


def cli_binary() -> Optional[str]:
    """The ``robowire`` tool named by ``ROBOWIRE_CLI``, if any."""
    path = os.environ.get("ROBOWIRE_CLI")
    return path if path else None


def cli_lines(case: Case) -> list[dict[str, Any]]:
    """The tool's lines for `case`, parsed: from the tool itself when
    ``ROBOWIRE_CLI`` names it, else from the golden file it wrote."""
    binary = cli_binary()
    if binary is not None:
        run = subprocess.run([binary, *case.cli_args()], capture_output=True, check=True)
        text = run.stdout.decode()
    else:
        text = (GOLDEN / f"{case.name}.jsonl").read_text()
    return [json.loads(line) for line in text.splitlines()]


def decode_all(
    case: Case, chunk: Optional[int] = None, errors: bool = True, lazy: bool = False, typed: bool = False
) -> list[Any]:
    """Decode `case`'s capture with the Python decoder, `chunk` bytes at a time."""
    decoder = case.decoder(errors=errors, lazy=lazy, typed=typed)
    if case.datagrams:
        return [item for datagram in case.datagram_list() for item in decoder.decode(datagram)]
    data = case.input()
    step = chunk or max(len(data), 1)
    items = []
    for start in range(0, len(data), step):
        items += decoder.feed(data[start : start + step])
    return items + decoder.finish()


def f32(x: float) -> float:
    """The value of the ``f32`` nearest to `x`, as a Python float: what an
    item holds for a wire value written ``x`` in the tool's JSON text."""
    return struct.unpack("<f", struct.pack("<f", x))[0]


def f32_bits(x: float) -> int:
    """The bits of the ``f32`` that the float `x` holds exactly; a NaN's sign
    and payload are read from the ``f64``'s bits, not through C's cast."""
    if math.isnan(x):
        (wide,) = struct.unpack("<Q", struct.pack("<d", x))
        return ((wide >> 63) << 31) | 0x7F800000 | ((wide >> 29) & 0x7FFFFF)
    (bits,) = struct.unpack("<I", struct.pack("<f", x))
    assert struct.unpack("<f", struct.pack("<I", bits))[0] == x, f"{x!r} is not an f32"
    return bits


def json_f32_bits(value: Any) -> int:
    """The bits of the ``f32`` the tool's JSON text for it says: a number, or
    ``"inf"``, ``"-inf"``, ``"nan:0x…"``."""
    if isinstance(value, str):
        named = {"inf": 0x7F800000, "-inf": 0xFF800000}
        if value in named:
            return named[value]
        assert value.startswith("nan:0x"), value
        return int(value[len("nan:0x") :], 16)
    return f32_bits(f32(value))


def assert_same_item(ours: Any, theirs: Any, path: str = "") -> None:
    """`ours` (a Python item in the dict form) is the tool's line `theirs`:
    the same keys in the same order and the same values, a float compared as
    the ``f32`` the line's text reads back as (the item holds the f32's exact
    value, the line its shortest decimal)."""
    if isinstance(ours, float):
        assert json_f32_bits(theirs) == f32_bits(ours), (path, ours, theirs)
    elif isinstance(ours, dict):
        assert isinstance(theirs, dict) and list(ours) == list(theirs), (path, ours, theirs)
        for key in ours:
            assert_same_item(ours[key], theirs[key], f"{path}.{key}")
    elif isinstance(ours, list):
        assert isinstance(theirs, list) and len(ours) == len(theirs), (path, ours, theirs)
        for i, (a, b) in enumerate(zip(ours, theirs)):
            assert_same_item(a, b, f"{path}[{i}]")
    else:
        assert type(ours) is type(theirs) and ours == theirs, (path, ours, theirs)


@pytest.fixture(params=CASES, ids=[c.name for c in CASES])
def case(request: pytest.FixtureRequest) -> Case:
    return request.param
