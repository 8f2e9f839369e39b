#![no_std]
#![cfg_attr(docsrs, feature(doc_auto_cfg))]
#![deny(missing_docs)]
#![forbid(unsafe_code)]
//! robowire: `no_std`, allocation-free, sans-IO codecs for small robot serial
//! protocols.

#[cfg(test)]
extern crate std;

pub mod stream;

pub use stream::{Check, Event, Frame, Framing, Rejected, Stats, StreamDecoder};
pub mod encode;
pub mod telemetrix;

pub use encode::{Encode, EncodeError, FrameBuf};
pub use stream::{Feed, Flush, Framed, OwnedEvent};
