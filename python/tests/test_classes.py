"""A class per Telemetrix and Pixy2 message ``type``: every type has one,
every decoded frame comes out in its own, and the stubs' typed fields
(written by update_stubs.py) hold for a frame of every type and for every
item of the sample captures."""

from __future__ import annotations

import ast
import copy
import pickle
from typing import Any

import pytest

import robowire
from robowire import pixy2, telemetrix

import update_stubs
from update_stubs import camel, samples, stub_path

MODULES = [telemetrix, pixy2]


def type_names(module: Any) -> list[str]:
    return module.field_info("ping" if module is telemetrix else "version", "type")["names"]


def stub_fields(module: Any) -> dict[str, dict[str, ast.expr]]:
    """Each class of ``module``'s stub: its annotated attributes (the base
    ``Message``'s included)."""
    tree = ast.parse(stub_path(module).read_text())
    classes: dict[str, dict[str, ast.expr]] = {}
    for node in tree.body:
        if isinstance(node, ast.ClassDef):
            fields = {
                n.target.id: n.annotation
                for n in node.body
                if isinstance(n, ast.AnnAssign) and isinstance(n.target, ast.Name)
            }
            for base in node.bases:
                if isinstance(base, ast.Name) and base.id in classes:
                    fields = {**classes[base.id], **fields}
            classes[node.name] = fields
    return classes


def holds(value: Any, annotation: ast.expr) -> bool:
    """Whether ``value`` is of the stub's type ``annotation``."""
    if isinstance(annotation, ast.Name):
        simple = {"int": int, "float": float, "str": str, "bool": bool}
        if annotation.id == "Any":
            return True
        if annotation.id == "int":
            return isinstance(value, int) and not isinstance(value, bool)
        return isinstance(value, simple[annotation.id])
    assert isinstance(annotation, ast.Subscript), ast.dump(annotation)
    head = annotation.value
    assert isinstance(head, ast.Name)
    args = annotation.slice.elts if isinstance(annotation.slice, ast.Tuple) else [annotation.slice]
    if head.id == "Optional":
        return value is None or holds(value, args[0])
    if head.id == "Union":
        return any(holds(value, arg) for arg in args)
    if head.id == "Literal":
        return any(value == arg.value for arg in args if isinstance(arg, ast.Constant))
    if head.id == "list":
        return isinstance(value, list) and all(holds(x, args[0]) for x in value)
    if head.id == "dict":
        return isinstance(value, dict) and all(holds(k, args[0]) and holds(v, args[1]) for k, v in value.items())
    raise AssertionError(ast.dump(annotation))


@pytest.mark.parametrize("module", MODULES, ids=lambda m: m.__name__)
def test_every_type_has_its_class(module: Any) -> None:
    names = type_names(module)
    assert len(names) == {telemetrix: 62, pixy2: 22}[module]
    for name in names:
        cls = getattr(module, camel(name))
        assert issubclass(cls, module.Message) and issubclass(cls, robowire.Item)
        assert cls.__module__ == module.__name__ and cls.__name__ in module.__all__
    assert module.AnyMessage.__args__ == tuple(getattr(module, camel(n)) for n in names)


@pytest.mark.parametrize("module", MODULES, ids=lambda m: m.__name__)
def test_the_stubs_are_what_update_stubs_writes(module: Any) -> None:
    assert stub_path(module).read_text() == update_stubs.updated(module), (
        "run python python/tests/update_stubs.py"
    )


@pytest.mark.parametrize("module", MODULES, ids=lambda m: m.__name__)
def test_every_item_holds_to_its_class_in_the_stubs(module: Any) -> None:
    classes = stub_fields(module)
    items = samples(module)
    assert {item.type for item in items} == set(type_names(module))
    for item in items:
        name = camel(item.type)
        assert type(item) is getattr(module, name)
        fields = classes[name]
        # Every key is declared, every declared field reads as its type.
        assert set(item) - {"offset"} <= set(fields), (item, set(item) - set(fields))
        for field, annotation in fields.items():
            value = getattr(item, field)
            assert holds(value, annotation), (item, field, value, ast.unparse(annotation))


def test_a_field_some_frames_lack_reads_none_and_stays_no_key() -> None:
    # mirte 1.2 reports whole metres and centimetres; mirte 1.3 centimetres only.
    (older,) = telemetrix.Decoder(source="pico", dialect="mirte12").feed(bytes.fromhex("04 0b 09 01 17"))
    (mirte,) = telemetrix.Decoder(source="pico").feed(bytes.fromhex("05 0b 09 0a 00 77"))
    assert isinstance(older, telemetrix.SonarDistance) and isinstance(mirte, telemetrix.SonarDistance)
    assert (older.m, older.cm, older.echo) == (1, 23, None)
    assert mirte.m is None and "m" not in mirte and mirte.get("m") is None
    with pytest.raises(KeyError):
        mirte["m"]
    assert mirte.quirk is None and mirte.also is None and mirte.t is None
    # A field no frame of the type has is an error, as on any Item.
    with pytest.raises(AttributeError, match="no field width"):
        mirte.width  # noqa: B018


def test_classes_survive_pickle_copy_and_repr() -> None:
    items = telemetrix.Decoder(source="pico").feed(bytes.fromhex("04 03 1a 04 c9 05 0b 09 0a 00 77"), t=2.5)
    for item in items:
        for again in (pickle.loads(pickle.dumps(item)), copy.copy(item), copy.deepcopy(item)):
            assert type(again) is type(item) and again == item and again.t == 2.5
    assert repr(items[0]) == (
        "AnalogReport({'t': 2.5, 'offset': 0, 'len': 5, 'type': 'analog_report', 'pin': 26, 'value': 1225})"
    )
    (blocks,) = pixy2.Decoder(source="device").feed(bytes.fromhex("af c1 21 00 00 00"))
    assert type(pickle.loads(pickle.dumps(blocks))) is pixy2.Blocks


def test_rejections_and_omnitiles_commands_stay_items() -> None:
    (rejected, _) = telemetrix.Decoder(source="pico", errors=True).feed(bytes.fromhex("ff 04 03 1a 04 c9"))
    assert type(rejected) is robowire.Item and "error" in rejected
    (command,) = robowire.omnitiles.Decoder(source="host").feed(bytes.fromhex("a5 50 50"))
    assert type(command) is robowire.Item
