//! The Pixy2 vocabulary: one whole frame through `TryFrom`, `Display` of
//! messages, `FromStr` of named enums, the type names, the decoders' sizes.

use robowire::pixy2::{
    self, BothDecoder, DeviceDecoder, DeviceError, Envelope, Error, Form, GetBlocks, GetFps,
    HostDecoder, Message, MessageBuf, ProgName, Request, Response, ResponseBuf, SetServos,
    BOTH_BUFFER, DEVICE_BUFFER, HOST_BUFFER, MAX_FRAME_LEN,
};
use robowire::Encode;

const GET_BLOCKS: [u8; 6] = [0xae, 0xc1, 0x20, 0x02, 0xff, 0x03];
const BUSY: [u8; 7] = [0xaf, 0xc1, 0x03, 0x01, 0xfe, 0x00, 0xfe];

#[test]
fn one_whole_frame_parses_into_every_message_type() {
    let get = Request::from(GetBlocks {
        sigmap: 0xff,
        max_blocks: 3,
    });
    assert_eq!(Request::try_from(&GET_BLOCKS[..]), Ok(get));
    assert_eq!(
        Envelope::<Request>::try_from(&GET_BLOCKS[..]),
        Ok(Envelope::new(Form::NoChecksum, get))
    );
    assert_eq!(
        Message::try_from(&GET_BLOCKS[..]),
        Ok(Message::Request(get))
    );
    assert_eq!(
        MessageBuf::try_from(&GET_BLOCKS[..]),
        Ok(MessageBuf::Request(get))
    );
    let busy = Response::Error(DeviceError::Busy);
    assert_eq!(Response::try_from(&BUSY[..]), Ok(busy));
    assert_eq!(
        ResponseBuf::try_from(&BUSY[..]),
        Ok(ResponseBuf::Error(DeviceError::Busy))
    );
    assert_eq!(
        Envelope::<Response<'_>>::try_from(&BUSY[..]),
        Ok(Envelope::new(Form::Checksum, busy))
    );
    assert_eq!(
        Envelope::<ResponseBuf>::try_from(&BUSY[..]).map(|e| e.form),
        Ok(Form::Checksum)
    );
    assert_eq!(
        Envelope::<Message<'_>>::try_from(&BUSY[..]),
        Ok(Envelope::new(Form::Checksum, Message::Response(busy)))
    );
    assert_eq!(
        Envelope::<MessageBuf>::try_from(&BUSY[..]).map(|e| e.body),
        Ok(MessageBuf::Response(ResponseBuf::Error(DeviceError::Busy)))
    );
}

#[test]
fn a_slice_that_is_not_exactly_one_frame_is_an_error() {
    // Cut short, with bytes after it, without its sync word.
    assert_eq!(
        Request::try_from(&GET_BLOCKS[..5]),
        Err(Error::Truncated { len: 5 })
    );
    assert_eq!(Request::try_from(&[][..]), Err(Error::Truncated { len: 0 }));
    let mut long = GET_BLOCKS.to_vec();
    long.extend([0x00, 0x01]);
    assert_eq!(
        Request::try_from(&long[..]),
        Err(Error::TrailingBytes { extra: 2 })
    );
    assert_eq!(
        Request::try_from(&GET_BLOCKS[1..]),
        Err(Error::Sync { found: 0xc1 })
    );
    assert_eq!(
        Request::try_from(&[0xae, 0x00, 0x18, 0x00][..]),
        Err(Error::Sync { found: 0x00 })
    );
    // The other direction, a bad checksum, a bad length, a malformed payload.
    assert_eq!(
        Request::try_from(&BUSY[..]),
        Err(Error::UnknownType { packet_type: 0x03 })
    );
    assert_eq!(
        Response::try_from(&GET_BLOCKS[..]),
        Err(Error::UnknownType { packet_type: 0x20 })
    );
    let mut bad_sum = BUSY;
    bad_sum[4] = 0xfd;
    assert_eq!(
        Response::try_from(&bad_sum[..]),
        Err(Error::Checksum {
            expected: 0xfd,
            found: 0xfe
        })
    );
    assert_eq!(
        Request::try_from(&[0xae, 0xc1, 0x12, 0x01, 0x00][..]),
        Err(Error::BadLength {
            packet_type: 0x12,
            len: 1
        })
    );
    // getBlocks with sigmap 0 is a request (the device answers ERROR -3).
    assert_eq!(
        Request::try_from(&[0xae, 0xc1, 0x20, 0x02, 0x00, 0x01][..]),
        Ok(Request::from(GetBlocks {
            sigmap: 0,
            max_blocks: 1
        }))
    );
    // A request over the device's 64-byte limit.
    let mut prog = vec![0xae, 0xc1, 0x02, 65];
    prog.extend([b'x'; 65]);
    assert!(matches!(
        Request::try_from(&prog[..]),
        Err(Error::TooLong { .. })
    ));
}

