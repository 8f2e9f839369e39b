"""feed_array: the frames of a chunk as numpy structured arrays, one per
message kind, with the same values as the items and independent of chunking."""

from __future__ import annotations

import math
from typing import Any

import pytest

np = pytest.importorskip("numpy")

from robowire import omnitiles, pixy2, telemetrix  # noqa: E402

from conftest import CASES, Case, decode_all, f32_bits  # noqa: E402

OMNI_STREAMS = [c for c in CASES if c.make is omnitiles.Decoder]
NO_READING = 0xFFFF


def feed_arrays(case: Case, chunk: int | None = None) -> dict[str, Any]:
    """`case`'s capture through feed_array, `chunk` bytes at a time, joined."""
    decoder = case.decoder(errors=False)
    data = case.input()
    step = chunk or len(data)
    parts: dict[str, list[Any]] = {}
    for start in range(0, len(data), step):
        for kind, array in decoder.feed_array(data[start : start + step]).items():
            parts.setdefault(kind, []).append(array)
    return {kind: np.concatenate(arrays) for kind, arrays in parts.items()}


def row_of(item: dict[str, Any]) -> dict[str, Any]:
    """The record feed_array gives for a dict-form item."""
    row = {k: v for k, v in item.items() if k not in ("type", "layout", "uwb", "imu", "m1_adcs", "m2_adcs")}
    if item["type"] != "telemetry":
        return row
    for key in ("m1_pos", "m2_pos", "tof"):
        row[key] = NO_READING if row.get(key) is None else row[key]
    for key, n in (("uwb", 4), ("m1_adcs", 4), ("m2_adcs", 2)):
        values = item.get(key) or [None] * n
        for i, v in enumerate(values):
            row[f"{key}_{i}"] = NO_READING if v is None else v
    imu = item.get("imu") or {k: math.nan for k in ("ax", "ay", "az", "gx", "gy", "gz")}
    row.update(imu)
    return row


@pytest.mark.parametrize("case", OMNI_STREAMS, ids=[c.name for c in OMNI_STREAMS])
def test_arrays_hold_the_items_values(case: Case) -> None:
    items = decode_all(case, errors=False)
    arrays = feed_arrays(case)
    assert sum(len(a) for a in arrays.values()) == len(items) > 0
    seen = {kind: 0 for kind in arrays}
    for item in items:
        array = arrays[item["type"]]
        record = array[seen[item["type"]]]
        seen[item["type"]] += 1
        expected = row_of(item)
        assert list(array.dtype.names) == list(expected) or set(array.dtype.names) == set(expected)
        for name, value in expected.items():
            got = record[name].item()
            if isinstance(value, float):
                assert f32_bits(got) == f32_bits(value) or (math.isnan(got) and math.isnan(value)), name
            else:
                assert got == value, name


@pytest.mark.parametrize("case", OMNI_STREAMS, ids=[c.name for c in OMNI_STREAMS])
@pytest.mark.parametrize("chunk", [1, 7, 53, 4096])
def test_arrays_do_not_depend_on_chunking(case: Case, chunk: int) -> None:
    whole = feed_arrays(case)
    pieces = feed_arrays(case, chunk)
    assert whole.keys() == pieces.keys()
    for kind in whole:
        assert whole[kind].tobytes() == pieces[kind].tobytes(), kind


def test_arrays_are_flat_records_for_pandas() -> None:
    arrays = feed_arrays(CASES[0])
    telemetry = arrays["telemetry"]
    assert telemetry.ndim == 1
    assert all(telemetry.dtype[name].shape == () for name in telemetry.dtype.names)
    assert telemetry.dtype["ax"] == np.dtype("<f4") and telemetry.dtype["m1_pos"] == np.dtype("<u2")
    pandas = pytest.importorskip("pandas")
    frame = pandas.DataFrame(telemetry)
    assert list(frame.columns) == list(telemetry.dtype.names) and len(frame) == len(telemetry)


