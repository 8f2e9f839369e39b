//! The optional `serde` and `defmt` derives on the protocol-neutral types.

#[cfg(feature = "serde")]
#[test]
fn serde_round_trips_reports_and_counters() {
    use robowire::{EncodeError, OwnedFrame, Rejected, Stats};

    let mut decoder = robowire::omnitiles::device_decoder();
    decoder
        .feed(&[0x00, 0xa5, 0x50, 0x51, 0xa5, 0x50, 0x50])
        .for_each(drop);
    let stats = decoder.stats();
    let json = serde_json::to_string(&stats).unwrap();
    assert_eq!(
        json,
        r#"{"bytes":7,"frames":1,"frame_bytes":3,"skipped":4,"checksum_failures":1,"other_rejections":0,"malformed":0,"superseded":0}"#
    );
    assert_eq!(serde_json::from_str::<Stats>(&json).unwrap(), stats);
    // The 0.2 names still read.
    let old = r#"{"bytes":7,"frames":1,"frame_bytes":3,"skipped":4,"checksum_errors":1,"rejected":0,"malformed":0,"superseded":0}"#;
    assert_eq!(serde_json::from_str::<Stats>(old).unwrap(), stats);

    let framed = OwnedFrame {
        offset: 4,
        len: 3,
        message: 7u8,
    };
    let json = serde_json::to_string(&framed).unwrap();
    assert_eq!(json, r#"{"offset":4,"len":3,"message":7}"#);
    assert_eq!(
        serde_json::from_str::<OwnedFrame<u8>>(&json).unwrap(),
        framed
    );

    let rejected = Rejected {
        offset: 1,
        error: 9u8,
    };
    let json = serde_json::to_string(&rejected).unwrap();
    assert_eq!(
        serde_json::from_str::<Rejected<u8>>(&json).unwrap(),
        rejected
    );

    let error = EncodeError::BufferTooSmall {
        needed: 6,
        available: 2,
    };
    assert_eq!(
        serde_json::to_string(&error).unwrap(),
        r#"{"BufferTooSmall":{"needed":6,"available":2}}"#
    );
}

/// Compiles only if every type here implements `defmt::Format`.
#[cfg(feature = "defmt")]
#[test]
fn defmt_formats_reports_and_counters() {
    fn format<T: defmt::Format>() -> &'static str {
        core::any::type_name::<T>()
    }
    let names = [
        format::<robowire::Stats>(),
        format::<robowire::OwnedFrame<u8>>(),
        format::<robowire::Rejected<u8>>(),
        format::<robowire::EncodeError>(),
        format::<robowire::Check<u8>>(),
        format::<robowire::Frame<'static, u8>>(),
        format::<robowire::FrameBuf<8>>(),
        format::<robowire::omnitiles::Motor>(),
        format::<robowire::omnitiles::Command>(),
        format::<robowire::omnitiles::Layout>(),
        format::<robowire::omnitiles::Layouts>(),
        format::<robowire::omnitiles::Imu>(),
        format::<robowire::omnitiles::Telemetry>(),
        format::<robowire::omnitiles::Message>(),
        format::<robowire::omnitiles::Error>(),
        format::<robowire::omnitiles::UnknownName>(),
        format::<robowire::omnitiles::Framing<robowire::omnitiles::Host>>(),
        format::<robowire::omnitiles::Framing<robowire::omnitiles::Device>>(),
        format::<robowire::omnitiles::Framing<robowire::omnitiles::Both>>(),
        format::<robowire::omnitiles::DatagramDecoder<robowire::omnitiles::Both>>(),
        format::<robowire::omnitiles::Datagram<'static, 'static, robowire::omnitiles::Host>>(),
        format::<robowire::pixy2::Block>(),
        format::<robowire::pixy2::BlockIter<'static>>(),
        format::<robowire::pixy2::Blocks<'static>>(),
        format::<robowire::pixy2::BlocksBuf>(),
        format::<robowire::pixy2::Error>(),
        format::<robowire::pixy2::Malformed>(),
        format::<robowire::pixy2::DeviceError>(),
        format::<robowire::pixy2::Vector>(),
        format::<robowire::pixy2::IntersectionLine>(),
        format::<robowire::pixy2::Intersection>(),
        format::<robowire::pixy2::Barcode>(),
        format::<robowire::pixy2::Section<'static>>(),
        format::<robowire::pixy2::Sections<'static>>(),
        format::<robowire::pixy2::Elements<'static, robowire::pixy2::Vector>>(),
        format::<robowire::pixy2::FeatureIter<'static, robowire::pixy2::Barcode>>(),
        format::<robowire::pixy2::Features<'static>>(),
        format::<robowire::pixy2::FeaturesBuf>(),
        format::<robowire::pixy2::Host>(),
        format::<robowire::pixy2::Device>(),
        format::<robowire::pixy2::Both>(),
        format::<robowire::pixy2::Framing<robowire::pixy2::Host>>(),
        format::<robowire::pixy2::Form>(),
        format::<robowire::pixy2::Envelope<robowire::pixy2::Request>>(),
        format::<robowire::pixy2::Message<'static>>(),
        format::<robowire::pixy2::MessageBuf>(),
        format::<robowire::pixy2::PairError>(),
        format::<robowire::pixy2::ProgSwitch>(),
        format::<robowire::pixy2::ProgName>(),
        format::<robowire::pixy2::ChangeProg>(),
        format::<robowire::pixy2::GetResolution>(),
        format::<robowire::pixy2::GetVersion>(),
        format::<robowire::pixy2::SetCameraBrightness>(),
        format::<robowire::pixy2::SetServos>(),
        format::<robowire::pixy2::SetLed>(),
        format::<robowire::pixy2::SetLamp>(),
        format::<robowire::pixy2::GetFps>(),
        format::<robowire::pixy2::GetBlocks>(),
        format::<robowire::pixy2::GetFeatures>(),
        format::<robowire::pixy2::SetMode>(),
        format::<robowire::pixy2::SetVector>(),
        format::<robowire::pixy2::SetNextTurn>(),
        format::<robowire::pixy2::SetDefaultTurn>(),
        format::<robowire::pixy2::ReverseVector>(),
        format::<robowire::pixy2::GetRgb>(),
        format::<robowire::pixy2::Request>(),
        format::<robowire::pixy2::FirmwareType>(),
        format::<robowire::pixy2::Version>(),
        format::<robowire::pixy2::Resolution>(),
        format::<robowire::pixy2::Rgb>(),
        format::<robowire::pixy2::Response<'static>>(),
        format::<robowire::pixy2::ResponseBuf>(),
        format::<robowire::telemetrix::Pull>(),
        format::<robowire::telemetrix::PinMode>(),
        format::<robowire::telemetrix::PwmPin>(),
        format::<robowire::telemetrix::PwmPins>(),
        format::<robowire::telemetrix::ModifyReporting>(),
        format::<robowire::telemetrix::Rgb>(),
        format::<robowire::telemetrix::EncoderKind>(),
        format::<robowire::telemetrix::Pulls>(),
        format::<robowire::telemetrix::Command<'static>>(),
        format::<robowire::telemetrix::CommandBuf>(),
        format::<robowire::telemetrix::Dialect>(),
        format::<robowire::telemetrix::Error>(),
        format::<robowire::telemetrix::UnknownName>(),
        format::<robowire::telemetrix::Framing<robowire::telemetrix::Host>>(),
        format::<robowire::telemetrix::Framing<robowire::telemetrix::Device>>(),
        format::<robowire::telemetrix::Framing<robowire::telemetrix::Both>>(),
        format::<robowire::telemetrix::Payload<4>>(),
        format::<robowire::telemetrix::List<u16, 8>>(),
        format::<robowire::telemetrix::ModuleType>(),
        format::<robowire::telemetrix::Pca9685Config>(),
        format::<robowire::telemetrix::ModuleInit<'static>>(),
        format::<robowire::telemetrix::ModuleNew<'static>>(),
        format::<robowire::telemetrix::ServoMove>(),
        format::<robowire::telemetrix::HiwonderCommand>(),
        format::<robowire::telemetrix::Pca9685Channel>(),
        format::<robowire::telemetrix::Pca9685Command>(),
        format::<robowire::telemetrix::Ssd1306Command>(),
        format::<robowire::telemetrix::RelayCommand>(),
        format::<robowire::telemetrix::ServoPosition>(),
        format::<robowire::telemetrix::ServoPositions<'static>>(),
        format::<robowire::telemetrix::Ssd1306Done>(),
        format::<robowire::telemetrix::ModuleReport<'static>>(),
        format::<robowire::telemetrix::SonarReading>(),
        format::<robowire::telemetrix::Sonar>(),
        format::<robowire::telemetrix::Report<'static>>(),
        format::<robowire::telemetrix::ReportBuf>(),
        format::<robowire::telemetrix::Message<'static>>(),
        format::<robowire::telemetrix::MessageBuf>(),
        format::<robowire::telemetrix::SensorType>(),
        format::<robowire::telemetrix::SensorNew>(),
        format::<robowire::telemetrix::SensorReading>(),
        format::<robowire::telemetrix::InDialect<'static, robowire::telemetrix::Report<'static>>>(),
    ];
    assert!(names.iter().all(|n| n.starts_with("robowire::")));
}

