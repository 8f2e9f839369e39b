//! Optional adapters between the [streaming engine](crate::stream) and I/O
//! traits: each is written once, generic over [`FrameRules`], so every protocol
//! gets it.
//!
//! | feature | module | what it adds |
//! |---|---|---|
//! | `tokio-util-07` | `io::tokio` | `FrameCodec`: `tokio_util::codec` `Decoder` and `Encoder` (needs `std`) |
//! | `embedded-io-07` | `io::embedded_io` | blocking `PacketReader` and `PacketWriter` over `embedded_io` 0.7 |
//! | `embedded-io-async-07` | `io::embedded_io_async` | the same over `embedded_io_async` 0.7 |
//!
//! All of them keep the engine's rules: a rejected candidate (bad checksum,
//! unknown id, garbage) is an event or a counter in [`Stats`](crate::Stats),
//! never an I/O error and never the end of a stream; the end of the input
//! resolves what is still buffered ([`StreamDecoder::finish`]). The
//! `embedded-io` adapters are `no_std` and allocation-free: the reader reads
//! into a buffer the caller provides and the writer encodes into a
//! [`FrameBuf`](crate::FrameBuf) on the stack.
//!
//! [`FrameRules`]: crate::FrameRules
//! [`StreamDecoder::finish`]: crate::StreamDecoder::finish

#[cfg(feature = "tokio-util-07")]
#[cfg_attr(docsrs, doc(cfg(feature = "tokio-util-07")))]
pub mod tokio;

#[cfg(feature = "embedded-io-07")]
#[cfg_attr(docsrs, doc(cfg(feature = "embedded-io-07")))]
pub mod embedded_io;

#[cfg(feature = "embedded-io-async-07")]
#[cfg_attr(docsrs, doc(cfg(feature = "embedded-io-async-07")))]
pub mod embedded_io_async;

#[cfg(any(feature = "embedded-io-07", feature = "embedded-io-async-07"))]
mod chunks;

#[cfg(any(feature = "embedded-io-07", feature = "embedded-io-async-07"))]
#[cfg_attr(
    docsrs,
    doc(cfg(any(feature = "embedded-io-07", feature = "embedded-io-async-07")))
)]
pub use chunks::WriteError;
