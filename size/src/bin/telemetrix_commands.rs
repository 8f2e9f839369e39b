//! Row: the Telemetrix command decoder on the Pico's side (built for
//! thumbv6m-none-eabi, the RP2040), fed by `push`/`poll`.
#![no_std]
#![no_main]

use robowire::telemetrix::{self, Command, DeviceDecoder};
use robowire_size::{out, read_byte, Static};

#[no_mangle]
static DECODER: Static<DeviceDecoder> = Static::new(telemetrix::device_decoder());

fn on_command(command: &Command<'_>) {
    match *command {
        Command::DigitalWrite { pin, value } => out(0x100 | u32::from(pin) << 1 | value as u32),
        Command::LoopBack { byte } => out(0x200 | u32::from(byte)),
        _ => out(0x300),
    }
}

#[no_mangle]
pub extern "C" fn _start() -> ! {
    let decoder = DECODER.get();
    loop {
        let byte = read_byte();
        if let Some(Ok(frame)) = decoder.push(byte) {
            on_command(&frame.message);
        }
        while let Some(event) = decoder.poll() {
            if let Ok(frame) = event {
                on_command(&frame.message);
            }
        }
    }
}
