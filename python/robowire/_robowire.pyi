"""The compiled core of :mod:`robowire` (import from ``robowire`` instead)."""

from collections.abc import Iterator, KeysView, ItemsView, Mapping, ValuesView
from typing import Any, ClassVar, Generic, Optional, TypeVar, Union, final

from . import omnitiles as omnitiles, pixy2 as pixy2, telemetrix as telemetrix
from ._stats import Stats

__all__ = ["Item", "StreamDecoder", "__version__", "omnitiles", "pixy2", "telemetrix"]
__version__: str

# The stubs import `typing`, and `deprecated` from `warnings` (3.13) or
# typing_extensions, which the package depends on before 3.13.

_Bytes = Union[bytes, bytearray, memoryview]
"""What the decoders take: ``bytes``, ``bytearray`` or ``memoryview``."""

class _Fields(Mapping[str, Any]):
    """What :class:`Item` and the message classes share (a name of the stubs
    only): a read-only mapping of the item's dict."""

    @property
    def offset(self) -> int:
        """Offset of the item's first byte in the stream (builds no dict)."""
    def to_dict(self) -> dict[str, Any]:
        """The item as a new plain dict in the JSON-lines schema."""
    def get(self, key: str, default: Any = None, /) -> Any: ...
    def keys(self) -> KeysView[str]: ...
    def values(self) -> ValuesView[Any]: ...
    def items(self) -> ItemsView[str, Any]: ...
    def __getitem__(self, key: str, /) -> Any: ...
    def __iter__(self) -> Iterator[str]: ...
    def __len__(self) -> int: ...
    __hash__: ClassVar[None]  # type: ignore[assignment]
    """Unhashable, as the dict it equals; pickles and copies as that dict."""

class Item(_Fields):
    """A decoded item kept in Rust: what OmniTiles commands, rejections and
    every item of the deprecated ``lazy=True`` are, and at run time the base
    of the Telemetrix and Pixy2 message classes.

    A read-only mapping with exactly the keys and values of the dict a ``typed=False``
    decoder returns; equal to that dict. Fields read as attributes too
    (``item.speed``, typed ``Any``). A field read alone is made from the
    frame, without a dict; iterating, ``len``, ``==`` and :meth:`to_dict`
    build the dict once.
    """

    def __getattr__(self, name: str) -> Any: ...

_Dict = dict[str, Any]
"""An item of a ``typed=False`` decoder: a dict in the JSON-lines schema."""

_T_co = TypeVar("_T_co", covariant=True)
"""What a decoder's items are: each protocol's ``Decoder`` constructor picks it
from its ``source``, ``errors`` and ``typed`` options."""

class StreamDecoder(Generic[_T_co]):
    """The stream decoder every protocol's ``Decoder`` is.

    Feed it bytes as they arrive, in chunks of any size; it returns the
    decoded items, each a dict in the ``robowire`` tool's JSON-lines schema
    (``offset``, ``len``, then the message's keys; with ``errors=True`` also
    rejections: ``offset``, then ``error`` and its keys).
    """

    def feed(self, data: _Bytes, /, t: Optional[float] = None) -> list[_T_co]:
        """Decode the next chunk; the items it completes, in stream order, each
        carrying the receive time ``t`` if one is given."""
    def finish(self, t: Optional[float] = None) -> list[_T_co]:
        """End of input: the items a buffered partial frame resolves to."""
    def settle(self, t: Optional[float] = None) -> list[_T_co]:
        """The line went idle: a buffered frame only the next byte would decide."""
    def clear(self) -> None:
        """Forget a buffered partial frame (its bytes count as skipped)."""
    def deadline(self, idle: float, /) -> Optional[float]:
        """When the line counts as idle after ``idle`` seconds without a byte
        (the last feed that left bytes held, plus ``idle``), or ``None``."""
    def poll(self, idle: float, now: Optional[float] = None) -> list[_T_co]:
        """At ``now`` (default ``time.monotonic()``), past :meth:`deadline`:
        :meth:`settle`'s items, once per silence; else ``[]``."""
    def feed_array(self, data: _Bytes, /, masked: bool = False) -> dict[str, Any]:
        """Decode the next chunk into numpy structured arrays, one per message
        kind (Pixy2: and per listed element kind, ``blocks``,
        ``features_vectors``, ...; needs numpy); ``masked=True``: ``numpy.ma``
        arrays with every cell without a reading masked."""
    def _count(self, data: _Bytes, /) -> int:
        """Decode as :meth:`feed` does, building no items; the frames decoded."""
    @property
    def stats(self) -> Stats:
        """Counters: bytes, frames, frame_bytes, skipped, checksum_failures,
        other_rejections, malformed, superseded."""
    @property
    def buffered(self) -> int:
        """Bytes held as the start of an unfinished frame."""
    @property
    def errors(self) -> bool:
        """Whether rejected candidates are returned as items."""
    @property
    def lazy(self) -> bool:
        """Whether items are :class:`Item` objects (``lazy=True``, deprecated)."""
    @property
    def typed(self) -> bool:
        """Whether items are typed (the default; ``typed=False`` gives dicts)."""
