"""Receive times: ``feed(data, t=...)`` gives every item the call returns a
``t``, the first key of its dict form as in the tool's lines."""

from __future__ import annotations

import pickle

import pytest

from robowire import omnitiles, telemetrix

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
