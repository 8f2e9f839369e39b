//! The shape of the Telemetrix API: whole frames through `TryFrom` and
//! `parse_in`, the owned forms, names, and decoder sizes.

use robowire::telemetrix::{
    both_decoder, device_decoder, host_decoder, BothDecoder, Command, CommandBuf, DeviceDecoder,
    Dialect, Error, HostDecoder, LenientHostDecoder, Message, MessageBuf, Report, ReportBuf,
    BOTH_BUFFER, DEVICE_BUFFER, HOST_BUFFER, LENIENT_BUFFER, MAX_FRAME_LEN,
};
use robowire::Encode;

#[test]
fn one_whole_frame_parses_into_every_message_type() {
    let ping = [0x02, 0x20, 0x07];
    assert_eq!(
        Command::try_from(&ping[..]),
        Ok(Command::Ping { counter: 7 })
    );
    assert_eq!(
        CommandBuf::try_from(&ping[..]).unwrap(),
        Command::Ping { counter: 7 }
    );
    assert_eq!(
        Message::try_from(&ping[..]),
        Ok(Message::Command(Command::Ping { counter: 7 }))
    );
    let pong = [0x03, 0x20, 0x07, 0x2A];
    let report = Report::Pong {
        counter: 7,
        boot_id: 42,
    };
    assert_eq!(Report::try_from(&pong[..]), Ok(report));
    assert_eq!(ReportBuf::try_from(&pong[..]).unwrap(), report);
    assert_eq!(
        MessageBuf::try_from(&pong[..]).unwrap().message(),
        Message::Report(report)
    );
    // A digital write is byte for byte a digital report: read as the report.
    let level = [0x03, 0x02, 0x19, 0x01];
    assert_eq!(
        Message::try_from(&level[..]),
        Ok(Message::Report(Report::Digital {
            pin: 25,
            value: true
        }))
    );
    // The dialect decides the layout.
    let sonar = [0x04, 0x0B, 0x09, 0x01, 0x17];
    assert!(matches!(
        Report::parse_in(&sonar, Dialect::Mirte12),
        Ok(Report::Sonar(_))
    ));
    assert!(Command::parse_in(&ping, Dialect::Upstream11).is_err());
}

#[test]
fn a_slice_that_is_not_exactly_one_frame_is_an_error() {
    let ping = [0x02, 0x20, 0x07, 0x00];
    assert_eq!(
        Command::try_from(&ping[..]),
        Err(Error::BadLength { id: 0x20, len: 2 })
    );
    assert!(Command::try_from(&ping[..2]).is_err());
    assert!(Report::try_from(&[0x03][..]).is_err());
    assert!(Message::try_from(&[][..]).is_err());
    assert!(CommandBuf::try_from(&[0x02, 0x20, 0x07, 0x07][..]).is_err());
}

#[test]
fn owned_forms_hold_the_frame() {
    let command = Command::I2cWrite {
        port: 0,
        addr: 0x3C,
        msg_id: 7,
        no_stop: 0,
        data: &[0x00, 0xAF],
    };
    let owned = command.to_buf().unwrap();
    assert_eq!(
        &owned[..],
        &[0x08, 0x0C, 0x00, 0x3C, 0x07, 0x02, 0x00, 0x00, 0xAF]
    );
    assert_eq!(owned.message(), command);
    assert_eq!(Command::from(&owned), command);
    assert_eq!(owned.encoded_len(), 9);
    let mut out = [0u8; 9];
    assert_eq!(owned.encode(&mut out), Ok(9));
    assert_eq!(out, owned.frame());
    assert!(owned.encode(&mut [0u8; 4]).is_err());
    // A value the firmware would mishandle is refused, as by the encoder.
    assert!(Command::DigitalWrite {
        pin: 30,
        value: true
    }
    .to_buf()
    .is_err());
    // Each dialect's own layout, parsed in it, is kept in it.
    let upstream = CommandBuf::parse_in(
        &[0x07, 0x0C, 0x00, 0x3C, 0x02, 0x01, 0x01, 0xAF],
        Dialect::Upstream11,
    )
    .unwrap();
    assert_eq!(upstream.dialect(), Dialect::Upstream11);
    assert!(matches!(
        upstream.message(),
        Command::I2cWriteUpstream { .. }
    ));
}

#[test]
fn decoders_own_what_they_parse_in_the_right_dialect() {
    // An upstream I2C write is also a valid mirte frame of other values: the
    // owned form must keep the upstream reading.
    let frame = [0x07, 0x0C, 0x00, 0x3C, 0x02, 0x01, 0x01, 0xAF];
    let mut decoder =
        DeviceDecoder::new(robowire::telemetrix::Framing::new().with_dialect(Dialect::Upstream11));
    let owned: Vec<CommandBuf> = decoder
        .feed(&frame)
        .map(|event| event.unwrap().message)
        .collect();
    assert_eq!(owned.len(), 1);
    assert_eq!(
        owned[0].message(),
        Command::parse_in(&frame, Dialect::Upstream11).unwrap()
    );
    assert_eq!(owned[0].frame(), &frame[..]);
}

#[test]
fn type_names_are_the_messages_names() {
    assert_eq!(Command::NAMES.len(), 39);
    assert_eq!(Report::NAMES.len(), 23);
    assert_eq!(
        Message::NAMES.len(),
        Command::NAMES.len() + Report::NAMES.len()
    );
    assert_eq!(Message::NAMES[..39], *Command::NAMES);
    assert_eq!(Message::NAMES[39..], *Report::NAMES);
    let mut all = Message::NAMES.to_vec();
    all.sort_unstable();
    all.dedup();
    assert_eq!(all.len(), Message::NAMES.len(), "a name used twice");
    assert_eq!(Command::Ping { counter: 1 }.name(), "ping");
    assert_eq!(
        Message::Report(Report::Id { id: 1 }).name(),
        "get_id_report"
    );
}

#[test]
fn decoder_sizes_and_buffers() {
    assert_eq!(
        (HOST_BUFFER, DEVICE_BUFFER, BOTH_BUFFER, LENIENT_BUFFER),
        (256, 32, 512, 512)
    );
    assert_eq!(MAX_FRAME_LEN, 256);
    assert_eq!(<Command<'_> as Encode>::MAX_LEN, 31);
    assert_eq!(<Report<'_> as Encode>::MAX_LEN, 256);
    let sizes = (
        core::mem::size_of::<HostDecoder>(),
        core::mem::size_of::<DeviceDecoder>(),
        core::mem::size_of::<BothDecoder>(),
        core::mem::size_of::<LenientHostDecoder>(),
    );
    let owned = (
        core::mem::size_of::<CommandBuf>(),
        core::mem::size_of::<ReportBuf>(),
        core::mem::size_of::<MessageBuf>(),
    );
    // The documented sizes (telemetrix module docs) on a 64-bit target.
    if cfg!(target_pointer_width = "64") {
        assert_eq!(sizes, (360, 136, 616, 616), "{sizes:?}");
    }
    assert_eq!(owned, (32, 258, 261));
    let _ = host_decoder();
    let _ = device_decoder();
    let _ = both_decoder();
}