#[cfg(all(
    feature = "defmt",
    any(feature = "embedded-io-07", feature = "embedded-io-async-07")
))]
#[test]
fn defmt_formats_write_errors() {
    fn format<T: defmt::Format>() -> &'static str {
        core::any::type_name::<T>()
    }
    assert!(format::<robowire::io::WriteError<u8>>().contains("WriteError"));
}

/// Serialize `value` to JSON, check the text, and read it back.
#[cfg(feature = "serde")]
fn json_round_trip<T>(value: &T, expected: &str)
where
    T: serde::Serialize + serde::de::DeserializeOwned + PartialEq + core::fmt::Debug,
{
    let json = serde_json::to_string(value).unwrap();
    assert_eq!(json, expected);
    assert_eq!(&serde_json::from_str::<T>(&json).unwrap(), value);
}

#[cfg(feature = "serde")]
#[test]
fn serde_engine_types() {
    use robowire::{Check, Frame, FrameBuf};

    json_round_trip(&Check::<u8>::Need(4), r#"{"Need":4}"#);
    json_round_trip(&Check::<u8>::Reject(2), r#"{"Reject":2}"#);

    let frame = Frame {
        offset: 3,
        raw: &[0xa5, 0x50, 0x50][..],
        message: 1u8,
    };
    assert_eq!(
        serde_json::to_string(&frame).unwrap(),
        r#"{"offset":3,"len":3,"message":1}"#
    );

    let buf = FrameBuf::<8>::encode(&robowire::omnitiles::Command::Ping).unwrap();
    json_round_trip(&buf, "[165,80,80]");
    json_round_trip(&FrameBuf::<8>::new(), "[]");
    let too_long = serde_json::from_str::<FrameBuf<2>>("[165,80,80]").unwrap_err();
    assert!(
        too_long.to_string().contains("at most 2 bytes"),
        "{too_long}"
    );
}

#[cfg(feature = "serde")]
#[test]
fn serde_omnitiles_commands_and_config() {
    use robowire::omnitiles::{
        Both, Command, Device, Error, Framing, Host, Layout, Layouts, Message, Motor,
    };

    // Messages and errors are the command-line tool's JSON lines.
    json_round_trip(
        &Message::Command(Command::Extend {
            motor: Motor::M1,
            speed: 200,
        }),
        r#"{"type":"m1_extend","speed":200}"#,
    );
    json_round_trip(&Command::Ping, r#"{"type":"ping"}"#);
    json_round_trip(
        &Command::BaseVelocity {
            vx: -127,
            vy: 0,
            omega: 5,
        },
        r#"{"type":"base_velocity","vx":-127,"vy":0,"omega":5}"#,
    );
    json_round_trip(&Motor::M2, r#""m2""#);
    json_round_trip(&Layout::UwbTof17, r#""uwbtof17""#);
    json_round_trip(&Layouts::DOCUMENTED, "23");
    json_round_trip(&Layouts::NONE, "0");
    json_round_trip(
        &Framing::<Host>::new().with_layouts(Layouts::only(Layout::Spi45)),
        r#"{"layouts":8}"#,
    );
    json_round_trip(&Framing::<Device>::new(), r#"{"layouts":0}"#);
    json_round_trip(&Framing::<Both>::new(), r#"{"layouts":23}"#);
    json_round_trip(
        &Error::Checksum {
            expected: 0xf8,
            found: 0xf7,
        },
        r#"{"error":"checksum","expected":248,"found":247}"#,
    );
    json_round_trip(&Error::Unconfirmed, r#"{"error":"unconfirmed"}"#);
    json_round_trip(
        &Error::Superseded { len: 7 },
        r#"{"error":"superseded","len":7}"#,
    );
    // A command is no telemetry, and the other way round.
    let err = serde_json::from_str::<Command>(
        r#"{"type":"telemetry","layout":"pos7","m1_pos":1,"m2_pos":2}"#,
    )
    .unwrap_err();
    assert!(
        err.to_string()
            .starts_with("type `telemetry` is not a command"),
        "{err}"
    );
    let err =
        serde_json::from_str::<robowire::omnitiles::Telemetry>(r#"{"type":"ping"}"#).unwrap_err();
    assert!(
        err.to_string().starts_with("type `ping` is not telemetry"),
        "{err}"
    );
}

#[cfg(feature = "serde")]
#[test]
fn serde_omnitiles_refuses_undefined_layout_bits() {
    use robowire::omnitiles::{Both, Device, Framing, Layouts};

    assert_eq!(serde_json::from_str::<Layouts>("31").unwrap(), Layouts::ALL);
    for bits in ["32", "255", "33"] {
        let err = serde_json::from_str::<Layouts>(bits).unwrap_err();
        assert!(err.to_string().contains("telemetry layouts"), "{err}");
    }
    assert!(serde_json::from_str::<Layouts>("256").is_err());
    assert!(serde_json::from_str::<Framing<Both>>(r#"{"layouts":64}"#).is_err());
    // A device framing accepts no telemetry.
    let err = serde_json::from_str::<Framing<Device>>(r#"{"layouts":1}"#).unwrap_err();
    assert!(err.to_string().contains("commands only"), "{err}");
}

#[cfg(feature = "serde")]
#[test]
fn serde_omnitiles_telemetry() {
    use robowire::omnitiles::{Imu, Layout, Message, Telemetry};
    use robowire::FrameBuf;

    // A BLE frame, decoded from its bytes.
    let mut sent = Telemetry::empty(Layout::Ble53);
    sent.m1_pos = Some(2000);
    sent.uwb = Some([Some(1200), None, Some(800), None]);
    sent.imu = Some(Imu::from_array([0.5, -0.25, 9.75, 0.0, 0.125, -1.5]));
    sent.m1_adcs = Some([1, 2, 3, 4]);
    sent.m2_adcs = Some([5, 6]);
    let frame = FrameBuf::<64>::encode(&sent).unwrap();
    let telemetry = Telemetry::try_from(&frame[..]).unwrap();
    assert_eq!(telemetry, sent);
    assert_eq!(telemetry.tof, Some(None));
    json_round_trip(
        &Message::Telemetry(telemetry),
        concat!(
            r#"{"type":"telemetry","layout":"ble53","m1_pos":2000,"m2_pos":null,"#,
            r#""uwb":[1200,null,800,null],"tof":null,"#,
            r#""imu":{"ax":0.5,"ay":-0.25,"az":9.75,"gx":0.0,"gy":0.125,"gz":-1.5},"#,
            r#""m1_adcs":[1,2,3,4],"m2_adcs":[5,6]}"#
        ),
    );

    // A group the layout does not carry is absent; `null` is no reading.
    let short = Telemetry::try_from(&[0xa5, 0x60, 0xd0, 0x07, 0xe8, 0x03, 0x22][..]).unwrap();
    assert_eq!(short.tof, None);
    json_round_trip(
        &short,
        r#"{"type":"telemetry","layout":"pos7","m1_pos":2000,"m2_pos":1000}"#,
    );
    let with_tof = Telemetry {
        tof: Some(Some(310)),
        ..Telemetry::empty(Layout::UwbTof17)
    };
    json_round_trip(
        &with_tof,
        r#"{"type":"telemetry","layout":"uwbtof17","m1_pos":null,"m2_pos":null,"uwb":[null,null,null,null],"tof":310}"#,
    );

    // Field groups the layout does not carry (or lacks) are refused.
    let imu_in_pos7 = r#"{"type":"telemetry","layout":"pos7","m1_pos":1,"m2_pos":2,
        "imu":{"ax":0.0,"ay":0.0,"az":0.0,"gx":0.0,"gy":0.0,"gz":0.0}}"#;
    let err = serde_json::from_str::<Telemetry>(imu_in_pos7).unwrap_err();
    assert!(
        err.to_string()
            .starts_with("layout pos7 does not carry `imu`"),
        "{err}"
    );
    let ble_without_adcs = r#"{"type":"telemetry","layout":"ble53","m1_pos":1,"m2_pos":2,"uwb":[1,2,3,4],"tof":5,
        "imu":{"ax":0.0,"ay":0.0,"az":0.0,"gx":0.0,"gy":0.0,"gz":0.0}}"#;
    let err = serde_json::from_str::<Telemetry>(ble_without_adcs).unwrap_err();
    assert!(
        err.to_string()
            .starts_with("missing field `m1_adcs` (layout ble53 carries it)"),
        "{err}"
    );

    // NaN and infinities are strings that read back bit for bit.
    let nan = Telemetry {
        imu: Some(Imu::from_array([
            f32::NAN,
            f32::INFINITY,
            0.0,
            0.0,
            0.0,
            0.0,
        ])),
        ..Telemetry::empty(Layout::Spi45)
    };
    let json = serde_json::to_string(&nan).unwrap();
    assert!(
        json.contains(r#""ax":"nan:0x7fc00000","ay":"inf""#),
        "{json}"
    );
    assert_eq!(serde_json::from_str::<Telemetry>(&json).unwrap(), nan);
    // An IMU sample alone is the `imu` object.
    json_round_trip(
        &Imu::from_array([0.1, 0.0, 9.8, 0.0, -0.0, 1e-3]),
        r#"{"ax":0.1,"ay":0.0,"az":9.8,"gx":0.0,"gy":-0.0,"gz":0.001}"#,
    );
}

#[cfg(feature = "serde")]
#[test]
fn serde_pixy2_requests() {
    use robowire::pixy2::{
        ChangeProg, Envelope, Form, GetBlocks, Host, MessageBuf, ProgName, Request, SetServos,
    };

    json_round_trip(
        &Envelope::new(
            Form::NoChecksum,
            Request::from(GetBlocks {
                sigmap: GetBlocks::ALL,
                max_blocks: 4,
            }),
        ),
        r#"{"type":"get_blocks","checksum":false,"sigmap":255,"max_blocks":4}"#,
    );
    json_round_trip(
        &MessageBuf::Request(Request::from(SetServos { pan: 500, tilt: 20 })),
        r#"{"type":"set_servos","pan":500,"tilt":20}"#,
    );

    // A program name is its text; a payload of other than 33 bytes says so.
    json_round_trip(
        &Request::from(ChangeProg(ProgName::LINE_TRACKING)),
        r#"{"type":"change_prog","name":"line_tracking"}"#,
    );
    json_round_trip(
        &Request::from(ChangeProg(ProgName::from_payload(b"video").unwrap())),
        r#"{"type":"change_prog","name":"video","payload_len":5}"#,
    );
    // ProgName alone is its payload bytes, padding included.
    let short = ProgName::from_payload(b"video").unwrap();
    json_round_trip(&short, "[118,105,100,101,111]");
    let too_long = format!("[{}]", ["120"; 65].join(","));
    let err = serde_json::from_str::<ProgName>(&too_long).unwrap_err();
    assert!(err.to_string().contains("at most 64 bytes"), "{err}");

    json_round_trip(&Form::Checksum, r#""checksum""#);
    json_round_trip(
        &robowire::pixy2::Framing::<Host>::new().checksum_only(),
        r#"{"checksum_only":true}"#,
    );
}

#[cfg(feature = "serde")]
#[test]
fn serde_pixy2_owned_blocks_response() {
    use robowire::pixy2::{self, Block, BlocksBuf, Envelope, Response, ResponseBuf, MAX_BLOCKS};

    let bytes = [
        0xaf, 0xc1, 0x21, 0x0e, 0xb7, 0x01, 0x01, 0x00, 0x64, 0x00, 0x32, 0x00, 0x14, 0x00, 0x0a,
        0x00, 0x00, 0x00, 0x03, 0xff,
    ];
    let mut decoder = pixy2::host_decoder();
    let owned: Vec<Envelope<ResponseBuf>> = decoder
        .feed(&bytes)
        .map(|event| event.unwrap().message)
        .collect();
    assert_eq!(owned.len(), 1);
    let block_json =
        r#"{"signature":1,"x":100,"y":50,"width":20,"height":10,"angle":0,"index":3,"age":255}"#;
    json_round_trip(
        &owned[0],
        &format!(r#"{{"type":"blocks","checksum":true,"blocks":[{block_json}]}}"#),
    );

    // The borrowed response, straight from the frame, serializes as the owned one.
    let mut input = &bytes[..];
    let mut fresh = pixy2::host_decoder();
    let frame = fresh.decode(&mut input).unwrap().unwrap();
    let view: Response<'_> = frame.message.body;
    assert_eq!(
        serde_json::to_string(&view).unwrap(),
        serde_json::to_string(&owned[0].body).unwrap()
    );

    // At most 18 blocks.
    let full = BlocksBuf::from_blocks(&[Block::default(); MAX_BLOCKS]).unwrap();
    let json = serde_json::to_string(&full).unwrap();
    assert_eq!(serde_json::from_str::<BlocksBuf>(&json).unwrap(), full);
    let nineteen = format!("[{block_json},{}]", &json[1..json.len() - 1]);
    let err = serde_json::from_str::<BlocksBuf>(&nineteen).unwrap_err();
    assert!(err.to_string().contains("at most 18"), "{err}");
}

#[cfg(feature = "serde")]
#[test]
fn serde_pixy2_owned_features_response() {
    use robowire::pixy2::{
        Barcode, DeviceError, Error, FeaturesBuf, Intersection, IntersectionLine, Malformed,
        PairError, Response, ResponseBuf, Vector,
    };

    let vector = Vector {
        x0: 10,
        y0: 51,
        x1: 40,
        y1: 2,
        index: 7,
        flags: 0,
    };
    let barcode = Barcode {
        x: 30,
        y: 20,
        flags: 0,
        code: 5,
    };
    let features = FeaturesBuf::from_parts(&[vector], &[], &[barcode]).unwrap();
    let sections = concat!(
        r#"[{"vectors":[{"x0":10,"y0":51,"x1":40,"y1":2,"index":7,"flags":0}]},"#,
        r#"{"barcodes":[{"x":30,"y":20,"flags":0,"code":5}]}]"#
    );
    json_round_trip(
        &ResponseBuf::Features(features),
        &format!(r#"{{"type":"features","sections":{sections}}}"#),
    );
    assert_eq!(
        serde_json::to_string(&Response::Features(features.view())).unwrap(),
        format!(r#"{{"type":"features","sections":{sections}}}"#)
    );
    json_round_trip(&features, sections);

    // Intersections and sections of unknown types keep every byte.
    let mut slots = [IntersectionLine::default(); 6];
    slots[0] = IntersectionLine {
        index: 1,
        reserved: 9,
        angle: -90,
    };
    slots[3].index = 4;
    let crossing = Intersection {
        x: 39,
        y: 20,
        n: 1,
        reserved: 0,
        slots,
    };
    json_round_trip(
        &crossing,
        concat!(
            r#"{"x":39,"y":20,"lines":[{"index":1,"angle":-90,"reserved":9}],"#,
            r#""unused_slots":[{"index":0,"angle":0},{"index":0,"angle":0},"#,
            r#"{"index":4,"angle":0},{"index":0,"angle":0},{"index":0,"angle":0}]}"#
        ),
    );
    let with_crossing = FeaturesBuf::from_parts(&[vector], &[crossing], &[]).unwrap();
    let mut payload = with_crossing.view().as_bytes().to_vec();
    payload.extend_from_slice(&[0x08, 0x02, 0xaa, 0xbb]);
    let unknown = FeaturesBuf::from_payload(&payload).unwrap();
    let json = serde_json::to_string(&unknown).unwrap();
    assert!(json.ends_with(r#"{"ftype":8,"data":[170,187]}]"#), "{json}");
    let back = serde_json::from_str::<FeaturesBuf>(&json).unwrap();
    assert_eq!(back, unknown);
    assert_eq!(back.view().intersections().next(), Some(crossing));

    // What a features payload cannot hold is refused, naming the field.
    let seven = format!(
        r#"[{{"intersections":[{{"x":1,"y":2,"lines":[{}]}}]}}]"#,
        [r#"{"index":1,"angle":0}"#; 7].join(",")
    );
    let err = serde_json::from_str::<FeaturesBuf>(&seven).unwrap_err();
    assert!(
        err.to_string().starts_with(
            "field `sections[0].intersections[0].lines` holds 7 entries, at most 6 fit"
        ),
        "{err}"
    );
    let err = serde_json::from_str::<FeaturesBuf>(r#"[{"ftype":2,"data":[]}]"#).unwrap_err();
    assert!(err.to_string().contains("is a known feature type"), "{err}");

    json_round_trip(
        &ResponseBuf::Error(DeviceError::Unknown(-9)),
        r#"{"type":"error","code":-9}"#,
    );
    json_round_trip(&DeviceError::Busy, r#""busy""#);
    json_round_trip(
        &Error::Malformed {
            packet_type: 0x31,
            what: Malformed::IntersectionLines { n: 7 },
        },
        r#"{"error":"malformed","packet_type":49,"what":"intersection_lines","n":7}"#,
    );
    json_round_trip(
        &Malformed::SectionPastEnd { offset: 3 },
        r#"{"what":"section_past_end","section_offset":3}"#,
    );
    json_round_trip(
        &PairError::Device(DeviceError::Busy),
        r#"{"Device":"busy"}"#,
    );
}

#[cfg(feature = "serde")]
#[test]
fn serde_telemetrix_is_the_json_lines_schema() {
    use robowire::telemetrix::{
        host_decoder, Command, Dialect, Error, Framing, Host, Report, ReportBuf,
    };

    // The full schema is pinned by tests/schema_telemetrix.rs; here: an
    // owned report from the decoder, the framing configuration and errors.
    let mut decoder = host_decoder();
    let owned: Vec<ReportBuf> = decoder
        .feed(&[0x03, 0x20, 0x07, 0x2A])
        .map(|event| event.unwrap().message)
        .collect();
    json_round_trip(&owned[0], r#"{"type":"pong","counter":7,"boot_id":42}"#);
    assert_eq!(
        serde_json::to_string(&Report::Pong {
            counter: 7,
            boot_id: 42
        })
        .unwrap(),
        r#"{"type":"pong","counter":7,"boot_id":42}"#
    );
    assert_eq!(
        serde_json::to_string(&Command::Ping { counter: 7 }).unwrap(),
        r#"{"type":"ping","counter":7}"#
    );
    json_round_trip(
        &Framing::<Host>::new()
            .with_dialect(Dialect::Upstream11)
            .lenient(),
        r#"{"dialect":"upstream11","lenient":true}"#,
    );
    // The firmware-exact mode is written only when on.
    json_round_trip(
        &robowire::telemetrix::Framing::<robowire::telemetrix::Device>::new().as_firmware(),
        r#"{"dialect":"mirte13","lenient":false,"firmware":true}"#,
    );
    // Serialize only: the field name is a `&'static str`.
    assert_eq!(
        serde_json::to_string(&Error::OutOfRange {
            id: 1,
            field: "pin"
        })
        .unwrap(),
        r#"{"error":"out_of_range","id":1,"field":"pin"}"#
    );
}
