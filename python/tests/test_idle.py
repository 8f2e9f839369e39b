"""The idle deadline: a frame only the next byte would decide (a 7-byte
OmniTiles frame that may begin a longer one) leaves once the line has been
silent for the gap, through deadline() and poll(), sans-IO."""

from __future__ import annotations

import time

from robowire import omnitiles, telemetrix

POS7 = bytes.fromhex("a5 60 d0 07 e8 03 22")
IDLE = 0.005


def test_a_short_frame_leaves_at_the_deadline() -> None:
    decoder = omnitiles.Decoder(source="tile")
    assert decoder.feed(POS7, t=1.0) == [] and decoder.buffered == 7
    assert decoder.deadline(IDLE) == 1.0 + IDLE
    assert decoder.poll(IDLE, now=1.004) == []
    (frame,) = decoder.poll(IDLE, now=1.0 + IDLE)
    assert (frame.layout, frame.m1_pos, frame.t) == ("pos7", 2000, 1.0)
    # Once per silence, and nothing is held any more.
    assert decoder.deadline(IDLE) is None and decoder.poll(IDLE, now=9.0) == []


def test_an_unfinished_frame_waits_for_its_rest() -> None:
    decoder = omnitiles.Decoder(source="tile")
    decoder.feed(POS7[:4], t=0.0)
    assert decoder.poll(IDLE, now=1.0) == [] and decoder.buffered == 4
    assert decoder.deadline(IDLE) is None  # no wake-up loop on a cut frame
    decoder.feed(POS7[4:], t=2.0)
    assert decoder.deadline(IDLE) == 2.0 + IDLE
    assert [f.layout for f in decoder.poll(IDLE, now=3.0)] == ["pos7"]


def test_no_deadline_when_nothing_is_held() -> None:
    decoder = telemetrix.Decoder(source="pico")
    assert len(decoder.feed(bytes.fromhex("05 0b 09 0a 00 77"), t=0.0)) == 1
    assert decoder.deadline(IDLE) is None and decoder.poll(IDLE, now=1.0) == []


def test_the_default_clock_is_monotonic() -> None:
    decoder = omnitiles.Decoder(source="tile")
    before = time.monotonic()
    decoder.feed(POS7)
    deadline = decoder.deadline(IDLE)
    assert deadline is not None and before + IDLE <= deadline <= time.monotonic() + IDLE
    assert decoder.poll(IDLE) == []  # too soon
    time.sleep(IDLE * 2)
    (frame,) = decoder.poll(IDLE)
    assert "t" not in frame  # no t= was given: the items carry none


def test_clear_and_finish_drop_the_deadline() -> None:
    for end in ("clear", "finish"):
        decoder = omnitiles.Decoder(source="tile")
        decoder.feed(POS7, t=0.0)
        getattr(decoder, end)()
        assert decoder.deadline(IDLE) is None
