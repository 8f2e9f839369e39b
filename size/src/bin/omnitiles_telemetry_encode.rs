//! Row: the OmniTiles 53-byte (BLE) telemetry encoder, as a tile answers.
#![no_std]
#![no_main]

use robowire::omnitiles::{Layout, Telemetry};
use robowire::Encode;
use robowire_size::{out, read_byte};

#[no_mangle]
pub extern "C" fn _start() -> ! {
    let mut frame = [0u8; Telemetry::MAX_LEN];
    loop {
        let m1 = u16::from(read_byte());
        let m2 = u16::from(read_byte());
        let telemetry = Telemetry {
            m1_pos: Some(m1),
            m2_pos: Some(m2),
            m1_adcs: Some([m1; 4]),
            m2_adcs: Some([m2; 2]),
            ..Telemetry::empty(Layout::Ble53)
        };
        if let Ok(n) = telemetry.encode(&mut frame) {
            for &byte in frame.iter().take(n) {
                out(u32::from(byte));
            }
        }
    }
}
