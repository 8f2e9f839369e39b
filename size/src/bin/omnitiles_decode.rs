//! Row: the same decoder fed a slice at a time through `decode`, as a DMA
//! half-buffer or an idle-line read feeds it.
#![no_std]
#![no_main]

use robowire::omnitiles::{Command, Device, Framing, DEVICE_BUFFER};
use robowire::StreamDecoder;
use robowire_size::{out, read_byte, Static};

/// The firmware-sized command decoder: the framing's 14-byte buffer and
/// `u32` counters.
type DeviceDecoder = StreamDecoder<Framing<Device>, DEVICE_BUFFER, u32>;

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
    let mut chunk = [0u8; 16];
    loop {
        // A read of up to 16 bytes (the length comes from the hardware).
        let n = usize::from(read_byte() & 15);
        for byte in chunk.iter_mut() {
            *byte = read_byte();
        }
        let mut input = &chunk[..n];
        while let Some(event) = decoder.decode(&mut input) {
            if let Ok(frame) = event {
                on_command(frame.message);
            }
        }
    }
}
