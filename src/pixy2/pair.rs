//! Pairing a response with the request it answers (spec §7.4 item 4).
//!
//! Each request type is a [`Query`] whose [`answer`](Query::answer) checks that
//! a response is the one expected (the right type, or ERROR for any request)
//! and turns it into a typed answer:
//!
//! ```
//! use robowire::pixy2::{GetFps, PairError, Query, Response, DeviceError};
//!
//! assert_eq!(GetFps.answer(Response::Result(61)), Ok(61));
//! assert_eq!(
//!     GetFps.answer(Response::Error(DeviceError::Busy)),
//!     Err(PairError::Device(DeviceError::Busy))
//! );
//! ```

use super::blocks::Blocks;
use super::error::DeviceError;
use super::features::{Features, Section};
use super::request::{
    ChangeProg, GetBlocks, GetFeatures, GetFps, GetResolution, GetRgb, GetVersion, Request,
    ReverseVector, SetCameraBrightness, SetDefaultTurn, SetLamp, SetLed, SetMode, SetNextTurn,
    SetServos, SetVector,
};
use super::response::{Resolution, Response, Rgb, Version};
use super::wire::packet_type as ty;

/// Why a response does not answer a request.
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[derive(Debug, Clone, Copy, PartialEq, Eq, thiserror::Error)]
#[non_exhaustive]
pub enum PairError {
    /// The device answered with an ERROR packet.
    #[error(transparent)]
    Device(DeviceError),
    /// A response of another type than the request expects (for example a
    /// stale answer to an earlier request).
    #[error("expected response type 0x{expected:02x}, got 0x{found:02x}")]
    WrongType {
        /// The expected type.
        expected: u8,
        /// The received type.
        found: u8,
    },
    /// A RESULT value the request cannot produce (setters answer 0,
    /// changeProg 0 or 1, getRGB has a zero top byte).
    #[error("unexpected RESULT value {value}")]
    UnexpectedResult {
        /// The value.
        value: i32,
    },
    /// More blocks than getBlocks asked for.
    #[error("{found} blocks returned, at most {max} requested")]
    TooManyBlocks {
        /// The request's `max_blocks`.
        max: u8,
        /// Blocks in the response.
        found: usize,
    },
    /// A block whose signature the request's signature map excludes.
    #[error("block with signature {signature} was not requested")]
    UnrequestedSignature {
        /// The block's signature.
        signature: u16,
    },
    /// A line feature section whose type the request's bitmap excludes.
    #[error("line feature type {ftype} was not requested")]
    UnrequestedFeature {
        /// The section's feature type.
        ftype: u8,
    },
}

/// The state changeProg reports.
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum ProgSwitch {
    /// RESULT 1: the program is running.
    Running,
    /// RESULT 0: the switch is scheduled; send changeProg again to poll.
    Pending,
}

/// A request that knows its answer.
pub trait Query: Copy + Into<Request> {
    /// The typed answer; it may borrow the response's frame.
    type Answer<'a>;

    /// Check that `response` answers this request and extract the answer.
    fn answer<'a>(&self, response: Response<'a>) -> Result<Self::Answer<'a>, PairError>;

    /// The request as a [`Request`] (for encoding).
    fn request(&self) -> Request {
        (*self).into()
    }
}

/// ERROR becomes [`PairError::Device`]; any type but `expected` is
/// [`PairError::WrongType`].
fn expect_type(response: &Response<'_>, expected: u8) -> Result<(), PairError> {
    match response {
        Response::Error(e) => Err(PairError::Device(*e)),
        r if r.packet_type() == expected => Ok(()),
        r => Err(PairError::WrongType {
            expected,
            found: r.packet_type(),
        }),
    }
}

fn result_value(response: Response<'_>) -> Result<i32, PairError> {
    expect_type(&response, ty::RESULT)?;
    match response {
        Response::Result(v) => Ok(v),
        r => Err(PairError::WrongType {
            expected: ty::RESULT,
            found: r.packet_type(),
        }),
    }
}

macro_rules! setters {
    ($($name:ident),*) => {$(
        /// Answered by RESULT 0.
        impl Query for $name {
            type Answer<'a> = ();
            fn answer<'a>(&self, response: Response<'a>) -> Result<(), PairError> {
                match result_value(response)? {
                    0 => Ok(()),
                    value => Err(PairError::UnexpectedResult { value }),
                }
            }
        }
    )*};
}

setters!(
    SetCameraBrightness,
    SetServos,
    SetLed,
    SetLamp,
    SetMode,
    SetVector,
    SetNextTurn,
    SetDefaultTurn,
    ReverseVector
);

