"""The link-quality counters of a decoder (``decoder.stats``)."""

from typing import TypedDict

class Stats(TypedDict):
    """A new dict of counters on each read. They add up:
    ``bytes == frame_bytes + skipped + buffered``. (At run time a ``dict``
    subclass that still reads the deprecated keys ``checksum_errors`` and
    ``rejected``, with a warning; the type leaves them out.)"""

    bytes: int
    """Bytes taken so far."""
    frames: int
    """Frames that passed framing (parsed or not)."""
    frame_bytes: int
    """Bytes in those frames."""
    skipped: int
    """Bytes in no frame: garbage, and the first byte of each rejected candidate."""
    checksum_failures: int
    """Candidates whose checksum failed."""
    other_rejections: int
    """Every other rejected candidate, ``superseded`` ones included."""
    malformed: int
    """Frames whose integrity was fine but whose contents did not parse."""
    superseded: int
    """Candidates that validated after a resync but were set aside for an
    overlapping frame that what follows confirmed."""
