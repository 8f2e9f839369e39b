//! Commands: host → tile.

use super::{checksum, START};
use crate::encode::{check_room, Encode, EncodeError};

/// One of the tile's two linear actuators.
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Motor {
    /// M1: 150 mm stroke.
    M1,
    /// M2: 100 mm stroke.
    M2,
}

/// Message ids (spec §3).
pub mod id {
    /// M1 extend, u8 speed.
    pub const M1_EXTEND: u8 = 0x30;
    /// M1 retract, u8 speed.
    pub const M1_RETRACT: u8 = 0x31;
    /// M1 brake.
    pub const M1_BRAKE: u8 = 0x32;
    /// M1 set position, u8 scaled over the stroke.
    pub const M1_SET_POSITION: u8 = 0x33;
    /// M2 extend, u8 speed.
    pub const M2_EXTEND: u8 = 0x40;
    /// M2 retract, u8 speed.
    pub const M2_RETRACT: u8 = 0x41;
    /// M2 brake.
    pub const M2_BRAKE: u8 = 0x42;
    /// M2 set position, u8 scaled over the stroke.
    pub const M2_SET_POSITION: u8 = 0x43;
    /// Ping (no reply).
    pub const PING: u8 = 0x50;
    /// Telemetry, tile → host only.
    pub const TELEMETRY: u8 = 0x60;
    /// Mecanum base velocity, three i8.
    pub const BASE_VELOCITY: u8 = 0x70;
    /// Brake all four wheels.
    pub const BASE_BRAKE: u8 = 0x71;
}

/// A command from the host to a tile.
///
/// ```
/// use robowire::omnitiles::{Command, Motor};
/// use robowire::Encode;
/// let mut out = [0u8; Command::MAX_LEN];
/// let n = Command::Extend { motor: Motor::M1, speed: 200 }.encode(&mut out).unwrap();
/// assert_eq!(&out[..n], [0xa5, 0x30, 0xc8, 0xf8]);
/// ```
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Command {
    /// `0x50`: connectivity check; the tile logs it and does not reply.
    Ping,
    /// `0x30`/`0x40`: drive the actuator outwards; duty `speed/255` (see
    /// [`units::speed_to_duty`](super::units::speed_to_duty)). Speed 0 brakes.
    Extend {
        /// Which actuator.
        motor: Motor,
        /// Speed byte, 0..=255.
        speed: u8,
    },
    /// `0x31`/`0x41`: drive the actuator inwards.
    Retract {
        /// Which actuator.
        motor: Motor,
        /// Speed byte, 0..=255.
        speed: u8,
    },
    /// `0x32`/`0x42`: brake the actuator.
    Brake {
        /// Which actuator.
        motor: Motor,
    },
    /// `0x33`/`0x43`: move to a position; the byte is scaled 0..=255 over the
    /// stroke (see [`units::position_to_mm`](super::units::position_to_mm)).
    SetPosition {
        /// Which actuator.
        motor: Motor,
        /// Target, 0..=255 over the full stroke.
        position: u8,
    },
    /// `0x70`: mecanum base velocity as normalised duty (`v/127`).
    BaseVelocity {
        /// Forward.
        vx: i8,
        /// Left (the physical sign is unsettled upstream; see the spec).
        vy: i8,
        /// Counter-clockwise rotation.
        omega: i8,
    },
    /// `0x71`: brake all four wheels.
    BaseBrake,
}

/// Payload length of a command id, or `None` if the id is no command.
#[inline]
pub const fn payload_len(id: u8) -> Option<usize> {
    // One table load instead of a chain of comparisons on the hot path.
    match PAYLOAD_LEN[id as usize] {
        NOT_A_COMMAND => None,
        n => Some(n as usize),
    }
}

/// [`PAYLOAD_LEN`] entry of an id that is no command.
const NOT_A_COMMAND: u8 = u8::MAX;

/// Payload length by id, [`NOT_A_COMMAND`] for ids that are no command.
const PAYLOAD_LEN: [u8; 256] = {
    let mut table = [NOT_A_COMMAND; 256];
    let mut id = 0;
    while id < 256 {
        if let Some(n) = command_payload_len(id as u8) {
            table[id] = n as u8;
        }
        id += 1;
    }
    table
};

/// The command table (spec §3) that [`PAYLOAD_LEN`] is built from.
const fn command_payload_len(id: u8) -> Option<usize> {
    match id {
        id::M1_EXTEND | id::M1_RETRACT | id::M1_SET_POSITION => Some(1),
        id::M2_EXTEND | id::M2_RETRACT | id::M2_SET_POSITION => Some(1),
        id::M1_BRAKE | id::M2_BRAKE | id::PING | id::BASE_BRAKE => Some(0),
        id::BASE_VELOCITY => Some(3),
        _ => None,
    }
}

