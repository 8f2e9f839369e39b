//! Row: the Pixy2 request decoder on the camera's side, fed by `push`/`poll`.
#![no_std]
#![no_main]

use robowire::pixy2::{self, DeviceDecoder, Request};
use robowire_size::{out, read_byte, Static};

#[no_mangle]
static DECODER: Static<DeviceDecoder> = Static::new(pixy2::device_decoder());

fn on_request(request: &Request) {
    match request {
        Request::SetLed(led) => out(u32::from_le_bytes([led.r, led.g, led.b, 1])),
        Request::GetVersion(_) => out(0x200),
        _ => out(0x300),
    }
}

#[no_mangle]
pub extern "C" fn _start() -> ! {
    let decoder = DECODER.get();
    loop {
        let byte = read_byte();
        if let Some(Ok(frame)) = decoder.push(byte) {
            on_request(&frame.message.body);
        }
        while let Some(event) = decoder.poll() {
            if let Ok(frame) = event {
                on_request(&frame.message.body);
            }
        }
    }
}