#[test]
fn decoded_frames_parse_back_whole() {
    let mut wire = Vec::new();
    for message in [
        Envelope::new(Form::NoChecksum, MessageBuf::Request(Request::from(GetFps))),
        Envelope::new(
            Form::Checksum,
            MessageBuf::Response(ResponseBuf::Result(61)),
        ),
        Envelope::new(
            Form::Checksum,
            MessageBuf::Request(Request::from(SetServos { pan: 1, tilt: 2 })),
        ),
    ] {
        let mut out = [0u8; MAX_FRAME_LEN];
        let n = message.encode(&mut out).unwrap();
        assert_eq!(Envelope::<MessageBuf>::try_from(&out[..n]), Ok(message));
        wire.extend_from_slice(&out[..n]);
    }
    let mut decoder = pixy2::both_decoder();
    let frames: Vec<_> = decoder.feed(&wire).map(Result::unwrap).collect();
    assert_eq!(frames.len(), 3);
    for frame in frames {
        let start = frame.offset as usize;
        let bytes = &wire[start..start + frame.len];
        assert_eq!(Envelope::<MessageBuf>::try_from(bytes), Ok(frame.message));
    }
}

#[test]
fn messages_display_as_one_line_of_the_json_words() {
    let cases: [(MessageBuf, &str); 6] = [
        (
            Request::from(GetBlocks {
                sigmap: 255,
                max_blocks: 3,
            })
            .into(),
            "get_blocks sigmap=255 max_blocks=3",
        ),
        (Request::from(GetFps).into(), "get_fps"),
        (
            Request::from(pixy2::ChangeProg(ProgName::new("line").unwrap())).into(),
            "change_prog name=line",
        ),
        (
            ResponseBuf::Error(DeviceError::Busy).into(),
            "error code=busy",
        ),
        (
            ResponseBuf::Error(DeviceError::Unknown(-7)).into(),
            "error code=-7",
        ),
        (
            ResponseBuf::Resolution(pixy2::Resolution {
                width: 316,
                height: 208,
            })
            .into(),
            "resolution width=316 height=208",
        ),
    ];
    for (message, text) in cases {
        assert_eq!(message.to_string(), text);
        assert_eq!(message.as_message().to_string(), text);
    }
    let blocks = Response::try_from(
        &[
            0xaf, 0xc1, 0x21, 0x0e, 0xb7, 0x01, 0x01, 0x00, 0x64, 0x00, 0x32, 0x00, 0x14, 0x00,
            0x0a, 0x00, 0x00, 0x00, 0x03, 0xff,
        ][..],
    )
    .unwrap();
    assert_eq!(
        blocks.to_string(),
        "blocks {signature=1 x=100 y=50 width=20 height=10 angle=0 index=3 age=255}"
    );
    assert_eq!(
        Envelope::new(Form::Checksum, Request::from(GetFps)).to_string(),
        "get_fps checksum=true"
    );
}

#[test]
fn names_read_back() {
    for form in [Form::NoChecksum, Form::Checksum] {
        assert_eq!(form.to_string().parse::<Form>(), Ok(form));
    }
    assert_eq!(Form::NAMES, ["no_checksum", "checksum"]);
    let err = "crc".parse::<Form>().unwrap_err();
    assert_eq!(
        err.to_string(),
        "no frame form is called that (expected no_checksum, checksum)"
    );
    for code in -128..=127i8 {
        let e = DeviceError::from_code(code);
        assert_eq!(code.to_string().parse::<DeviceError>(), Ok(e));
        if let Some(name) = e.name() {
            assert_eq!(name.parse::<DeviceError>(), Ok(e));
            assert_eq!(
                DeviceError::NAMES[usize::from(code.unsigned_abs()) - 1],
                name
            );
        } else {
            assert!(!(-6..=-1).contains(&code));
        }
    }
    assert_eq!("busy".parse::<DeviceError>(), Ok(DeviceError::Busy));
    assert_eq!(
        "bogus".parse::<DeviceError>().unwrap_err().what(),
        "device error"
    );
    let name: ProgName = "video".parse().unwrap();
    assert_eq!(name, ProgName::VIDEO);
    assert_eq!(name.to_string(), "video");
    assert!("x".repeat(33).parse::<ProgName>().is_err());
}

#[test]
fn type_names_are_the_messages_names() {
    assert_eq!(
        Message::NAMES.len(),
        Request::NAMES.len() + Response::NAMES.len()
    );
    assert_eq!(Message::NAMES[..16], Request::NAMES);
    assert_eq!(Message::NAMES[16..], Response::NAMES);
    let mut all = Message::NAMES.to_vec();
    all.sort_unstable();
    all.dedup();
    assert_eq!(all.len(), Message::NAMES.len(), "a name used twice");
    assert_eq!(Request::from(GetFps).name(), "get_fps");
    assert_eq!(Response::Result(0).name(), "result");
}

#[test]
fn decoder_sizes_and_buffers() {
    assert_eq!((HOST_BUFFER, DEVICE_BUFFER, BOTH_BUFFER), (528, 144, 528));
    assert_eq!(MAX_FRAME_LEN, 261);
    let sizes = (
        core::mem::size_of::<HostDecoder>(),
        core::mem::size_of::<DeviceDecoder>(),
        core::mem::size_of::<BothDecoder>(),
    );
    // The documented sizes (pixy2 module docs) on a 64-bit target.
    if cfg!(target_pointer_width = "64") {
        assert_eq!(sizes, (632, 248, 632), "{sizes:?}");
    }
    let _ = pixy2::host_decoder();
    let _ = pixy2::device_decoder();
    let _ = pixy2::both_decoder();
}
