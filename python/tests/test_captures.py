"""The sample captures in tests/data decode to exactly the tool's lines
(floats compared as the f32 they stand for), however the bytes are split,
as dicts or as lazy items."""

from __future__ import annotations

import json

import pytest

from conftest import CASES, GOLDEN, Case, assert_same_item, cli_binary, cli_lines, decode_all


def test_capture_gives_the_tools_lines(case: Case) -> None:
    expected = cli_lines(case)
    got = decode_all(case)
    assert len(got) == len(expected)
    for ours, theirs in zip(got, expected):
        # Same keys in the same order, as the tool writes them; floats are
        # the same f32.
        assert_same_item(ours, theirs)


def test_capture_has_frames(case: Case) -> None:
    frames = [item for item in decode_all(case) if "type" in item]
    assert len(frames) >= 1


@pytest.mark.parametrize("chunk", [1, 2, 3, 7, 53, 64, 4096])
def test_chunking_does_not_change_results(case: Case, chunk: int) -> None:
    if case.datagrams:
        pytest.skip("datagrams are decoded whole")
    assert decode_all(case, chunk) == decode_all(case)


def test_without_errors_only_frames(case: Case) -> None:
    expected = [item for item in cli_lines(case) if "type" in item]
    got = decode_all(case, errors=False)
    assert len(got) == len(expected)
    for ours, theirs in zip(got, expected):
        assert_same_item(ours, theirs)


def test_lazy_items_equal_the_dicts(case: Case) -> None:
    lazy = decode_all(case, lazy=True)
    eager = decode_all(case)
    assert lazy == eager
    assert [item.to_dict() for item in lazy] == eager
    assert [item.offset for item in lazy] == [item["offset"] for item in eager]


def test_stats_add_up(case: Case) -> None:
    decoder = case.decoder()
    if case.datagrams:
        items = [i for d in case.datagram_list() for i in decoder.decode(d)]
        buffered = 0
    else:
        data = case.input()
        items = decoder.feed(data[: len(data) // 2])
        buffered = decoder.buffered
        mid = decoder.stats
        assert mid["bytes"] == mid["frame_bytes"] + mid["skipped"] + buffered
        items += decoder.feed(data[len(data) // 2 :]) + decoder.finish()
        buffered = decoder.buffered
        assert buffered == 0
    stats = decoder.stats
    assert stats["bytes"] == stats["frame_bytes"] + stats["skipped"] + buffered
    frames = [i for i in items if "type" in i]
    assert stats["frames"] == len(frames) + stats["malformed"]


@pytest.mark.skipif(cli_binary() is None, reason="ROBOWIRE_CLI does not name the robowire tool")
def test_golden_files_are_the_tools_lines(case: Case) -> None:
    golden = [json.loads(line) for line in (GOLDEN / f"{case.name}.jsonl").read_text().splitlines()]
    assert golden == cli_lines(case)


def test_every_case_has_a_golden_file() -> None:
    for case in CASES:
        assert (GOLDEN / f"{case.name}.jsonl").is_file(), case.name
