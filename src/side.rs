//! Which side of a link a decoder runs on, as a type.
//!
//! Every protocol module names its decoders after these markers:
//! `HostDecoder` decodes what a device sends (it runs on the host),
//! `DeviceDecoder` decodes what a host sends (it runs on the device, or in a
//! simulator of it), and `BothDecoder` accepts both directions (captures,
//! sniffers, tooling). The protocol's `Framing<Side>` is generic over the same
//! markers, so a decoder's message type follows from its side, and code for
//! frames a side never accepts is never linked.

/// The host's side of a link: decodes what the device sends.
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub struct Host;

/// The device's side of a link (firmware, or a simulator of it): decodes what
/// the host sends.
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub struct Device;

/// Both directions at once (captures, sniffers, tooling).
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub struct Both;
