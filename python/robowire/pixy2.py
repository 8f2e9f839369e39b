"""Pixy2: host requests and device responses (``ae c1`` / ``af c1`` frames).

* :class:`Decoder` -- the stream decoder for a serial link or a capture;
* :func:`encode` -- a message dict to its frame.

Items are objects of a class per message ``type`` (``blocks``:
:class:`Blocks`; all derive from :class:`Message` and :class:`robowire.Item`,
:data:`AnyMessage` is their union): read-only mappings of the ``robowire``
tool's JSON-lines schema whose fields read as typed attributes, a field only
some frames carry reading ``None`` when absent. With ``typed=False`` they are
these dicts, which :func:`encode` takes too::

    {"offset": 0, "len": 4, "type": "get_version", "checksum": False}
    {"offset": 4, "len": 22, "type": "version", "checksum": True, "hardware": 8704,
     "firmware_major": 3, "firmware_minor": 0, "firmware_build": 10,
     "firmware_type": "general"}

``checksum`` says the frame form (``af c1`` with a checksum, ``ae c1``
without). Requests: ``change_prog``, ``get_resolution``, ``get_version``,
``set_camera_brightness``, ``set_servos``, ``set_led``, ``set_lamp``,
``get_fps``, ``get_blocks``, ``get_features``, ``set_mode``, ``set_vector``,
``set_next_turn``, ``set_default_turn``, ``reverse_vector``, ``get_rgb``;
responses: ``result``, ``error``, ``resolution``, ``version``, ``blocks``,
``features``. Run ``robowire decode pixy2 --help`` for every field.
"""

from . import _messages
from ._robowire import pixy2 as _native

Decoder = _native.Decoder
encode = _native.encode
field_info = _native.field_info
Message = _native.Message

# A class per message ``type``, made in Rust.
_CLASSES = _messages.classes(_native)
globals().update(_CLASSES)
AnyMessage = _messages.union(_CLASSES)

__all__ = ["AnyMessage", "Decoder", "Message", "encode", "field_info", *sorted(_CLASSES)]