impl Query for ChangeProg {
    type Answer<'a> = ProgSwitch;
    fn answer<'a>(&self, response: Response<'a>) -> Result<ProgSwitch, PairError> {
        match result_value(response)? {
            1 => Ok(ProgSwitch::Running),
            0 => Ok(ProgSwitch::Pending),
            value => Err(PairError::UnexpectedResult { value }),
        }
    }
}

impl Query for GetFps {
    type Answer<'a> = u32;
    fn answer<'a>(&self, response: Response<'a>) -> Result<u32, PairError> {
        result_value(response).map(|v| v as u32)
    }
}

impl Query for GetRgb {
    type Answer<'a> = Rgb;
    fn answer<'a>(&self, response: Response<'a>) -> Result<Rgb, PairError> {
        let value = result_value(response)?;
        Rgb::from_result(value).ok_or(PairError::UnexpectedResult { value })
    }
}

impl Query for GetResolution {
    type Answer<'a> = Resolution;
    fn answer<'a>(&self, response: Response<'a>) -> Result<Resolution, PairError> {
        expect_type(&response, ty::RESOLUTION)?;
        match response {
            Response::Resolution(r) => Ok(r),
            r => Err(wrong(ty::RESOLUTION, &r)),
        }
    }
}

impl Query for GetVersion {
    type Answer<'a> = Version;
    fn answer<'a>(&self, response: Response<'a>) -> Result<Version, PairError> {
        expect_type(&response, ty::VERSION)?;
        match response {
            Response::Version(v) => Ok(v),
            r => Err(wrong(ty::VERSION, &r)),
        }
    }
}

impl Query for GetBlocks {
    type Answer<'a> = Blocks<'a>;
    /// Also checks that the blocks could answer this request: no more than
    /// `max_blocks`, and only requested signatures.
    fn answer<'a>(&self, response: Response<'a>) -> Result<Blocks<'a>, PairError> {
        expect_type(&response, ty::BLOCKS)?;
        let Response::Blocks(blocks) = response else {
            return Err(wrong(ty::BLOCKS, &response));
        };
        if blocks.len() > usize::from(self.max_blocks) {
            return Err(PairError::TooManyBlocks {
                max: self.max_blocks,
                found: blocks.len(),
            });
        }
        if let Some(b) = blocks.iter().find(|b| !self.wants(b.signature)) {
            return Err(PairError::UnrequestedSignature {
                signature: b.signature,
            });
        }
        Ok(blocks)
    }
}

impl Query for GetFeatures {
    type Answer<'a> = Features<'a>;
    /// Also checks that no section of a known type outside the request's
    /// bitmap is present.
    fn answer<'a>(&self, response: Response<'a>) -> Result<Features<'a>, PairError> {
        expect_type(&response, ty::FEATURES)?;
        let Response::Features(features) = response else {
            return Err(wrong(ty::FEATURES, &response));
        };
        for section in features.sections() {
            let ftype = match section {
                Section::Vectors(_) => GetFeatures::VECTORS,
                Section::Intersections(_) => GetFeatures::INTERSECTIONS,
                Section::Barcodes(_) => GetFeatures::BARCODES,
                Section::Unknown { .. } => continue,
            };
            if self.features & ftype == 0 {
                return Err(PairError::UnrequestedFeature { ftype });
            }
        }
        Ok(features)
    }
}

fn wrong(expected: u8, response: &Response<'_>) -> PairError {
    PairError::WrongType {
        expected,
        found: response.packet_type(),
    }
}

impl Query for Request {
    /// The response itself, once it is known to answer this request.
    type Answer<'a> = Response<'a>;

    fn answer<'a>(&self, response: Response<'a>) -> Result<Response<'a>, PairError> {
        match self {
            Self::ChangeProg(q) => q.answer(response).map(|_| ()),
            Self::GetResolution(q) => q.answer(response).map(|_| ()),
            Self::GetVersion(q) => q.answer(response).map(|_| ()),
            Self::SetCameraBrightness(q) => q.answer(response),
            Self::SetServos(q) => q.answer(response),
            Self::SetLed(q) => q.answer(response),
            Self::SetLamp(q) => q.answer(response),
            Self::GetFps(q) => q.answer(response).map(|_| ()),
            Self::GetBlocks(q) => q.answer(response).map(|_| ()),
            Self::GetFeatures(q) => q.answer(response).map(|_| ()),
            Self::SetMode(q) => q.answer(response),
            Self::SetVector(q) => q.answer(response),
            Self::SetNextTurn(q) => q.answer(response),
            Self::SetDefaultTurn(q) => q.answer(response),
            Self::ReverseVector(q) => q.answer(response),
            Self::GetRgb(q) => q.answer(response).map(|_| ()),
        }
        .map(|()| response)
    }
}
