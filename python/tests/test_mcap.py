"""The robowire tool's MCAP recordings, read with the ``mcap`` package: every
message is the JSON line the default format prints, on the channel of its
type, with a JSON Schema. Needs ``ROBOWIRE_CLI`` (CI sets it) and ``mcap``
(CI installs it)."""

from __future__ import annotations

import io
import json
import subprocess

import pytest

from conftest import CASES, DATA, Case, cli_binary, cli_lines

mcap_reader = pytest.importorskip("mcap.reader")
jsonschema = pytest.importorskip("jsonschema")


@pytest.mark.skipif(cli_binary() is None, reason="ROBOWIRE_CLI does not name the robowire tool")
@pytest.mark.parametrize("case", CASES, ids=lambda case: case.name)
def test_mcap_messages_are_the_json_lines(case: Case) -> None:
    binary = cli_binary()
    assert binary is not None
    run = subprocess.run([binary, *case.cli_args(), "--format", "mcap"], capture_output=True, check=True)
    reader = mcap_reader.make_reader(io.BytesIO(run.stdout))
    messages = list(reader.iter_messages())
    lines = cli_lines(case)
    assert len(messages) == len(lines)
    for (schema, channel, message), line in zip(messages, lines):
        assert json.loads(message.data) == line
        kind = line.get("type", "rejected")
        protocol = case.cli_args()[1]
        assert channel.topic == f"/{protocol}/{kind}" or channel.topic.startswith(f"/{protocol}/{kind}/")
        assert channel.message_encoding == "json"
        assert schema.encoding == "jsonschema"
        assert json.loads(schema.data)["title"] == kind
    summary = reader.get_summary()
    assert summary is not None and summary.statistics.message_count == len(lines)


@pytest.mark.skipif(cli_binary() is None, reason="ROBOWIRE_CLI does not name the robowire tool")
@pytest.mark.parametrize("case", CASES, ids=lambda case: case.name)
def test_every_message_is_valid_under_its_channel_schema(case: Case) -> None:
    """Each channel's JSON Schema is a valid 2020-12 schema with exact types
    (no leaf is typed loosely), and every message of the capture, with times
    or without, validates against it."""
    binary = cli_binary()
    assert binary is not None
    for timed in ([], ["--timestamps"]):
        args = [binary, *case.cli_args(), *timed, "--format", "mcap"]
        run = subprocess.run(args, capture_output=True, check=True)
        reader = mcap_reader.make_reader(io.BytesIO(run.stdout))
        validators = {}
        count = 0
        for schema, channel, message in reader.iter_messages():
            if schema.id not in validators:
                document = json.loads(schema.data)
                jsonschema.Draft202012Validator.check_schema(document)
                tag = "error" if channel.topic.endswith("/rejected") else "type"
                assert tag in document["required"] and tag in document["properties"]
                validators[schema.id] = jsonschema.Draft202012Validator(document)
            errors = [e.message for e in validators[schema.id].iter_errors(json.loads(message.data))]
            assert not errors, (channel.topic, message.data, errors)
            count += 1
        assert count == len(cli_lines(case))


def test_schema_leaves_say_their_type_and_unit() -> None:
    """The telemetry schema is exact: integers with the wire's range, null
    only for "no reading", names as enums, units on the fields that have one."""
    binary = cli_binary()
    if binary is None:
        pytest.skip("ROBOWIRE_CLI does not name the robowire tool")
    capture = str(DATA / "ble_telemetry.bin")
    run = subprocess.run([binary, "decode", "omnitiles", capture, "--format", "mcap"], capture_output=True, check=True)
    reader = mcap_reader.make_reader(io.BytesIO(run.stdout))
    (schema,) = reader.get_summary().schemas.values()
    document = json.loads(schema.data)
    properties = document["properties"]
    assert properties["type"] == {"const": "telemetry", "description": "The message type."}
    assert properties["layout"]["enum"] == ["pos7", "uwb15", "uwbtof17", "spi45", "ble53"]
    assert properties["m1_pos"]["type"] == ["integer", "null"]
    assert (properties["m1_pos"]["minimum"], properties["m1_pos"]["maximum"]) == (0, 65534)
    assert properties["m1_pos"]["unit"] == "ADC counts"
    assert properties["uwb"]["items"]["unit"] == "mm"
    assert properties["imu"]["properties"]["az"]["unit"] == "m/s²"
    assert properties["imu"]["required"] == ["ax", "ay", "az", "gx", "gy", "gz"]
    assert properties["m1_adcs"]["items"]["type"] == "integer"
    assert "null" not in json.dumps(properties["m1_adcs"])
    assert set(document["required"]) == {"offset", "len", "type", "layout", "m1_pos", "m2_pos"}
