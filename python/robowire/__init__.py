"""robowire: exact, fast decoders and encoders for small robot serial protocols.

Three protocols, one API, backed by robowire's Rust codecs:

* :mod:`robowire.omnitiles` -- OmniTiles host commands and tile telemetry;
* :mod:`robowire.pixy2` -- Pixy2 requests and responses;
* :mod:`robowire.telemetrix` -- Telemetrix4RpiPico commands and reports.

Each has a stream ``Decoder`` (a :class:`StreamDecoder`: ``feed(data) -> list``,
``finish() -> list``, ``stats``) and ``encode(message) -> bytes``. Decoded
items and messages to encode are dicts in the JSON-lines schema of the
``robowire`` command-line tool: ``{"offset": 0, "len": 4, "type":
"m1_extend", "speed": 200}``.
"""

from ._robowire import StreamDecoder, __version__
from . import omnitiles

__all__ = ["StreamDecoder", "omnitiles", "pixy2", "telemetrix", "__version__"]
