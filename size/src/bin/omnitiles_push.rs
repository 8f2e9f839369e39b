//! Row: a robust OmniTiles command decoder fed one byte at a time by
//! `push`/`poll`, as a receive interrupt feeds it, matching three commands.
#![no_std]
#![no_main]

use robowire::omnitiles::{Command, Device, Framing, DEVICE_BUFFER};
use robowire::StreamDecoder;
use robowire_size::{out, read_byte, Static};

/// The firmware-sized command decoder: the framing's 14-byte buffer and
/// `u32` counters.
type DeviceDecoder = StreamDecoder<Framing<Device>, DEVICE_BUFFER, u32>;

/// The decoder, in a `static` as a firmware keeps it (its size is the RAM row).
#[no_mangle]
static DECODER: Static<DeviceDecoder> = Static::new(StreamDecoder::new(Framing::new()));

fn on_command(command: Command) {
    match command {
        Command::Extend { motor, speed } => out(0x100 | (motor as u32) << 8 | u32::from(speed)),
        Command::Brake { motor } => out(0x200 | motor as u32),
        Command::Ping => out(0x300),
        _ => {}
    }
}

#[no_mangle]
pub extern "C" fn _start() -> ! {
    let decoder = DECODER.get();
    loop {
        let byte = read_byte();
        if let Some(Ok(frame)) = decoder.push(byte) {
            on_command(frame.message);
        }
        while let Some(event) = decoder.poll() {
            if let Ok(frame) = event {
                on_command(frame.message);
            }
        }
    }
}