def test_not_carried_groups_are_sentinels() -> None:
    (pos7,) = omnitiles.Decoder(source="tile", layouts="pos7").feed_array(bytes.fromhex("a5 60 d0 07 ff ff 35")).values()
    record = pos7[0]
    assert (record["len"], record["m1_pos"], record["m2_pos"], record["uwb_0"], record["tof"]) == (7, 2000, 0xFFFF, 0xFFFF, 0xFFFF)
    assert math.isnan(record["az"])


def test_rejections_are_counted_and_frames_kept() -> None:
    decoder = omnitiles.Decoder(source="host", errors=True)
    arrays = decoder.feed_array(bytes.fromhex("a5 30 c8 f7 a5 50 50 a5 30"))
    assert list(arrays) == ["ping"] and arrays["ping"]["offset"].tolist() == [4]
    assert decoder.stats["checksum_failures"] == 1
    assert decoder.feed_array(bytes.fromhex("c8 f8"))["m1_extend"][0].tolist() == (7, 4, 200)
    assert decoder.feed_array(b"") == {}


OTHER_STREAMS = [c for c in CASES if c.make is not omnitiles.Decoder and not c.datagrams]
# The lists whose elements are rows of their own table (the tool's CSV
# tables, FieldInfo::rows): by message type, the list's path and its table.
ROW_LISTS = {
    "blocks": [("blocks", "blocks")],
    "features": [
        ("sections.*.vectors", "features_vectors"),
        ("sections.*.intersections", "features_intersections"),
        ("sections.*.barcodes", "features_barcodes"),
    ],
}


def leaves(value: Any, path: str = "") -> list[tuple[str, Any]]:
    """A dict-form value's leaves by path (`reading.volts`, `data.3`)."""
    if isinstance(value, dict):
        return [leaf for k, v in value.items() for leaf in leaves(v, f"{path}.{k}" if path else k)]
    if isinstance(value, list):
        return [leaf for i, v in enumerate(value) for leaf in leaves(v, f"{path}.{i}")]
    return [(path, value)]


def expected_rows(items: list[dict[str, Any]]) -> dict[str, list[dict[str, Any]]]:
    """The rows each table should hold for `items` (dict form), by table."""
    tables: dict[str, list[dict[str, Any]]] = {}
    for index, item in enumerate(items):
        # The type names the table: it is no column.
        cells = [(p, v) for p, v in leaves(item) if p != "type"]
        lists = ROW_LISTS.get(item["type"])
        if lists is None:
            tables.setdefault(item["type"], []).append(dict(cells))
            continue
        shared = {"frame": index, **{p: v for p, v in cells if not p.startswith(("blocks.", "sections."))}}
        for pattern, table in lists:
            head, _, tail = pattern.partition("*")
            elements: dict[str, dict[str, Any]] = {}
            for p, v in cells:
                # p: sections.<s>.vectors.<i>.<field> or blocks.<i>.<field>
                parts = p.split(".")
                want = pattern.split(".")
                if len(parts) <= len(want) + 1:
                    continue
                if all(w == h or (w == "*" and h.isdigit()) for w, h in zip(want, parts)):
                    element = ".".join(parts[: len(want) + 1])
                    elements.setdefault(element, {})[".".join(parts[len(want) + 1 :])] = v
            rows = tables.setdefault(table, [])
            for position, fields in enumerate(elements.values()):
                rows.append({**shared, "element": position, **fields})
            if not elements:
                rows.append({**shared, "element": None})
    return tables


def cell_of(record: Any, mask: Any, names: tuple[str, ...], path: str, value: Any) -> tuple[Any, bool]:
    """The value and mask of `path` in a masked record for an expected `value`
    (a name of a number-or-name field is in the `.name` column)."""
    column = f"{path}.name" if isinstance(value, str) and f"{path}.name" in names else path
    return record[column], bool(mask[column])


