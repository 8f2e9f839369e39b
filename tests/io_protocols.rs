//! Every integration covers every protocol: Pixy2 and Telemetrix through the
//! tokio-util codec and the embedded-io packet reader and writer (OmniTiles
//! has its own, fuller tests in io_tokio.rs and io_embedded.rs).
#![cfg(any(feature = "tokio-util-07", feature = "embedded-io-07"))]

fn hex(s: &str) -> Vec<u8> {
    s.split_whitespace()
        .map(|b| u8::from_str_radix(b, 16).unwrap())
        .collect()
}

/// Pixy2 responses as a device sends them over SPI: filler, a doubled first
/// sync byte, a frame with a bad checksum, ERROR −2, then blocks.
fn pixy2_responses() -> Vec<u8> {
    hex("01 01 af af c1 01 04 3d 00 3d 00 00 00 \
         af c1 03 01 fe 00 fd \
         af c1 03 01 fe 00 fe \
         af c1 21 0e b7 01 01 00 64 00 32 00 14 00 0a 00 00 00 03 ff")
}

/// Telemetrix reports with `00` padding and a garbage byte between them.
fn telemetrix_reports() -> Vec<u8> {
    hex("00 00 03 02 0a 01 ff 04 03 1a 08 00 05 0b 09 0a 00 64 03 20 07 2a")
}

#[cfg(feature = "tokio-util-07")]
mod tokio_codec {
    use super::*;
    use futures_util::{SinkExt, StreamExt};
    use robowire::io::tokio::{Pixy2HostCodec, TelemetrixHostCodec, TelemetrixPicoCodec};
    use robowire::pixy2::{DeviceError, Form, GetFps, Request, ResponseBuf};
    use robowire::telemetrix::{Command, Report, ReportBuf};
    use tokio::io::AsyncWriteExt;
    use tokio_util::codec::{FramedRead, FramedWrite};

    #[tokio::test]
    async fn pixy2_host_reads_responses_through_noise() {
        let (mut tx, rx) = tokio::io::duplex(5);
        tokio::spawn(async move { tx.write_all(&pixy2_responses()).await.unwrap() });
        let mut read = FramedRead::new(rx, Pixy2HostCodec::default());
        let mut bodies = Vec::new();
        while let Some(item) = read.next().await {
            let frame = item.unwrap();
            assert_eq!(frame.message.form, Form::Checksum);
            bodies.push(frame.message.body);
        }
        assert_eq!(bodies.len(), 3, "{bodies:?}");
        assert_eq!(bodies[0], ResponseBuf::Result(61));
        assert_eq!(bodies[1], ResponseBuf::Error(DeviceError::Busy));
        assert!(matches!(bodies[2], ResponseBuf::Blocks(_)));
        assert_eq!(read.decoder().stats().checksum_failures, 1);
    }

    #[tokio::test]
    async fn pixy2_host_writes_requests() {
        let mut out = Vec::new();
        let mut write = FramedWrite::new(&mut out, Pixy2HostCodec::default());
        write.send(&Request::GetFps(GetFps)).await.unwrap();
        drop(write);
        assert_eq!(out, hex("ae c1 18 00"));
    }

