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

/// The checksum summed sixteen lanes at a time is the plain wrapping sum,
/// whatever the length and alignment (every remainder of 16 and of 8).
#[test]
fn checksum_is_the_plain_wrapping_sum() {
    let mut data = [0u8; 600];
    let mut x = 0x9e37_79b9_7f4a_7c15u64;
    for b in &mut data {
        x ^= x << 13;
        x ^= x >> 7;
        x ^= x << 17;
        *b = x as u8;
    }
    let plain = |p: &[u8]| p.iter().fold(0u16, |s, &b| s.wrapping_add(u16::from(b)));
    for start in 0..17 {
        for len in 0..=(data.len() - start) {
            let p = &data[start..start + len];
            assert_eq!(pixy2::checksum(p), plain(p), "from {start}, {len} bytes");
        }
    }
    // All 0xff: the lanes wrap long before a real payload's length.
    let ones = [0xffu8; 600];
    for len in 0..=ones.len() {
        assert_eq!(pixy2::checksum(&ones[..len]), plain(&ones[..len]), "{len}");
    }
}

/// A blocks view iterates the same blocks whichever way it is consumed
/// (`next`, `next_back`, `fold`, as `sum` and `for` use them), for every
/// count of blocks.
#[test]
fn block_iteration_agrees_every_way() {
    use pixy2::{Block, BlocksBuf};
    for n in 0..=pixy2::MAX_BLOCKS {
        let mut buf = BlocksBuf::new();
        for i in 0..n {
            let mut bytes = [0u8; Block::SIZE];
            for (j, b) in bytes.iter_mut().enumerate() {
                *b = (i * 31 + j * 7) as u8;
            }
            buf.push(Block::from_bytes(&bytes)).unwrap();
        }
        let view = buf.view();
        let by_index: Vec<Block> = (0..n).map(|i| view.get(i).unwrap()).collect();
        let mut by_next = Vec::new();
        let mut iter = view.iter();
        assert_eq!(iter.len(), n);
        // A `for` loop takes them one `next` at a time.
        for block in iter.by_ref() {
            by_next.push(block);
        }
        let mut by_back: Vec<Block> = view.iter().rev().collect();
        by_back.reverse();
        let by_fold = view.iter().fold(Vec::new(), |mut v, b| {
            v.push(b);
            v
        });
        assert_eq!(by_next, by_index, "{n} blocks, next");
        assert_eq!(by_back, by_index, "{n} blocks, next_back");
        assert_eq!(by_fold, by_index, "{n} blocks, fold");
        let xs: u64 = view.iter().map(|b| u64::from(b.x)).sum();
        assert_eq!(xs, by_index.iter().map(|b| u64::from(b.x)).sum::<u64>());
        // Mixed ends meet in the middle.
        let mut iter = view.iter();
        let (front, back) = (iter.next(), iter.next_back());
        assert_eq!(front, by_index.first().copied());
        if n > 1 {
            assert_eq!(back, by_index.last().copied());
            assert_eq!(iter.len(), n - 2);
        }
    }
}

/// Every blocks length byte: whole blocks (at most 18) decode, any other
/// length is refused from the header.
#[test]
fn every_blocks_length_byte() {
    for len in 0..=255u8 {
        let mut frame = vec![0xaf, 0xc1, 0x21, len, 0, 0];
        frame.extend(std::iter::repeat(0).take(usize::from(len)));
        let got = Response::try_from(&frame[..]);
        if len % 14 == 0 {
            assert!(
                matches!(got, Ok(Response::Blocks(b)) if b.len() == usize::from(len) / 14),
                "{len}: {got:?}"
            );
        } else {
            assert_eq!(
                got,
                Err(Error::BadLength {
                    packet_type: 0x21,
                    len
                }),
                "{len}"
            );
        }
    }
    assert_eq!(pixy2::Blocks::new(&[0; 252]).map(|b| b.len()), Some(18));
    assert_eq!(pixy2::Blocks::new(&[0; 266]), None);
    assert_eq!(pixy2::Blocks::new(&[0; 13]), None);
}
