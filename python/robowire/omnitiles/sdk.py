"""A drop-in for the OmniTiles SDK's stream parser, decoded by robowire.

Switching takes one import line::

    from omnitiles.protocol import StreamParser      # the SDK
    from robowire.omnitiles.sdk import StreamParser  # robowire

:class:`StreamParser` ``.feed(data)`` returns :class:`Telemetry` items with the
SDK's fields and meanings (``timestamp``, ``m1_pos_adc``, ``m1_pos_mm``,
``m1_adcs``, ``uwb_mm``, ``tof_mm``, ``imu``, ``raw``, ...). Where robowire
differs (a 0xFFFF position is ``None``; no false short frame at a chunk
boundary; no stall on a stray 0xA5) is in docs/python.md.
"""

from .._robowire import sdk as _native

StreamParser = _native.StreamParser
Telemetry = _native.Telemetry

__all__ = ["StreamParser", "Telemetry"]
