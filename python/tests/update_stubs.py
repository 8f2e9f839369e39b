#!/usr/bin/env python3
"""Write the message classes of robowire/telemetrix.pyi and robowire/pixy2.pyi:
a class per ``type`` with a typed attribute per field, from what the decoders
give for a frame of every type (every_type.py) and the sample captures, and
the library's field table (its docs, names and optional fields).

    python python/tests/update_stubs.py

test_classes.py checks that the stubs are what this writes.
"""

from __future__ import annotations

import sys
from collections import defaultdict
from pathlib import Path
from typing import Any

sys.path.insert(0, str(Path(__file__).resolve().parent))

import conftest  # noqa: E402
from every_type import pixy2_items, telemetrix_items  # noqa: E402
from robowire import Item, pixy2, telemetrix  # noqa: E402

PACKAGE = Path(__file__).resolve().parents[1] / "robowire"
BEGIN = "# BEGIN message classes: written by python/tests/update_stubs.py\n"
END = "# END message classes\n"

# Fields of the item and not the frame: every class has them.
STREAM = ("offset", "len", "type")
# Optional in every message of the protocol (kinds.rs's common lists).
COMMON: dict[Any, dict[str, str]] = {
    telemetrix: {
        "t": "float",
        "quirk": "str",
        "also": "str",
    },
    pixy2: {"t": "float", "quirk": "str"},
}
COMMON_DOCS = {
    "t": "The receive time given to ``feed``, or ``None``.",
    "also": "The other direction's reading of a frame that reads both ways (``source=\"any\"``), or ``None``.",
}


def samples(module: Any) -> list[Any]:
    """Every item of the every-type corpus and of the sample captures."""
    if module is telemetrix:
        items = [item for _, item in telemetrix_items()]
    else:
        items = list(pixy2_items())
    for case in conftest.CASES:
        if case.make is module.Decoder:
            decoder = case.decoder(errors=False, typed=True)
            items += decoder.feed(case.input()) + decoder.finish()
    return items


def camel(name: str) -> str:
    return "".join(word[:1].upper() + word[1:] for word in name.split("_"))


def shape(value: Any) -> str:
    """The annotation of one value."""
    if isinstance(value, bool):
        return "bool"
    if isinstance(value, int):
        return "int"
    if isinstance(value, float):
        return "float"
    if isinstance(value, str):
        return "str"
    if isinstance(value, dict):
        return "dict[str, Any]"
    if isinstance(value, list):
        inner = union({shape(x) for x in value})
        return f"list[{inner}]" if inner else "list"
    raise TypeError(value)


def union(shapes: set[str]) -> str:
    """One annotation for several: lists of unknown elements give way to typed ones."""
    if any(s.startswith("list[") for s in shapes):
        shapes = shapes - {"list"}
    shapes = {"list[Any]" if s == "list" else s for s in shapes}
    if not shapes:
        return ""
    ordered = sorted(shapes)
    return ordered[0] if len(ordered) == 1 else f"Union[{', '.join(ordered)}]"


def doc_of(module: Any, kind: str, field: str) -> str:
    info = module.field_info(kind, field)
    if info is None:
        return COMMON_DOCS.get(field, "")
    text = info["doc"]
    if info["unit"]:
        text += f" Unit: {info['unit']}."
    return text


def classes(module: Any) -> str:
    names = module.field_info("ping" if module is telemetrix else "version", "type")["names"]
    fields: dict[str, dict[str, set[str]]] = defaultdict(lambda: defaultdict(set))
    present: dict[str, list[set[str]]] = defaultdict(list)
    for item in samples(module):
        present[item.type].append(set(item.keys()))
        for key, value in item.items():
            if key not in STREAM and key not in COMMON[module]:
                fields[item.type][key].add(shape(value))
    missing = [name for name in names if name not in present]
    assert not missing, f"no sample of {missing}"
    out = [BEGIN, "\n", "class Message(_Fields):\n"]
    out.append(
        '    """The base of every message class: a read-only mapping of the item\'s dict\n'
        "    whose fields read as typed attributes, those only some frames carry as\n"
        "    ``None`` when absent. At run time a subclass of :class:`robowire.Item`;\n"
        "    the stubs leave out ``Item``'s untyped attribute fallback, so that a\n"
        '    field the type does not have is an error."""\n\n'
    )
    out.append("    len: int\n    \"\"\"The frame's length in bytes.\"\"\"\n")
    for key, annotation in COMMON[module].items():
        out.append(f"    {key}: Optional[{annotation}]\n")
        out.append(f'    """{doc_of(module, "*", key)}"""\n')
    for name in names:
        always = set.intersection(*present[name])
        lines = [
            "",
            "@final",
            f"class {camel(name)}(Message):",
            f'    """A ``{name}`` message."""',
            "",
            f'    type: Literal["{name}"]',
        ]
        declared = [(k, union(v), k in always) for k, v in fields[name].items()]
        for key, annotation, required in declared:
            annotation = annotation or "Any"
            if not required:
                annotation = f"Optional[{annotation}]"
            lines.append(f"    {key}: {annotation}")
            doc = doc_of(module, name, key)
            if doc:
                doc = doc.replace('"""', "'''")
                lines.append(f'    """{doc}"""')
        out.append("\n".join(lines) + "\n")
    members = ", ".join(camel(name) for name in names)
    out.append(
        f"\nAnyMessage = Union[{members}]\n"
        '"""Every message class, as a union a ``type`` check narrows: what a decoder\'s items are."""\n'
    )
    out.append(END)
    return "".join(out)


def stub_path(module: Any) -> Path:
    return PACKAGE / f"{module.__name__.rsplit('.', 1)[1]}.pyi"


def updated(module: Any) -> str:
    """The stub file of ``module`` with its message classes as this writes them."""
    text = stub_path(module).read_text()
    if BEGIN in text:
        head, rest = text.split(BEGIN, 1)
        tail = rest.split(END, 1)[1]
    else:
        head, tail = text.rstrip("\n") + "\n\n", ""
    return head + classes(module) + tail


def main() -> int:
    for module in (telemetrix, pixy2):
        stub_path(module).write_text(updated(module))
    return 0


if __name__ == "__main__":
    assert issubclass(telemetrix.AnalogReport, Item)
    sys.exit(main())