@pytest.mark.parametrize("case", OTHER_STREAMS, ids=[c.name for c in OTHER_STREAMS])
def test_telemetrix_and_pixy2_arrays_hold_the_items_values(case: Case) -> None:
    # feed_array has no finish: the items of the same feed are the truth.
    items = case.decoder(errors=False).feed(case.input())
    arrays = case.decoder(errors=False).feed_array(case.input(), masked=True)
    expected = expected_rows(items)
    assert set(arrays) == set(expected)
    for table, rows in expected.items():
        array = arrays[table]
        names = array.dtype.names
        assert len(array) == len(rows), table
        for k, row in enumerate(rows):
            record, mask = array.data[k], array.mask[k]
            for path, value in row.items():
                got, masked = cell_of(record, mask, names, path, value)
                if value is None:
                    assert masked, (table, k, path)
                    continue
                assert not masked, (table, k, path)
                if isinstance(got, str) and not isinstance(value, str):
                    assert got == str(value), (table, k, path)  # a type byte's number
                elif isinstance(value, float):
                    assert got == value or (math.isnan(got) and math.isnan(value)), (table, k, path)
                else:
                    assert got == value, (table, k, path, got, value)
            # Every other cell is one this frame does not have: masked.
            given = {f"{p}.name" if isinstance(v, str) and f"{p}.name" in names else p for p, v in row.items()}
            assert all(mask[n] for n in names if n not in given), (table, k)


def present_cells(array: Any) -> list[dict[str, Any]]:
    """Each row of a masked table as {column: value} of its unmasked cells
    (NaN as a string, to compare equal)."""
    names = array.dtype.names
    rows = []
    for record, mask in zip(array.data.tolist(), array.mask.tolist()):
        rows.append({n: ("nan" if v != v else v) for n, v, m in zip(names, record, mask) if not m})
    return rows


@pytest.mark.parametrize("case", OTHER_STREAMS, ids=[c.name for c in OTHER_STREAMS])
@pytest.mark.parametrize("chunk", [1, 7, 4096])
def test_telemetrix_and_pixy2_arrays_do_not_depend_on_chunking(case: Case, chunk: int) -> None:
    whole = case.decoder(errors=False).feed_array(case.input(), masked=True)
    decoder = case.decoder(errors=False)
    data = case.input()
    parts: dict[str, list[dict[str, Any]]] = {}
    for start in range(0, len(data), chunk):
        for kind, array in decoder.feed_array(data[start : start + chunk], masked=True).items():
            parts.setdefault(kind, []).extend(present_cells(array))
    assert {kind: present_cells(array) for kind, array in whole.items()} == parts


def test_number_or_name_fields_stay_numeric() -> None:
    # A sonar's cm is a number or a name ("out_of_range"): a u1 column with
    # the names beside it, so mean() is over the distances.
    frames = bytes.fromhex("05 0b 09 0a 00 77") + bytes.fromhex("05 0b 09 0a ff fd")
    items = telemetrix.Decoder(source="pico", typed=False).feed(frames)
    sonar = telemetrix.Decoder(source="pico").feed_array(frames, masked=True)["sonar_distance"]
    assert [i["cm"] for i in items] == [119, sonar["cm.name"][1]]
    assert sonar["cm"].dtype.kind in "ui" and sonar["cm"].mean() == 119
    assert sonar["cm.name"].mask.tolist() == [True, False]
    raw = telemetrix.Decoder(source="pico").feed_array(frames)["sonar_distance"]
    assert raw["cm"].tolist() == [119, np.iinfo(raw["cm"].dtype).max]


