"""The link-quality counters of a decoder (``decoder.stats``)."""

from __future__ import annotations

import warnings

_RENAMED = {"checksum_errors": "checksum_failures", "rejected": "other_rejections"}


class Stats(dict):  # type: ignore[type-arg]
    """A new dict of counters on each read, in the words of the ``robowire``
    tool's summary line: ``bytes`` (taken so far), ``frames``, ``frame_bytes``,
    ``skipped`` (bytes in no frame), ``checksum_failures``,
    ``other_rejections`` (every other rejected candidate, ``superseded`` ones
    included), ``malformed`` (frames whose contents did not parse) and
    ``superseded``. They add up: ``bytes == frame_bytes + skipped + buffered``.

    The keys of robowire 0.2, ``checksum_errors`` and ``rejected`` (other
    rejections without the superseded ones), still read, with a
    ``DeprecationWarning``, until the next release; they are not among the
    keys.
    """

    def __missing__(self, key: str) -> int:
        if key not in _RENAMED:
            raise KeyError(key)
        warnings.warn(
            f"stats[{key!r}] is deprecated: read stats[{_RENAMED[key]!r}]"
            + (" (which counts superseded candidates too)" if key == "rejected" else ""),
            DeprecationWarning,
            stacklevel=2,
        )
        if key == "rejected":
            return int(self["other_rejections"]) - int(self["superseded"])
        return int(self[_RENAMED[key]])
