"""Receive times: ``feed(data, t=...)`` gives every item the call returns a
``t``, the first key of its dict form as in the tool's lines."""

from __future__ import annotations

import pickle
import time

import pytest

from robowire import omnitiles, pixy2, telemetrix

from conftest import DATA

POS7 = bytes.fromhex("a5 60 d0 07 e8 03 22")
M1_EXTEND = bytes.fromhex("a5 30 c8 f8")
BLE53_START = bytes.fromhex("a5 60")


@pytest.mark.parametrize("typed", [True, False])
def test_items_carry_the_time_of_the_chunk_that_completes_them(typed: bool) -> None:
    kwargs = {} if typed else {"typed": False}
    decoder = omnitiles.Decoder(layouts="pos7", errors=True, **kwargs)
    items = decoder.feed(POS7 + M1_EXTEND + b"\xa5\x30\xc8\x00" + POS7[:3], t=12.5)
    items += decoder.feed(POS7[3:], t=13.0)
    assert [(i["t"], i["offset"]) for i in items] == [(12.5, 0), (12.5, 7), (12.5, 11), (13.0, 15)]
    assert all(list(i.keys())[0] == "t" for i in items)  # first, as the tool writes it
    assert items[0] == {"t": 12.5, **omnitiles.Decoder(layouts="pos7", typed=False).feed(POS7)[0]}
    if typed:
        telemetry = items[0]
        assert telemetry.t == 12.5 and telemetry.to_dict()["t"] == 12.5 and "t" in telemetry
        assert items[1].t == 12.5 and items[2].t == 12.5  # a command, a rejection


def test_without_a_time_there_is_no_t() -> None:
    (t,) = omnitiles.Decoder(layouts="pos7").feed(POS7)
    assert t.t is None and "t" not in t and "t" not in t.to_dict() and list(t)[0] == "offset"
    (d,) = omnitiles.Decoder(layouts="pos7", typed=False).feed(POS7)
    assert "t" not in d


def test_settle_finish_and_datagrams_take_a_time() -> None:
    decoder = omnitiles.Decoder(source="tile")
    assert decoder.feed(POS7, t=1.0) == []  # a 7-byte frame may start a longer one
    (t,) = decoder.settle(t=2.0)
    assert t.t == 2.0
    decoder.feed(POS7, t=3.0)
    assert [i.t for i in decoder.finish(t=4.0)] == [4.0]
    (d,) = omnitiles.DatagramDecoder(source="tile").decode(POS7, t=5.0)
    assert d.t == 5.0
    reports = telemetrix.Decoder(source="pico").feed((DATA / "telemetrix_reports.bin").read_bytes(), t=6.0)
    assert reports and all(r.t == 6.0 and r.to_dict()["t"] == 6.0 for r in reports)


def test_times_survive_pickle_and_equality_counts_them() -> None:
    decoder = omnitiles.Decoder(layouts="pos7")
    (a,) = decoder.feed(POS7, t=1.0)
    again = pickle.loads(pickle.dumps(a))
    assert again == a and again.t == 1.0 and hash(again) == hash(a)
    (other,) = omnitiles.Decoder(layouts="pos7").feed(POS7, t=2.0)
    assert other != a  # same frame, another receive time


def test_items_with_a_time_encode_to_their_frame() -> None:
    items = omnitiles.Decoder().feed(M1_EXTEND + POS7, t=9.0) + omnitiles.Decoder().finish()
    (command,) = [i for i in items if i["type"] == "m1_extend"]
    assert omnitiles.encode(command) == M1_EXTEND
    assert omnitiles.encode({"t": 9.0, "type": "m1_extend", "speed": 200}) == M1_EXTEND
    decoder = omnitiles.Decoder(layouts="pos7")
    (telemetry,) = decoder.feed(POS7, t=9.0)
    assert omnitiles.encode(telemetry) == POS7


class Ticks:
    """A clock that says 10.0, 11.0, ... and counts its reads."""

    def __init__(self) -> None:
        self.reads = 0

    def __call__(self) -> float:
        self.reads += 1
        return 9.0 + self.reads


def test_a_clock_stamps_every_call_without_a_time() -> None:
    clock = Ticks()
    decoder = telemetrix.Decoder(source="pico", clock=clock)
    reports = (DATA / "telemetrix_reports.bin").read_bytes()
    first = decoder.feed(reports)
    assert first and {r.t for r in first} == {10.0} and clock.reads == 1  # once per call
    assert {r.t for r in decoder.feed(reports)} == {11.0}
    assert {r.t for r in decoder.feed(reports, t=99.0)} == {99.0} and clock.reads == 2  # t wins
    assert decoder.feed(b"") == [] and clock.reads == 3
    (d,) = omnitiles.DatagramDecoder(source="tile", clock=Ticks()).decode(POS7)
    assert d.t == 10.0
    (p,) = pixy2.Decoder(source="device", clock=Ticks(), typed=False).feed(bytes.fromhex("af c1 21 00 00 00"))
    assert list(p.items())[0] == ("t", 10.0)


def test_a_settled_frame_has_the_time_its_bytes_came() -> None:
    for given in ({"t": 3.0}, {}):
        clock = Ticks()
        decoder = omnitiles.Decoder(source="tile", clock=clock)
        assert decoder.feed(POS7, **given) == []
        expected = given.get("t", 10.0)
        (t,) = decoder.settle()
        assert t.t == expected
        decoder.clear()
        decoder.feed(POS7, **given)
        assert [i.t for i in decoder.finish()] == [given.get("t", 11.0)]
    # And without a clock, from the feed's t (it had none before).
    decoder = omnitiles.Decoder(source="tile")
    decoder.feed(POS7, t=5.0)
    assert [i.t for i in decoder.settle()] == [5.0]


def test_poll_reads_the_clock() -> None:
    now = [100.0]
    decoder = omnitiles.Decoder(source="tile", clock=lambda: now[0])
    decoder.feed(POS7)
    assert decoder.deadline(0.005) == 100.005
    assert decoder.poll(0.005) == []
    now[0] = 100.01
    (frame,) = decoder.poll(0.005)
    assert frame.t == 100.0


def test_a_clock_must_be_callable_and_shows_in_repr() -> None:
    with pytest.raises(TypeError, match="clock must be a callable"):
        omnitiles.Decoder(clock=1.5)  # type: ignore[call-overload]
    assert repr(telemetrix.Decoder(clock=time.monotonic)) == (
        "robowire.telemetrix.Decoder(source=\"any\", dialect=\"mirte13\", clock=<built-in function monotonic>)"
    )
    assert repr(omnitiles.DatagramDecoder(source="tile", layouts=("pos7",), clock=time.time)).endswith(
        "layouts=('pos7',), clock=<built-in function time>)"
    )