def test_type_bytes_are_text_in_every_call() -> None:
    # A sensor type is a name, or its number where it names none: a text
    # column, whichever the call holds.
    known, unknown = bytes.fromhex("04 15 00 00 00"), bytes.fromhex("04 15 00 63 01")
    decoder = telemetrix.Decoder(source="pico")
    for frame, text in ((known, "gps"), (unknown, "99"), (known + unknown, "gps")):
        column = decoder.feed_array(frame)["sensor_main_report"]["sensor_type"]
        assert column.dtype.kind == "U" and column[0] == text


def test_pixy2_blocks_are_rows_with_their_frame() -> None:
    capture = next(c for c in CASES if c.name == "pixy2_any").input()
    items = [i for i in pixy2.Decoder(typed=False).feed(capture)]
    blocks = pixy2.Decoder().feed_array(capture)["blocks"]
    frames = [k for k, item in enumerate(items) if item["type"] == "blocks"]
    assert sorted(set(blocks["frame"].tolist())) == frames
    first = items[frames[0]]
    rows = blocks[blocks["frame"] == frames[0]]
    assert rows["x"].tolist()[: len(first["blocks"])] == [b["x"] for b in first["blocks"]]
    assert (rows["offset"] == first["offset"]).all()


@pytest.mark.parametrize("bad", ["a5 50 50", 3, None])
def test_feed_array_refuses_non_bytes(bad: Any) -> None:
    decoder = omnitiles.Decoder()
    with pytest.raises(TypeError, match="bytes"):
        decoder.feed_array(bad)
    assert decoder.stats["bytes"] == 0


@pytest.mark.parametrize("case", OMNI_STREAMS, ids=[c.name for c in OMNI_STREAMS])
def test_masked_arrays_mask_exactly_the_cells_without_a_reading(case: Case) -> None:
    """masked=True: a cell is masked exactly where the item has no value
    (None, or a group its layout does not carry); the data is unchanged."""
    decoder = case.decoder(errors=False, typed=False)
    data = case.input()
    masked = decoder.feed_array(data, masked=True)
    plain = feed_arrays(case)
    items = [i for i in decode_all(case, errors=False) if i["type"] == "telemetry"]
    assert masked.keys() == plain.keys()
    for kind, array in masked.items():
        assert isinstance(array, np.ma.MaskedArray)
        assert array.data.tobytes() == plain[kind].tobytes()
    if "telemetry" not in masked:
        return
    table = masked["telemetry"]
    for item, record_mask in zip(items, np.ma.getmaskarray(table)):
        uwb = item.get("uwb") or [None] * 4
        imu = item.get("imu")
        expected = {
            "m1_pos": item["m1_pos"] is None,
            "m2_pos": item["m2_pos"] is None,
            **{f"uwb_{i}": v is None for i, v in enumerate(uwb)},
            "tof": item.get("tof") is None,
            **{k: imu is None for k in ("ax", "ay", "az", "gx", "gy", "gz")},
            **{f"m1_adcs_{i}": "m1_adcs" not in item for i in range(4)},
            **{f"m2_adcs_{i}": "m2_adcs" not in item for i in range(2)},
            "offset": False,
            "len": False,
        }
        assert {name: bool(record_mask[name]) for name in table.dtype.names} == expected


def test_masked_means_average_the_readings_only() -> None:
    """The sample capture's fourth UWB range is often no reading: the
    sentinel table's mean is 65535's, the masked one's the readings'."""
    from conftest import DATA

    data = (DATA / "ble_telemetry.bin").read_bytes()
    sentinel = omnitiles.Decoder(source="tile").feed_array(data)["telemetry"]["uwb_3"]
    masked = omnitiles.Decoder(source="tile").feed_array(data, masked=True)["telemetry"]["uwb_3"]
    readings = [t.uwb[3] for t in omnitiles.Decoder(source="tile").feed(data) if t.uwb and t.uwb[3] is not None]
    assert 0 < len(readings) < len(sentinel)
    assert sentinel.mean() > 20_000
    assert masked.mean() == pytest.approx(sum(readings) / len(readings))
    assert masked.count() == len(readings)
