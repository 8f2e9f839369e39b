"""A frame of every message ``type``: the cases of the Rust schema tests
(tests/schema_telemetrix.rs and tests/schema_pixy2.rs, which check that
their cases cover every type), decoded here by the Python decoders.

Read from the Rust sources so that the two suites share one corpus.
"""

from __future__ import annotations

import re
from collections.abc import Iterator
from pathlib import Path
from typing import Any

from robowire import pixy2, telemetrix

# The report that lets a lenient decoder take an unknown one before it.
FOLLOWER = bytes.fromhex("04 03 1a 04 c9")
ROOT = Path(__file__).resolve().parents[2]
DIALECTS = {"M13": "mirte13", "M12": "mirte12", "U11": "upstream11"}

# (dialect, HOST | PICO, "hex", r#"line"#) and ("hex", r#"line"#) tuples.
TELEMETRIX_CASE = re.compile(
    r'\(\s*(M13|M12|U11),\s*(HOST|PICO),\s*"([0-9a-fA-F ]*)",\s*r#"\{"type":"(\w+)"'
)
PIXY2_CASE = re.compile(r'\(\s*"([0-9a-fA-F ]+)",\s*r#"\{"type"')


def telemetrix_items() -> Iterator[tuple[str, Any]]:
    """``(dialect, item)`` for every Telemetrix case, each decoded alone."""
    text = (ROOT / "tests" / "schema_telemetrix.rs").read_text()
    for dialect, side, frame, kind in TELEMETRIX_CASE.findall(text):
        source = "host" if side == "HOST" else "pico"
        name = DIALECTS[dialect]
        data = bytes.fromhex(frame)
        # An unknown report id is taken only leniently, before a valid report.
        lenient = kind == "unknown_report"
        decoder = telemetrix.Decoder(source=source, dialect=name, lenient=lenient)
        items = decoder.feed(data + (FOLLOWER if lenient else b"")) + decoder.finish()
        assert len(items) == 1 + lenient and items[0].type == kind, (frame, items)
        yield name, items[0]


def pixy2_items() -> Iterator[Any]:
    """The item of every Pixy2 case."""
    text = (ROOT / "tests" / "schema_pixy2.rs").read_text()
    for frame in PIXY2_CASE.findall(text):
        decoder = pixy2.Decoder(source="any")
        items = decoder.feed(bytes.fromhex(frame)) + decoder.finish()
        assert len(items) == 1, (frame, items)
        yield items[0]
