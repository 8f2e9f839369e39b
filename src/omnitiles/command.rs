//! Commands: host → tile.

use core::fmt;
use core::str::FromStr;

use super::error::{Error, UnknownName};
use super::whole::{check_whole, start_and_id};
use super::wire::{checksum, id, payload_len, MAX_COMMAND_LEN, START};
use crate::encode::{check_room, Encode, EncodeError};

/// One of the tile's two linear actuators.
///
/// Its name (`Display`, `FromStr`, and the `serde` form) is `m1` or `m2`, as
/// in the command names (`m1_extend`, …).
///
/// ```
/// use robowire::omnitiles::Motor;
/// assert_eq!("m2".parse(), Ok(Motor::M2));
/// assert_eq!(Motor::M1.to_string(), "m1");
/// ```
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(rename_all = "lowercase"))]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Motor {
    /// M1: 150 mm stroke.
    M1,
    /// M2: 100 mm stroke.
    M2,
}

impl Motor {
    /// Both motors.
    pub const ALL: [Motor; 2] = [Motor::M1, Motor::M2];

    /// The motor's name: `m1` or `m2`.
    pub const fn name(self) -> &'static str {
        match self {
            Motor::M1 => "m1",
            Motor::M2 => "m2",
        }
    }
}

impl fmt::Display for Motor {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for Motor {
    type Err = UnknownName;

    fn from_str(name: &str) -> Result<Motor, UnknownName> {
        Motor::ALL
            .into_iter()
            .find(|m| m.name() == name)
            .ok_or(UnknownName::new("motor", "m1 or m2"))
    }
}

/// A command from the host to a tile.
///
/// ```
/// use robowire::omnitiles::{Command, Motor};
/// use robowire::Encode;
/// let mut out = [0u8; Command::MAX_LEN];
/// let n = Command::Extend { motor: Motor::M1, speed: 200 }.encode(&mut out).unwrap();
/// assert_eq!(&out[..n], [0xa5, 0x30, 0xc8, 0xf8]);
/// // And back from the whole frame:
/// assert_eq!(Command::try_from(&out[..n]), Ok(Command::Extend { motor: Motor::M1, speed: 200 }));
/// assert_eq!(Command::Extend { motor: Motor::M1, speed: 200 }.to_string(), "m1_extend speed=200");
/// ```
///
/// With the `serde` feature a command is written as the command-line tool's
/// JSON line for it, without `offset` and `len`:
/// `{"type":"m1_extend","speed":200}`. Deserializing checks every field as
/// the tool does (the type, unknown fields, ranges), with its messages.
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

impl Command {
    /// The longest command frame (base velocity).
    pub const MAX_LEN: usize = MAX_COMMAND_LEN;

    /// Every command's [`name`](Self::name), in the order of the spec's id
    /// table with ping first: the `type` values of the JSON form.
    pub const NAMES: [&'static str; 11] = [
        "ping",
        "m1_extend",
        "m1_retract",
        "m1_brake",
        "m1_set_position",
        "m2_extend",
        "m2_retract",
        "m2_brake",
        "m2_set_position",
        "base_velocity",
        "base_brake",
    ];

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

    /// The snake-case name used by the command-line tool and the JSON form
    /// (`m1_extend`, `ping`, …; one of [`NAMES`](Self::NAMES)).
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
    /// and the payload has its length: the table, one arm per command, that
    /// the branch-free [`Command::parse_framed`] is tested against.
    #[cfg(test)]
    const fn from_id_and_payload(id: u8, payload: &[u8]) -> Option<Command> {
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

    /// A frame that passed framing (start byte, command id, length and
    /// checksum already checked) as a command.
    ///
    /// Without a branch on the command: a stream mixes commands
    /// unpredictably, and a branch per kind (what a `match` on the id
    /// compiles to) is mispredicted about once per frame. Every candidate is
    /// built and the right one selected.
    #[inline(always)]
    pub(crate) fn parse_framed(frame: &[u8]) -> Result<Command, Error> {
        let id = frame.get(1).copied().unwrap_or(0);
        if payload_len(id).map(|n| n + 3) != Some(frame.len()) {
            return Err(Error::UnknownId { id });
        }
        // Payload bytes past the frame's read its last byte instead: an index
        // clamped into the frame needs no branch.
        let last = frame.len() - 1;
        let byte = |at: usize| frame.get(at.min(last)).copied().unwrap_or(0);
        let (a, b, c) = (byte(2), byte(3), byte(4));
        let motor = if id >> 4 == 3 { Motor::M1 } else { Motor::M2 };
        let low = id & 0x0f;
        let motor_command = [
            Command::Extend { motor, speed: a },
            Command::Retract { motor, speed: a },
            Command::Brake { motor },
            Command::SetPosition { motor, position: a },
        ][usize::from(low & 3)];
        let base = if low == 0 {
            Command::BaseVelocity {
                vx: a as i8,
                vy: b as i8,
                omega: c as i8,
            }
        } else {
            Command::BaseBrake
        };
        Ok(match id >> 4 {
            3 | 4 => motor_command,
            5 => Command::Ping,
            _ => base,
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

/// One whole command frame, start byte to checksum: nothing before it and
/// nothing after it.
///
/// ```
/// use robowire::omnitiles::{Command, Error};
/// assert_eq!(Command::try_from(&[0xa5, 0x50, 0x50][..]), Ok(Command::Ping));
/// assert_eq!(
///     Command::try_from(&[0xa5, 0x50, 0x51][..]),
///     Err(Error::Checksum { expected: 0x50, found: 0x51 })
/// );
/// assert_eq!(Command::try_from(&[0xa5, 0x50, 0x50, 0x00][..]), Err(Error::BadLength { len: 4 }));
/// ```
impl TryFrom<&[u8]> for Command {
    type Error = Error;

    fn try_from(frame: &[u8]) -> Result<Command, Error> {
        let id = start_and_id(frame)?;
        let n = payload_len(id).ok_or(Error::UnknownId { id })?;
        check_whole(frame, 3 + n)?;
        Command::parse_framed(frame)
    }
}

/// One line with the JSON form's words: the name, then `field=value` pairs
/// (`m1_extend speed=200`, `base_velocity vx=10 vy=-5 omega=20`, `ping`).
impl fmt::Display for Command {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())?;
        match *self {
            Command::Extend { speed, .. } | Command::Retract { speed, .. } => {
                write!(f, " speed={speed}")
            }
            Command::SetPosition { position, .. } => write!(f, " position={position}"),
            Command::BaseVelocity { vx, vy, omega } => {
                write!(f, " vx={vx} vy={vy} omega={omega}")
            }
            Command::Ping | Command::Brake { .. } | Command::BaseBrake => Ok(()),
        }
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_framed_parser_agrees_with_the_command_table_for_every_id_and_length() {
        let payload = [0x81, 0x02, 0xfe];
        for id in 0..=255u8 {
            for n in 0..=payload.len() {
                let mut frame = [START, id, 0, 0, 0, 0];
                frame[2..2 + n].copy_from_slice(&payload[..n]);
                let frame = &frame[..3 + n];
                let expected =
                    Command::from_id_and_payload(id, &payload[..n]).ok_or(Error::UnknownId { id });
                assert_eq!(
                    Command::parse_framed(frame),
                    expected,
                    "id {id:#04x}, {n} bytes"
                );
            }
        }
    }
}