impl Command {
    /// The longest command frame (base velocity).
    pub const MAX_LEN: usize = 6;

    /// The command's message id.
    pub const fn id(&self) -> u8 {
        match *self {
            Command::Ping => id::PING,
            Command::Extend { motor, .. } => pick(motor, id::M1_EXTEND, id::M2_EXTEND),
            Command::Retract { motor, .. } => pick(motor, id::M1_RETRACT, id::M2_RETRACT),
            Command::Brake { motor } => pick(motor, id::M1_BRAKE, id::M2_BRAKE),
            Command::SetPosition { motor, .. } => {
                pick(motor, id::M1_SET_POSITION, id::M2_SET_POSITION)
            }
            Command::BaseVelocity { .. } => id::BASE_VELOCITY,
            Command::BaseBrake => id::BASE_BRAKE,
        }
    }

    /// The snake-case name used by the command-line tool (`m1_extend`, `ping`, …).
    pub const fn name(&self) -> &'static str {
        match *self {
            Command::Ping => "ping",
            Command::Extend { motor, .. } => pick_name(motor, "m1_extend", "m2_extend"),
            Command::Retract { motor, .. } => pick_name(motor, "m1_retract", "m2_retract"),
            Command::Brake { motor } => pick_name(motor, "m1_brake", "m2_brake"),
            Command::SetPosition { motor, .. } => {
                pick_name(motor, "m1_set_position", "m2_set_position")
            }
            Command::BaseVelocity { .. } => "base_velocity",
            Command::BaseBrake => "base_brake",
        }
    }

    /// The command with message id `id` and `payload`, if the id is a command
    /// and the payload has its length.
    pub const fn from_parts(id: u8, payload: &[u8]) -> Option<Command> {
        let motor = if id >> 4 == 3 { Motor::M1 } else { Motor::M2 };
        Some(match (id, payload) {
            (id::PING, []) => Command::Ping,
            (id::M1_EXTEND | id::M2_EXTEND, &[speed]) => Command::Extend { motor, speed },
            (id::M1_RETRACT | id::M2_RETRACT, &[speed]) => Command::Retract { motor, speed },
            (id::M1_BRAKE | id::M2_BRAKE, []) => Command::Brake { motor },
            (id::M1_SET_POSITION | id::M2_SET_POSITION, &[position]) => {
                Command::SetPosition { motor, position }
            }
            (id::BASE_VELOCITY, &[vx, vy, omega]) => Command::BaseVelocity {
                vx: vx as i8,
                vy: vy as i8,
                omega: omega as i8,
            },
            (id::BASE_BRAKE, []) => Command::BaseBrake,
            _ => return None,
        })
    }

    /// Write the payload (after the id) into `out`; returns its length.
    fn payload(&self, out: &mut [u8; 3]) -> usize {
        match *self {
            Command::Ping | Command::Brake { .. } | Command::BaseBrake => 0,
            Command::Extend { speed, .. } | Command::Retract { speed, .. } => {
                out[0] = speed;
                1
            }
            Command::SetPosition { position, .. } => {
                out[0] = position;
                1
            }
            Command::BaseVelocity { vx, vy, omega } => {
                *out = [vx as u8, vy as u8, omega as u8];
                3
            }
        }
    }
}

const fn pick(motor: Motor, m1: u8, m2: u8) -> u8 {
    match motor {
        Motor::M1 => m1,
        Motor::M2 => m2,
    }
}

const fn pick_name(motor: Motor, m1: &'static str, m2: &'static str) -> &'static str {
    match motor {
        Motor::M1 => m1,
        Motor::M2 => m2,
    }
}

impl Encode for Command {
    const MAX_LEN: usize = Command::MAX_LEN;

    fn encoded_len(&self) -> usize {
        3 + self.payload(&mut [0; 3])
    }

    fn encode(&self, out: &mut [u8]) -> Result<usize, EncodeError> {
        let mut payload = [0; 3];
        let n = self.payload(&mut payload);
        let len = 3 + n;
        check_room(out, len)?;
        let id = self.id();
        out[0] = START;
        out[1] = id;
        out[2..2 + n].copy_from_slice(&payload[..n]);
        out[2 + n] = checksum(&out[1..2 + n]);
        Ok(len)
    }
}
