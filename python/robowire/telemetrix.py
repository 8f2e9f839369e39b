"""Telemetrix4RpiPico: host commands and Pico reports (LEN, id, payload).

* :class:`Decoder` -- the stream decoder for a serial link or a capture;
* :func:`encode` -- a message dict to its frame, for a firmware dialect.

Items are objects of a class per message ``type`` (``analog_report``:
:class:`AnalogReport`; all derive from :class:`Message` and :class:`robowire.Item`,
:data:`AnyMessage` is their union): read-only mappings of the ``robowire``
tool's JSON-lines schema whose fields read as typed attributes, a field only
some frames carry reading ``None`` when absent. With ``typed=False`` they are
these dicts, which :func:`encode` takes too::

    {"offset": 0, "len": 4, "type": "firmware_version", "major": 1, "minor": 3}
    {"offset": 4, "len": 5, "type": "analog_report", "pin": 26, "value": 1225}
    {"offset": 9, "len": 6, "type": "sonar_distance", "trig": 9, "echo": 10, "cm": 119}

Dialects: ``mirte13`` (mirte firmware 1.3, the default), ``mirte12``,
``upstream11``. Run ``robowire decode telemetrix --help`` for every type and
field.
"""

from . import _messages
from ._robowire import telemetrix as _native

Decoder = _native.Decoder
encode = _native.encode
field_info = _native.field_info
Message = _native.Message

# A class per message ``type``, made in Rust.
_CLASSES = _messages.classes(_native)
globals().update(_CLASSES)
AnyMessage = _messages.union(_CLASSES)

__all__ = ["AnyMessage", "Decoder", "Message", "encode", "field_info", *sorted(_CLASSES)]
