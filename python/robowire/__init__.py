"""robowire: exact, fast decoders and encoders for small robot serial protocols.

Three protocols, one API, backed by robowire's Rust codecs:

* :mod:`robowire.omnitiles` -- OmniTiles host commands and tile telemetry;
* :mod:`robowire.pixy2` -- Pixy2 requests and responses;
* :mod:`robowire.telemetrix` -- Telemetrix4RpiPico commands and reports.

Each has a stream ``Decoder`` (a :class:`StreamDecoder`: ``feed(data) -> list``,
``finish() -> list``, ``stats``) and ``encode(message) -> bytes``. Decoded items
are typed: their fields read as attributes (``t.m1_pos``, ``t.imu.az``) or keys
(``t["m1_pos"]``) without a dict per frame, :class:`robowire.omnitiles.Telemetry`
for telemetry and :class:`Item` for everything else, each a read-only mapping in
the JSON-lines schema of the ``robowire`` command-line tool::

    >>> from robowire import omnitiles
    >>> decoder = omnitiles.Decoder(source="host")
    >>> decoder.feed(bytes.fromhex("a5 30 c8 f8 a5 50 50"))
    [Item({'offset': 0, 'len': 4, 'type': 'm1_extend', 'speed': 200}), Item({'offset': 4, 'len': 3, 'type': 'ping'})]
    >>> omnitiles.encode({"type": "m1_extend", "speed": 200}).hex(" ")
    'a5 30 c8 f8'

A decoder made with ``typed=False`` returns those dicts instead; ``encode``
takes either. ``decoder.stats`` is a :class:`Stats` dict of link-quality
counters. The type stubs make each decoder generic in its items
(``omnitiles.Decoder[omnitiles.Telemetry]`` for ``source="tile"``).
"""

from collections.abc import Mapping as _Mapping

from ._robowire import Item, StreamDecoder, __version__
from ._stats import Stats
from . import omnitiles, pixy2, telemetrix

_Mapping.register(Item)

__all__ = ["Item", "Stats", "StreamDecoder", "omnitiles", "pixy2", "telemetrix", "__version__"]