    #[tokio::test]
    async fn telemetrix_both_sides() {
        let (mut tx, rx) = tokio::io::duplex(3);
        tokio::spawn(async move { tx.write_all(&telemetrix_reports()).await.unwrap() });
        let reports: Vec<ReportBuf> = FramedRead::new(rx, TelemetrixHostCodec::default())
            .map(|item| item.unwrap().message)
            .collect()
            .await;
        assert_eq!(reports.len(), 4, "{reports:?}");
        assert_eq!(
            reports[0].message(),
            Report::Digital {
                pin: 10,
                value: true
            }
        );
        assert_eq!(
            reports[1].message(),
            Report::Analog {
                pin: 26,
                value: 2048
            }
        );
        assert_eq!(
            reports[3].message(),
            Report::Pong {
                counter: 7,
                boot_id: 42
            }
        );

        // The Pico side encodes reports and decodes commands.
        let mut out = Vec::new();
        let mut write = FramedWrite::new(&mut out, TelemetrixPicoCodec::default());
        write
            .send(&Report::Pong {
                counter: 7,
                boot_id: 42,
            })
            .await
            .unwrap();
        drop(write);
        assert_eq!(out, hex("03 20 07 2a"));
        let commands: Vec<_> = FramedRead::new(
            &hex("00 00 02 20 07 01 05")[..],
            TelemetrixPicoCodec::default(),
        )
        .map(|item| item.unwrap().message)
        .collect()
        .await;
        assert_eq!(commands.len(), 2);
        assert_eq!(commands[0].message(), Command::Ping { counter: 7 });
        assert_eq!(commands[1].message(), Command::GetFirmwareVersion);
    }
}

#[cfg(feature = "embedded-io-07")]
mod embedded {
    use super::*;
    use robowire::io::embedded_io::{PacketReader, PacketWriter};
    use robowire::pixy2::{self, DeviceError, Envelope, Form, Request, ResponseBuf};
    use robowire::telemetrix::{Device, DeviceDecoder, Framing, Host, HostDecoder, Report};

    #[test]
    fn pixy2_host_reader_and_device_writer() {
        let bytes = pixy2_responses();
        let mut reader = PacketReader::new(&bytes[..], pixy2::host_decoder(), [0u8; 16]);
        let mut bodies = Vec::new();
        while let Some(frame) = reader.read_message().unwrap() {
            bodies.push(frame.message.body);
        }
        assert_eq!(bodies.len(), 3);
        assert_eq!(bodies[0], ResponseBuf::Result(61));
        assert_eq!(bodies[1], ResponseBuf::Error(DeviceError::Busy));
        assert_eq!(reader.stats().checksum_failures, 1);

        // A simulated device answers in checksum form.
        let mut uart = [0u8; 32];
        let mut writer: PacketWriter<&mut [u8], 261> = PacketWriter::new(&mut uart[..]);
        let n = writer
            .send(&Envelope::new(Form::Checksum, ResponseBuf::Result(61)))
            .unwrap();
        assert_eq!(&uart[..n], &hex("af c1 01 04 3d 00 3d 00 00 00")[..]);

        // And reads requests with the device decoder.
        let requests = hex("ae c1 18 00 ae c1 0e 00");
        let mut reader = PacketReader::new(&requests[..], pixy2::device_decoder(), [0u8; 3]);
        let mut got = Vec::new();
        while let Some(frame) = reader.read_message().unwrap() {
            got.push(frame.message.body);
        }
        assert!(
            matches!(got[..], [Request::GetFps(_), Request::GetVersion(_)]),
            "{got:?}"
        );
    }

    #[test]
    fn telemetrix_host_reader_and_pico_writer() {
        let bytes = telemetrix_reports();
        let mut reader = PacketReader::new(
            &bytes[..],
            HostDecoder::new(Framing::<Host>::new()),
            [0u8; 4],
        );
        let mut n = 0;
        while let Some(frame) = reader.read_message().unwrap() {
            n += 1;
            assert!(frame.len >= 3);
        }
        assert_eq!(n, 4);
        let mut uart = [0u8; 8];
        let mut writer: PacketWriter<&mut [u8], 64> = PacketWriter::new(&mut uart[..]);
        let len = writer
            .send(&Report::Digital {
                pin: 10,
                value: true,
            })
            .unwrap();
        assert_eq!(&uart[..len], &hex("03 02 0a 01")[..]);
        let commands = hex("01 05 02 20 07");
        let mut reader = PacketReader::new(
            &commands[..],
            DeviceDecoder::new(Framing::<Device>::new()),
            [0u8; 1],
        );
        assert!(reader.read_message().unwrap().is_some());
        assert!(reader.read_message().unwrap().is_some());
        assert!(reader.read_message().unwrap().is_none());
    }
}
