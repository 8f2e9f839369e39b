"""The type stubs, as mypy --strict and pyright --strict read them: the
examples and tests/typing/types_hold.py pass; every line of
tests/typing/mistakes.py marked ``# mistake`` is an error, and no other.
Both checkers are in CI's venv (skipped where they are not installed)."""

from __future__ import annotations

import json
import re
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

PACKAGE = Path(__file__).resolve().parents[1]
TYPING = PACKAGE / "tests" / "typing"
PASSING = [PACKAGE / "examples", TYPING / "types_hold.py"]
MISTAKES = TYPING / "mistakes.py"


def marked_lines() -> set[int]:
    lines = MISTAKES.read_text().splitlines()
    return {n for n, line in enumerate(lines, 1) if "# mistake:" in line}


def mypy(*paths: Path) -> tuple[int, set[int]]:
    pytest.importorskip("mypy")
    run = subprocess.run(
        [sys.executable, "-m", "mypy", "--strict", "--no-incremental", "--python-executable", sys.executable]
        # Deprecated overloads (typed=True, lazy=True) are errors, as in pyright --strict.
        + ["--enable-error-code", "deprecated"]
        + [str(p) for p in paths],
        capture_output=True,
        text=True,
        cwd=TYPING,  # not python/: its robowire/ has no compiled core
    )
    errors = {int(m.group(1)) for m in re.finditer(r"^[^:\n]+:(\d+): error:", run.stdout, re.M)}
    print(run.stdout)
    return run.returncode, errors


def pyright(*paths: Path) -> tuple[int, set[int]]:
    exe = shutil.which("pyright", path=str(Path(sys.executable).parent))
    if exe is None:
        pytest.skip("pyright is not installed")
    run = subprocess.run(
        [exe, "-p", str(PACKAGE / "pyrightconfig.json"), "--pythonpath", sys.executable, "--outputjson"]
        + [str(p) for p in paths],
        capture_output=True,
        text=True,
        cwd=TYPING,
    )
    report = json.loads(run.stdout)
    errors = {d["range"]["start"]["line"] + 1 for d in report["generalDiagnostics"] if d["severity"] == "error"}
    print(json.dumps(report["generalDiagnostics"], indent=1))
    return run.returncode, errors


@pytest.mark.parametrize("checker", [mypy, pyright])
def test_examples_and_promises_type_check(checker: object) -> None:
    status, errors = checker(*PASSING)  # type: ignore[operator]
    assert (status, errors) == (0, set())


@pytest.mark.parametrize("checker", [mypy, pyright])
def test_mistakes_are_errors(checker: object) -> None:
    _, errors = checker(MISTAKES)  # type: ignore[operator]
    assert errors == marked_lines()


def test_stubs_import_only_the_standard_library() -> None:
    """typing_extensions is no dependency of the package, so no stub imports it."""
    for stub in (PACKAGE / "robowire").glob("*.pyi"):
        imports = re.findall(r"^(?:from|import) (\w+)", stub.read_text(), re.M)
        assert "typing_extensions" not in imports, stub.name


def test_decoders_subscript_at_run_time() -> None:
    """``Decoder[Telemetry]`` in an annotation evaluated at run time (no
    ``from __future__ import annotations``) is the class with its item type."""
    import typing

    import robowire
    from robowire import omnitiles, pixy2, telemetrix

    for cls in (omnitiles.Decoder, omnitiles.DatagramDecoder, pixy2.Decoder, telemetrix.Decoder):
        alias = cls[robowire.Item]
        assert typing.get_origin(alias) is cls
        assert typing.get_args(alias) == (robowire.Item,)
    assert isinstance(omnitiles.Decoder().stats, robowire.Stats)
