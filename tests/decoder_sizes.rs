//! `size_of` of every decoder type is what docs/embedded.md says it is (on a
//! 64-bit host; the guide gives thumbv7em figures beside them).
#![cfg(target_pointer_width = "64")]

use core::mem::size_of;
use robowire::{omnitiles, pixy2, telemetrix};

#[test]
fn the_embedded_guide_gives_every_decoder_size() {
    let guide = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/docs/embedded.md"))
        .expect("docs/embedded.md");
    let sizes = [
        (
            "omnitiles::HostDecoder",
            size_of::<omnitiles::HostDecoder>(),
        ),
        (
            "omnitiles::DeviceDecoder",
            size_of::<omnitiles::DeviceDecoder>(),
        ),
        (
            "omnitiles::BothDecoder",
            size_of::<omnitiles::BothDecoder>(),
        ),
        (
            "omnitiles::HostDatagramDecoder",
            size_of::<omnitiles::HostDatagramDecoder>(),
        ),
        (
            "omnitiles::DeviceDatagramDecoder",
            size_of::<omnitiles::DeviceDatagramDecoder>(),
        ),
        (
            "omnitiles::BothDatagramDecoder",
            size_of::<omnitiles::BothDatagramDecoder>(),
        ),
        ("pixy2::HostDecoder", size_of::<pixy2::HostDecoder>()),
        ("pixy2::DeviceDecoder", size_of::<pixy2::DeviceDecoder>()),
        ("pixy2::BothDecoder", size_of::<pixy2::BothDecoder>()),
        (
            "telemetrix::HostDecoder",
            size_of::<telemetrix::HostDecoder>(),
        ),
        (
            "telemetrix::DeviceDecoder",
            size_of::<telemetrix::DeviceDecoder>(),
        ),
        (
            "telemetrix::BothDecoder",
            size_of::<telemetrix::BothDecoder>(),
        ),
        (
            "telemetrix::LenientHostDecoder",
            size_of::<telemetrix::LenientHostDecoder>(),
        ),
        (
            "StreamDecoder<omnitiles::Framing<Device>, omnitiles::DEVICE_BUFFER, u32>",
            size_of::<
                robowire::StreamDecoder<
                    omnitiles::Framing<omnitiles::Device>,
                    { omnitiles::DEVICE_BUFFER },
                    u32,
                >,
            >(),
        ),
    ];
    for (name, size) in sizes {
        let prefix = format!("| `{name}` |");
        let row = guide
            .lines()
            .find(|line| line.starts_with(&prefix))
            .unwrap_or_else(|| panic!("docs/embedded.md has no row for {name}"));
        let cells: Vec<&str> = row.split('|').map(str::trim).collect();
        // | type | buffer | 64-bit | thumbv7em |
        assert_eq!(cells[3], size.to_string(), "{name}: {row}");
    }
}
