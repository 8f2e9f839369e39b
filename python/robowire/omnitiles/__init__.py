"""OmniTiles: host commands and tile telemetry (``a5``, id, payload, sum).

* :class:`Decoder` -- the stream decoder for a serial link or a capture;
* :class:`DatagramDecoder` -- one BLE notification (or write) at a time;
* :func:`encode` -- a message dict to its frame.

Items are typed (:class:`Telemetry` per telemetry frame, :class:`robowire.Item`
for the rest), read-only mappings of the ``robowire`` tool's JSON-lines schema;
with ``typed=False`` they are these dicts, which :func:`encode` takes too::

    {"offset": 0, "len": 4, "type": "m1_extend", "speed": 200}
    {"offset": 4, "len": 53, "type": "telemetry", "layout": "ble53",
     "m1_pos": 1104, "m2_pos": 2852, "uwb": [4579, 3151, 3112, None],
     "tof": 448, "imu": {"ax": -1.445499300956726, ...}, "m1_adcs": [...], "m2_adcs": [...]}

Command types: ``ping``, ``m1_extend``, ``m1_retract``, ``m1_brake``,
``m1_set_position``, the same for ``m2_``, ``base_velocity`` and
``base_brake``; fields ``speed`` (0..255), ``position`` (0..255), ``vx``,
``vy``, ``omega`` (-128..127). Telemetry: ``layout``, ``m1_pos``, ``m2_pos``
and, where the layout carries them, ``uwb``, ``tof``, ``imu``, ``m1_adcs``,
``m2_adcs``; a 0xFFFF reading is ``None``.
"""

from collections.abc import Mapping as _Mapping

from .._robowire import omnitiles as _native

Decoder = _native.Decoder
DatagramDecoder = _native.DatagramDecoder
Telemetry = _native.Telemetry
Imu = _native.Imu
encode = _native.encode
field_info = _native.field_info

_Mapping.register(Telemetry)
_Mapping.register(Imu)

__all__ = ["Decoder", "DatagramDecoder", "Imu", "Telemetry", "encode", "field_info"]
