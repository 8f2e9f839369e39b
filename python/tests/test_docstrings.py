"""The examples in the package's docstrings (most written in the Rust
sources) run and print what they show."""

from __future__ import annotations

import doctest
from typing import Any

import pytest

import robowire
from robowire import omnitiles, pixy2, telemetrix
from robowire.omnitiles import sdk

MODULES = [robowire, omnitiles, telemetrix, pixy2, sdk]


def examples() -> list[doctest.DocTest]:
    finder = doctest.DocTestFinder()
    found = []
    for module in MODULES:
        for name in dir(module):
            value: Any = getattr(module, name)
            if name.startswith("_") or not getattr(value, "__doc__", None):
                continue
            found += [t for t in finder.find(value, f"{module.__name__}.{name}", globs={}) if t.examples]
    return found


EXAMPLES = examples()


def test_the_docstrings_have_examples() -> None:
    names = {test.name for test in EXAMPLES}
    assert {"robowire.telemetrix.Decoder", "robowire.pixy2.Decoder", "robowire.omnitiles.encode"} <= names


@pytest.mark.parametrize("test", EXAMPLES, ids=lambda t: t.name)
def test_a_docstring_example_prints_what_it_shows(test: doctest.DocTest) -> None:
    runner = doctest.DocTestRunner(optionflags=doctest.ELLIPSIS)
    runner.run(test, out=lambda text: pytest.fail(text))
    assert runner.summarize(verbose=False).failed == 0
