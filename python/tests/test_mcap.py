"""The robowire tool's MCAP recordings, read with the ``mcap`` package: every
message is the JSON line the default format prints, on the channel of its
type, with a JSON Schema. Needs ``ROBOWIRE_CLI`` (CI sets it) and ``mcap``
(CI installs it)."""

from __future__ import annotations

import io
import json
import subprocess

import pytest

from conftest import CASES, Case, cli_binary, cli_lines

mcap_reader = pytest.importorskip("mcap.reader")


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
        assert channel.topic == f"/{kind}"
        assert channel.message_encoding == "json"
        assert schema.encoding == "jsonschema"
        assert json.loads(schema.data)["title"] == kind
    summary = reader.get_summary()
    assert summary is not None and summary.statistics.message_count == len(lines)
