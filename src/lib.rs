#![no_std]
#![cfg_attr(docsrs, feature(doc_cfg))]
#![deny(missing_docs)]
#![forbid(unsafe_code)]
#![doc = include_str!("../README.md")]

#[cfg(feature = "serde")]
extern crate alloc;
#[cfg(feature = "tokio-util-07")]
extern crate std;

pub mod encode;
pub mod io;
pub mod omnitiles;
pub mod pixy2;
#[cfg(feature = "serde")]
mod serde_support;
pub mod side;
pub mod stream;
pub mod telemetrix;

pub use encode::{Encode, EncodeError, FrameBuf};
#[allow(deprecated)]
pub use stream::Framed;
pub use stream::{
    Check, Event, Feed, Flush, Frame, FrameRules, OwnedEvent, OwnedFrame, Rejected, Stats,
    StreamDecoder,
};
