//! The message tables: every Telemetrix message described once, in one
//! place.
//!
//! Each row of the command table gives a command's id, the name of its id
//! constant, its `type` name in the JSON-lines schema, the
//! [`Command`](super::Command) variants that carry it, the dialects that
//! define it, its `LEN` range (one pair, or a `match` on the dialect) and its
//! payload: `plain { field: kind "key", … }` for a command whose fields are
//! fixed bytes in wire order (its variant is built from them, with the row's
//! docs), or `custom { … }` for one whose layout depends on its content or
//! dialect. A `custom` row carries its variants and all of its code, each
//! piece with the names it works on, as a closure names its parameters:
//!
//! ```text
//! custom {
//!     variants { /// docs
//!                Variant { field: Type, … }, … }
//!     parse(dialect, r, id) { /* the payload's reader → the message */ }
//!     write(w) { Command::Variant { field, … } => { /* to the Writer */ } … }
//!     fields(view, w) { Command::Variant { field, … } => { /* JSON fields */ } … }
//!     read(f, dialect, buf, raw) { /* JSON members → the message */ }
//!     check(command, dialect) { /* the encoder's own refusals → Result */ }
//!     home(command) { /* the variant's dialects → &'static [Dialect] */ }
//!     quirk(dialect, frame) { /* what is dubious in a frame → Option<Quirk> */ }
//! }
//! ```
//!
//! `parse` is an arm of the one parser `match` (`r` the payload's
//! [`Reader`](super::wire::Reader), `id` the message id, `?` and
//! `return Err` as in the parser); `write` and `fields` are arms of a `match`
//! on the message (by value: every payload type is `Copy`), `w` the payload
//! `Writer` or the field visitor `W` and `view` the `CommandView` (what a
//! capture told about the command); `read` builds the message from the JSON
//! object `f` (`buf` owns a byte list it borrows, `raw` the wire bytes a
//! quirk line gives). The last three are optional: `check` is what the
//! encoder refuses beyond the row's dialects and what the parser rejects
//! (a variant in the other dialect family's layout, the spec's maxima of
//! byte fields: `Ok(())` without it), `home` the dialects whose layout a
//! variant has (the row's dialects without it), `quirk` what the decoder
//! accepts but flags (no quirk without it). A report row's `write` also sees
//! the `dialect`, its `read` the `kind` (the row's `type` name read), and its
//! `LEN` rule is part of its head: `len { n }` for a fixed layout, or a
//! closure `len { header(n) |dialect, len, frame, at| … }` of the frame so
//! far (`at(i)` its byte `i`, if known), which looks at its first `n` bytes
//! (`header(n)` omitted: `LEN` and id only). Each piece expands where its
//! consumer's helpers are in scope (`command.rs`, `report.rs`, `fields.rs`,
//! `schema.rs`, `quirk.rs`); the payload types a row names (`PinMode`,
//! `SensorNew`, `ModuleReport`, …) are in the files of their own.
//!
//! A field kind says how the field is read, checked, written and named:
//!
//! | kind            | Rust   | wire                           | JSON            |
//! |-----------------|--------|--------------------------------|-----------------|
//! | `u8`            | `u8`   | one byte                       | number          |
//! | `pin`           | `u8`   | one byte, a GPIO `< 30`        | number          |
//! | `range(lo, hi)` | `u8`   | one byte in `lo..=hi`          | number          |
//! | `u16`           | `u16`  | two bytes, big-endian          | number          |
//! | `flag`          | `bool` | one byte, `0` or `1`           | `true`/`false`  |
//! | `level`         | `bool` | one byte, `0` or `1`           | `0`/`1`         |
//! | `rgb`           | `Rgb`  | three bytes                    | `r`, `g`, `b`   |
//! | `counted(name[, max])` | `&[u8]`| a count byte (`name` in errors), then the bytes; the encoder refuses more than `max` | array |
//! | `trailing_flag` | `Option<bool>` | a last `0`/`1` byte, or nothing | `true`/`false`, or absent |
//! | `nonzero_u32`   | `u32`  | four bytes, big-endian, not 0  | number          |
//! | `counted_pins(name, each[, max])` | `&[u8]` | as `counted`, each byte a GPIO `< 30` (`each` in errors) | array |
//! | `trailing_u16_pair(a, b)` | `Option<(u16, u16)>` | two last `u16`s, or nothing | `a` and `b`, or absent |
//! | `array(n)`      | `[u8; n]` | `n` bytes                   | array           |
//! | `rest`          | `&[u8]`| every byte left                | array           |
//! | `i16`           | `i16`  | two bytes, big-endian          | number          |
//! | `u16_max(max)`  | `u16`  | two bytes, big-endian, `<= max` | number         |
//! | `type_check(names)` | `u8` | `0` (a check's subtype), then a type byte | its name in `names`, or its number |
//!
//! A row has at most one `counted` field (the serde reader borrows one buffer
//! for it), and a `trailing_flag` only last.
//!
//! The table is a `macro_rules!` macro that hands its rows to a callback
//! macro: each consumer (the id constants in `wire`, the enum, parser and
//! writer in `command`, the fields in `fields`, the names in `names`, the
//! serde reader in `schema`) expands the rows where its private helpers are
//! in scope. Every row, `plain` or `custom`, is one arm of the parser's one
//! `match` (`parse_row!` in `kind`, shared by all tables): split in two
//! functions the Pico's command decoder linked 9,096 B instead of 7,736 B
//! (`python3 size/report.py`). A
//! `macro_rules!` table rather than a generator: it needs no build script, no
//! checked-in output to keep current and no extra CI step, and the rows are
//! read by the compiler itself, so a typo is a compile error at the row.
//! What it costs: `rustfmt` formats little of the code inside a macro's
//! definition and `clippy` looks at little of what a macro expands, so a
//! `custom` row's code is kept to their style by hand; and a `write` or
//! `fields` piece that leaves out one of its row's variants compiles (the
//! consumer's `match` has a catch-all arm), so the golden vectors and the
//! schema tests, which hold every variant, are what catch it. The wire
//! layouts stay checked against the protocol spec by the tests (golden
//! vectors in `tests/telemetrix.rs`), not by the table.
//!
//! The module data tables (`hiwonder_table`, `ssd1306_table`) describe the
//! MODULE_DATA messages of a module type that starts with a subtype byte
//! the same way, one row per subtype: the enum, its encode and parse
//! (`ModuleCommand`), its JSON fields and its serde reader come from them.
//! The sensor table (`sensor_table`) has a row per sensor type: the
//! [`SensorType`](super::SensorType) and its names, and its
//! [`SensorReading`](super::SensorReading) in `plain` fields or `custom`
//! code. The module table (`module_table`) has a row per module type: the
//! [`ModuleType`](super::ModuleType) and its names, its MODULE_NEW init
//! ([`ModuleInit`](super::ModuleInit)), its MODULE_DATA's
//! [`ModuleCommand`](super::ModuleCommand) type and the MODULE_REPORTs it
//! sends ([`ModuleReport`](super::ModuleReport)), each a section with a
//! `custom` row's pieces.

/// Hand the command rows to `$callback!`.
macro_rules! command_table {
    ($callback:ident) => {
        $callback! {
            /// 0 SERIAL_LOOP_BACK: the Pico echoes `byte` in report 0.
            0 SERIAL_LOOP_BACK "serial_loop_back" [LoopBack] in [Mirte13, Mirte12, Upstream11] len (2, 2)
                plain LoopBack {
                    /// The byte to echo.
                    byte: u8 "byte",
                };
            1 SET_PIN_MODE "set_pin_mode" [SetPinMode] in [Mirte13, Mirte12, Upstream11] len (3, 6)
                custom {
                    variants {
                        /// 1 SET_PIN_MODE.
                        SetPinMode {
                            /// GPIO number (< 30), or the analog pin for [`PinMode::AnalogInput`].
                            pin: u8,
                            /// Mode and tail.
                            mode: PinMode,
                        },
                    }
                    parse(dialect, r, cmd) {
                        let pin = r.u8()?;
                        let mode = match r.u8()? {
                            m @ (0 | 3 | 4) => PinMode::DigitalInput {
                                pull: match m {
                                    3 => Pull::Up,
                                    4 => Pull::Down,
                                    _ => Pull::None,
                                },
                                report: r.flag("report_enable")?,
                            },
                            1 => PinMode::DigitalOutput,
                            2 => PinMode::PwmOutput,
                            5 => PinMode::AnalogInput {
                                differential: r.u16()?,
                                report: r.flag("report_enable")?,
                            },
                            _ => return Err(Error::OutOfRange { id: cmd, field: "mode" }),
                        };
                        let pin_ok = match mode {
                            PinMode::AnalogInput { .. } => analog_pin_ok(dialect, pin),
                            _ => pin < PIN_COUNT,
                        };
                        ensure(pin_ok, cmd, "pin")?;
                        Command::SetPinMode { pin, mode }
                    }
                    write(w) {
                        Command::SetPinMode { pin, mode } => {
                            w.u8(pin);
                            match mode {
                                PinMode::DigitalInput { pull, report } => {
                                    w.u8(match pull {
                                        Pull::None => 0,
                                        Pull::Up => 3,
                                        Pull::Down => 4,
                                    });
                                    w.flag(report);
                                }
                                PinMode::DigitalOutput => w.u8(1),
                                PinMode::PwmOutput => w.u8(2),
                                PinMode::AnalogInput { differential, report } => {
                                    w.u8(5);
                                    w.u16(differential);
                                    w.flag(report);
                                }
                            }
                        }
                    }
                    fields(view, w) {
                        Command::SetPinMode { pin, mode } => {
                            w.u("pin", pin);
                            w.s("mode", mode.name());
                            match mode {
                                PinMode::DigitalInput { report, .. } => {
                                    w.flag("report_enable", report)
                                }
                                PinMode::AnalogInput { differential, report } => {
                                    w.u("differential", differential);
                                    w.flag("report_enable", report);
                                }
                                PinMode::DigitalOutput | PinMode::PwmOutput => {}
                            }
                        }
                    }
                    read(f, dialect, buf, raw) {
                        let mode = name(f, "mode", PinMode::NAMES)?;
                        let pin = if mode == 5 {
                            analog_pin(f, dialect)?
                        } else {
                            pin_(f, "pin")?
                        };
                        let mode = match mode {
                            m @ 0..=2 => PinMode::DigitalInput {
                                pull: [Pull::None, Pull::Up, Pull::Down][m],
                                report: flag(f, "report_enable")?,
                            },
                            3 => PinMode::DigitalOutput,
                            4 => PinMode::PwmOutput,
                            _ => PinMode::AnalogInput {
                                differential: u16_(f, "differential")?,
                                report: flag(f, "report_enable")?,
                            },
                        };
                        Command::SetPinMode { pin, mode }
                    }
                };
            2 DIGITAL_WRITE "digital_write" [DigitalWrite] in [Mirte13, Mirte12, Upstream11] len (3, 3)
                custom {
                    variants {
                        /// 2 DIGITAL_WRITE.
                        DigitalWrite {
                            /// GPIO number (< 30).
                            pin: u8,
                            /// Level, `true` for high: `1` on the wire, in JSON and in `Display`
                            /// (see [levels and flags](super#levels-and-flags)).
                            value: bool,
                        },
                    }
                    // The firmware drives any non-zero level high (flagged as a quirk).
                    parse(dialect, r, cmd) {
                        Command::DigitalWrite {
                            pin: r.pin("pin")?,
                            value: r.u8()? != 0,
                        }
                    }
                    write(w) {
                        Command::DigitalWrite { pin, value } => {
                            w.u8(pin);
                            w.flag(value);
                        }
                    }
                    fields(view, w) {
                        Command::DigitalWrite { pin, value } => {
                            w.u("pin", pin);
                            w.level("value", value);
                        }
                    }
                    read(f, dialect, buf, raw) {
                        Command::DigitalWrite {
                            pin: pin_(f, "pin")?,
                            // The level byte as sent, which the firmware reads as high
                            // unless it is 0.
                            value: if raw.is(Quirk::LevelNotBinary) {
                                let level = u8_(f, "value")?;
                                raw.byte = Some((3, level));
                                level != 0
                            } else {
                                digital_value(f)?
                            },
                        }
                    }
                    quirk(dialect, frame) {
                        match *frame {
                            [3, _, _, value] if value > 1 => Some(Quirk::LevelNotBinary),
                            _ => None,
                        }
                    }
                };
            // Up to 9 pins and, as a real host may send, 1 or 2 trailing
            // bytes that the firmware ignores (it takes (LEN - 1) / 3 pins).
            3 PWM_WRITE "pwm_write" [PwmWrite] in [Mirte13, Mirte12, Upstream11] len { Dialect::Mirte13 => (4, 30), _ => (4, 4) }
                custom {
                    variants {
                        /// 3 PWM_WRITE (k pins at once in mirte 1.3).
                        PwmWrite(PwmPins),
                    }
                    parse(dialect, r, cmd) {
                        let mut pins = PwmPins::new();
                        // Whole triples; 1 or 2 trailing bytes (mirte 1.3's LEN range
                        // allows them) are ignored as the firmware ignores them, and
                        // flagged as a quirk.
                        while r.remaining() >= 3 {
                            let pin = PwmPin {
                                pin: r.pin("pin")?,
                                value: r.u16()?,
                            };
                            pins.push(pin).map_err(|_| r.bad_length())?;
                        }
                        r.rest();
                        Command::PwmWrite(pins)
                    }
                    write(w) {
                        Command::PwmWrite(pins) => {
                            for p in &pins {
                                w.u8(p.pin);
                                w.u16(p.value);
                            }
                        }
                    }
                    fields(view, w) {
                        Command::PwmWrite(pins) => w.objs("pins", &pins),
                    }
                    read(f, dialect, buf, raw) {
                        if raw.is(Quirk::PwmTrailingBytes) {
                            raw.trailing = bytes(f, "trailing")?;
                        }
                        let pins = objects(f, "pins", |p| {
                            Ok(PwmPin {
                                pin: pin_(p, "pin")?,
                                value: u16_(p, "value")?,
                            })
                        })?;
                        Command::PwmWrite(
                            PwmPins::from_slice(&pins)
                                .map_err(|_| {
                                    format!("field `pins` holds {} pins, at most 9", pins.len())
                                })?,
                        )
                    }
                    check(command, dialect) {
                        match command {
                            Command::PwmWrite(pins)
                                if dialect != Dialect::Mirte13 && pins.len() > 1 =>
                            {
                                Err(EncodeError::TooLong { len: pins.len(), max: 1 })
                            }
                            _ => Ok(()),
                        }
                    }
                    quirk(dialect, frame) {
                        match *frame {
                            [len, ..] if len.wrapping_sub(1) % 3 != 0 => {
                                Some(Quirk::PwmTrailingBytes)
                            }
                            _ => None,
                        }
                    }
                };
            4 MODIFY_REPORTING "modify_reporting" [ModifyReporting] in [Mirte13, Mirte12, Upstream11] len (3, 3)
                custom {
                    variants {
                        /// 4 MODIFY_REPORTING.
                        ModifyReporting(ModifyReporting),
                    }
                    parse(dialect, r, cmd) {
                        let kind = r.u8()?;
                        let pin = r.u8()?;
                        // Digital pins in mirte 1.3 are what a real host sends, although
                        // the firmware indexes them as pin - 26: accepted, and flagged as
                        // a quirk.
                        let digital_ok = pin < PIN_COUNT;
                        // Mirte 1.2's and upstream 1.1's clients send the analog pin byte
                        // they are given unchecked (a GPIO number 26..=30, or any other)
                        // where their firmware takes an ADC number: accepted as sent, and
                        // flagged as a quirk past 4.
                        let analog_ok = dialect != Dialect::Mirte13 || analog_pin_ok(dialect, pin);
                        Command::ModifyReporting(match kind {
                            0 if pin == 0 => ModifyReporting::DisableAll,
                            1 if analog_ok => ModifyReporting::EnableAnalog { pin },
                            3 if analog_ok => ModifyReporting::DisableAnalog { pin },
                            2 if digital_ok => ModifyReporting::EnableDigital { pin },
                            4 if digital_ok => ModifyReporting::DisableDigital { pin },
                            0..=4 => return Err(Error::OutOfRange { id: cmd, field: "pin" }),
                            _ => return Err(Error::OutOfRange { id: cmd, field: "type" }),
                        })
                    }
                    write(w) {
                        Command::ModifyReporting(m) => {
                            let (kind, pin) = match m {
                                ModifyReporting::DisableAll => (0, 0),
                                ModifyReporting::EnableAnalog { pin } => (1, pin),
                                ModifyReporting::EnableDigital { pin } => (2, pin),
                                ModifyReporting::DisableAnalog { pin } => (3, pin),
                                ModifyReporting::DisableDigital { pin } => (4, pin),
                            };
                            w.u8(kind);
                            w.u8(pin);
                        }
                    }
                    fields(view, w) {
                        Command::ModifyReporting(action) => {
                            w.s("action", action.name());
                            match action {
                                ModifyReporting::DisableAll => {}
                                ModifyReporting::EnableAnalog { pin }
                                | ModifyReporting::EnableDigital { pin }
                                | ModifyReporting::DisableAnalog { pin }
                                | ModifyReporting::DisableDigital { pin } => w.u("pin", pin),
                            }
                        }
                    }
                    read(f, dialect, buf, raw) {
                        Command::ModifyReporting(match name(f, "action", ModifyReporting::NAMES)? {
                            0 => ModifyReporting::DisableAll,
                            1 => ModifyReporting::EnableAnalog {
                                pin: reporting_analog_pin(f, dialect, raw)?,
                            },
                            2 => ModifyReporting::EnableDigital { pin: pin_(f, "pin")? },
                            3 => ModifyReporting::DisableAnalog {
                                pin: reporting_analog_pin(f, dialect, raw)?,
                            },
                            _ => ModifyReporting::DisableDigital { pin: pin_(f, "pin")? },
                        })
                    }
                    quirk(dialect, frame) {
                        match *frame {
                            [3, _, 2 | 4, _] if dialect == Dialect::Mirte13 => {
                                Some(Quirk::DigitalReportingPinMinus26)
                            }
                            [3, _, 1 | 3, pin] if dialect != Dialect::Mirte13 && pin > 4 => {
                                Some(Quirk::AnalogReportingPinNotAdc)
                            }
                            _ => None,
                        }
                    }
                };
            /// 5 GET_FIRMWARE_VERSION: answered by report 5.
            5 GET_FIRMWARE_VERSION "get_firmware_version" [GetFirmwareVersion] in [Mirte13, Mirte12, Upstream11] len (1, 1)
                plain GetFirmwareVersion {};
            /// 6 GET_PICO_UNIQUE_ID: answered by report 6.
            6 GET_PICO_UNIQUE_ID "get_pico_unique_id" [GetUniqueId] in [Mirte13, Mirte12, Upstream11] len (1, 1)
                plain GetUniqueId {};
            /// 7 SERVO_ATTACH (sets PWM mode).
            7 SERVO_ATTACH "servo_attach" [ServoAttach] in [Mirte13, Mirte12, Upstream11] len (2, 6)
                plain ServoAttach {
                    /// GPIO number (< 30).
                    pin: pin "pin",
                    /// The ignored `u16 min_us, u16 max_us` that some hosts append.
                    pulse_range: trailing_u16_pair("min_us", "max_us") "pulse_range",
                };
            /// 8 SERVO_WRITE.
            8 SERVO_WRITE "servo_write" [ServoWrite] in [Mirte13, Mirte12, Upstream11] len (4, 4)
                plain ServoWrite {
                    /// GPIO number (< 30).
                    pin: pin "pin",
                    /// Pulse width in µs.
                    pulse_us: u16 "pulse_us",
                };
            /// 9 SERVO_DETACH (a no-op in the firmware).
            9 SERVO_DETACH "servo_detach" [ServoDetach] in [Mirte13, Mirte12, Upstream11] len (2, 2)
                plain ServoDetach {
                    /// GPIO number (< 30).
                    pin: pin "pin",
                };
            /// 10 I2C_BEGIN. `port == sda == scl` selects the port's default pins.
            10 I2C_BEGIN "i2c_begin" [I2cBegin] in [Mirte13, Mirte12, Upstream11] len (4, 4)
                plain I2cBegin {
                    /// 0 or 1.
                    port: range(0, 1) "port",
                    /// SDA GPIO (< 30).
                    sda: pin "sda",
                    /// SCL GPIO (< 30).
                    scl: pin "scl",
                };
            11 I2C_READ "i2c_read" [I2cRead, I2cReadUpstream] in [Mirte13, Mirte12, Upstream11] len { Dialect::Upstream11 => (6, 6), _ => (7, 7) }
                custom {
                    variants {
                        /// 11 I2C_READ, mirte layout: answered by report 10 or 9, or not at all
                        /// when the register write fails.
                        I2cRead {
                            /// 0 or 1.
                            port: u8,
                            /// 7-bit address.
                            addr: u8,
                            /// Echoed in the reply.
                            msg_id: u8,
                            /// Register written before the read.
                            reg: u8,
                            /// Bytes to read, 1..=57.
                            len: u8,
                            /// 0 (stop), 1 (no stop), or 254 (skip the register write, no stop).
                            no_stop: u8,
                        },
                        /// 11 I2C_READ, upstream layout (no `msg_id`).
                        I2cReadUpstream {
                            /// 0 or 1.
                            port: u8,
                            /// 7-bit address.
                            addr: u8,
                            /// Register written before the read.
                            reg: u8,
                            /// Bytes to read, 1..=57.
                            len: u8,
                            /// 0 or 1.
                            no_stop: u8,
                        },
                    }
                    parse(dialect, r, cmd) {
                        let (port, addr) = (r.port()?, r.i2c_addr()?);
                        // More than 57 bytes overrun the firmware's report buffer: a real
                        // host's frame all the same, flagged as a quirk.
                        if dialect.is_mirte() {
                            let (msg_id, reg) = (r.u8()?, r.u8()?);
                            let len = r.u8()?;
                            ensure(len >= 1, cmd, "len")?;
                            let no_stop = r.u8()?;
                            ensure(matches!(no_stop, 0 | 1 | 254), cmd, "no_stop")?;
                            Command::I2cRead { port, addr, msg_id, reg, len, no_stop }
                        } else {
                            let reg = r.u8()?;
                            let len = r.u8()?;
                            ensure(len >= 1, cmd, "len")?;
                            let no_stop = r.u8()?;
                            ensure(no_stop <= 1, cmd, "no_stop")?;
                            Command::I2cReadUpstream { port, addr, reg, len, no_stop }
                        }
                    }
                    write(w) {
                        Command::I2cRead { port, addr, msg_id, reg, len, no_stop } => {
                            w.bytes(&[port, addr, msg_id, reg, len, no_stop])
                        }
                        Command::I2cReadUpstream { port, addr, reg, len, no_stop } => {
                            w.bytes(&[port, addr, reg, len, no_stop])
                        }
                    }
                    fields(view, w) {
                        Command::I2cRead { port, addr, msg_id, reg, len, no_stop } => {
                            w.u("port", port);
                            w.u("addr", addr);
                            w.u("msg_id", msg_id);
                            w.u("reg", reg);
                            w.u("n", len);
                            w.u("no_stop", no_stop);
                        }
                        Command::I2cReadUpstream { port, addr, reg, len, no_stop } => {
                            w.u("port", port);
                            w.u("addr", addr);
                            w.u("reg", reg);
                            w.u("n", len);
                            w.u("no_stop", no_stop);
                        }
                    }
                    read(f, dialect, buf, raw) {
                        let (port, addr) = (ranged(f, "port", 0, 1)?, ranged(f, "addr", 0, 0x7f)?);
                        if dialect == Dialect::Upstream11 {
                            Command::I2cReadUpstream {
                                port,
                                addr,
                                reg: u8_(f, "reg")?,
                                len: past_buffer(f, "n", 1, I2C_READ_MAX, raw)?,
                                no_stop: u8_(f, "no_stop")?,
                            }
                        } else {
                            Command::I2cRead {
                                port,
                                addr,
                                msg_id: u8_(f, "msg_id")?,
                                reg: u8_(f, "reg")?,
                                len: past_buffer(f, "n", 1, I2C_READ_MAX, raw)?,
                                no_stop: u8_(f, "no_stop")?,
                            }
                        }
                    }
                    check(command, dialect) {
                        i2c_layout(matches!(command, Command::I2cRead { .. }), dialect)
                    }
                    home(command) {
                        match command {
                            Command::I2cRead { .. } => &[Dialect::Mirte13, Dialect::Mirte12],
                            _ => &[Dialect::Upstream11],
                        }
                    }
                    quirk(dialect, frame) {
                        // The length byte: the payload's fifth (mirte) or fourth.
                        let at = if dialect.is_mirte() { 6 } else { 5 };
                        past_buffer_at(frame, at, I2C_READ_MAX)
                    }
                };
            12 I2C_WRITE "i2c_write" [I2cWrite, I2cWriteUpstream] in [Mirte13, Mirte12, Upstream11] len { Dialect::Upstream11 => (6, 30), _ => (7, 30) }
                custom {
                    variants {
                        /// 12 I2C_WRITE, mirte layout: answered by report 8.
                        I2cWrite {
                            /// 0 or 1.
                            port: u8,
                            /// 7-bit address.
                            addr: u8,
                            /// Echoed in the reply.
                            msg_id: u8,
                            /// 0 or 1.
                            no_stop: u8,
                            /// 1..=24 bytes.
                            data: &'a [u8],
                        },
                        /// 12 I2C_WRITE, upstream layout (no `msg_id`).
                        I2cWriteUpstream {
                            /// 0 or 1.
                            port: u8,
                            /// 7-bit address.
                            addr: u8,
                            /// 0 or 1.
                            no_stop: u8,
                            /// 1..=25 bytes.
                            data: &'a [u8],
                        },
                    }
                    parse(dialect, r, cmd) {
                        let (port, addr) = (r.port()?, r.i2c_addr()?);
                        let msg_id = if dialect.is_mirte() { Some(r.u8()?) } else { None };
                        let n = r.u8()?;
                        ensure(n >= 1, cmd, "len")?;
                        let no_stop = r.u8()?;
                        ensure(no_stop <= 1, cmd, "no_stop")?;
                        let data = r.take(usize::from(n))?;
                        match msg_id {
                            Some(msg_id) => Command::I2cWrite { port, addr, msg_id, no_stop, data },
                            None => Command::I2cWriteUpstream { port, addr, no_stop, data },
                        }
                    }
                    write(w) {
                        Command::I2cWrite { port, addr, msg_id, no_stop, data } => {
                            w.bytes(&[port, addr, msg_id, data.len() as u8, no_stop]);
                            w.bytes(data);
                        }
                        Command::I2cWriteUpstream { port, addr, no_stop, data } => {
                            w.bytes(&[port, addr, data.len() as u8, no_stop]);
                            w.bytes(data);
                        }
                    }
                    fields(view, w) {
                        Command::I2cWrite { port, addr, msg_id, no_stop, data } => {
                            w.u("port", port);
                            w.u("addr", addr);
                            w.u("msg_id", msg_id);
                            w.u("no_stop", no_stop);
                            w.bytes("data", data);
                        }
                        Command::I2cWriteUpstream { port, addr, no_stop, data } => {
                            w.u("port", port);
                            w.u("addr", addr);
                            w.u("no_stop", no_stop);
                            w.bytes("data", data);
                        }
                    }
                    read(f, dialect, buf, raw) {
                        let (port, addr) = (ranged(f, "port", 0, 1)?, ranged(f, "addr", 0, 0x7f)?);
                        if dialect == Dialect::Upstream11 {
                            Command::I2cWriteUpstream {
                                port,
                                addr,
                                no_stop: u8_(f, "no_stop")?,
                                data: bytes_in(f, "data", buf)?,
                            }
                        } else {
                            Command::I2cWrite {
                                port,
                                addr,
                                msg_id: u8_(f, "msg_id")?,
                                no_stop: u8_(f, "no_stop")?,
                                data: bytes_in(f, "data", buf)?,
                            }
                        }
                    }
                    check(command, dialect) {
                        i2c_layout(matches!(command, Command::I2cWrite { .. }), dialect)?;
                        match command {
                            Command::I2cWrite { data, .. } => at_most(data.len(), 24),
                            Command::I2cWriteUpstream { data, .. } => at_most(data.len(), 25),
                            _ => Ok(()),
                        }
                    }
                    home(command) {
                        match command {
                            Command::I2cWrite { .. } => &[Dialect::Mirte13, Dialect::Mirte12],
                            _ => &[Dialect::Upstream11],
                        }
                    }
                };
            /// 13 SONAR_NEW (`trig == echo`: single-pin sonar). At most 4 are used.
            13 SONAR_NEW "sonar_new" [SonarNew] in [Mirte13, Mirte12, Upstream11] len (3, 3)
                plain SonarNew {
                    /// Trigger GPIO (< 30).
                    trig: pin "trig",
                    /// Echo GPIO (< 30).
                    echo: pin "echo",
                };
            /// 14 DHT_NEW. At most 2 are used.
            14 DHT_NEW "dht_new" [DhtNew] in [Mirte13, Mirte12, Upstream11] len (2, 2)
                plain DhtNew {
                    /// GPIO number (< 30).
                    pin: pin "pin",
                };
            /// 15 STOP_ALL_REPORTS.
            15 STOP_ALL_REPORTS "stop_all_reports" [StopAllReports] in [Mirte13, Mirte12, Upstream11] len (1, 1)
                plain StopAllReports {};
            /// 16 ENABLE_ALL_REPORTS.
            16 ENABLE_ALL_REPORTS "enable_all_reports" [EnableAllReports] in [Mirte13, Mirte12, Upstream11] len (1, 1)
                plain EnableAllReports {};
            /// 17 RESET_DATA (a no-op).
            17 RESET_DATA "reset_data" [ResetData] in [Mirte13, Mirte12, Upstream11] len (1, 1)
                plain ResetData {};
            /// 18 RESET_BOARD.
            18 RESET_BOARD "reset_board" [ResetBoard] in [Mirte13, Mirte12, Upstream11] len (1, 1)
                plain ResetBoard {};
            // A count past the firmware's pixel buffer is a real host's frame,
            // flagged as a quirk.
            19 INITIALIZE_NEO_PIXELS "initialize_neo_pixels" [InitNeoPixels] in [Mirte13, Mirte12, Upstream11] len (6, 6)
                custom {
                    variants {
                        /// 19 INITIALIZE_NEO_PIXELS: fills and shows.
                        InitNeoPixels {
                            /// GPIO number (< 30).
                            pin: u8,
                            /// Number of pixels: at most 100 in mirte 1.3, 150 in mirte
                            /// 1.2 and upstream 1.1 (the firmware's pixel buffer).
                            count: u8,
                            /// Fill colour.
                            rgb: Rgb,
                        },
                    }
                    parse(dialect, r, cmd) {
                        Command::InitNeoPixels { pin: r.pin("pin")?, count: r.u8()?, rgb: rgb(r)? }
                    }
                    write(w) {
                        Command::InitNeoPixels { pin, count, rgb } => {
                            w.bytes(&[pin, count, rgb.r, rgb.g, rgb.b])
                        }
                    }
                    fields(view, w) {
                        Command::InitNeoPixels { pin, count, rgb: colour } => {
                            w.u("pin", pin);
                            w.u("count", count);
                            rgb(w, colour);
                        }
                    }
                    read(f, dialect, buf, raw) {
                        Command::InitNeoPixels {
                            pin: pin_(f, "pin")?,
                            count: past_buffer(f, "count", 0, pixel_buffer(dialect), raw)?,
                            rgb: rgb(f)?,
                        }
                    }
                    quirk(dialect, frame) {
                        past_buffer_at(frame, 3, pixel_buffer(dialect))
                    }
                };
            /// 20 SHOW_NEO_PIXELS.
            20 SHOW_NEO_PIXELS "show_neo_pixels" [ShowNeoPixels] in [Mirte13, Mirte12, Upstream11] len (1, 1)
                plain ShowNeoPixels {};
            // An index past the firmware's pixel buffer is a real host's frame,
            // flagged as a quirk.
            21 SET_NEO_PIXEL "set_neo_pixel" [SetNeoPixel] in [Mirte13, Mirte12, Upstream11] len (6, 6)
                custom {
                    variants {
                        /// 21 SET_NEO_PIXEL.
                        SetNeoPixel {
                            /// Pixel index: below 100 in mirte 1.3, 150 in mirte 1.2 and
                            /// upstream 1.1 (the firmware's pixel buffer).
                            index: u8,
                            /// Colour.
                            rgb: Rgb,
                            /// Show at once.
                            auto_show: bool,
                        },
                    }
                    parse(dialect, r, cmd) {
                        Command::SetNeoPixel {
                            index: r.u8()?,
                            rgb: rgb(r)?,
                            auto_show: r.flag("auto_show")?,
                        }
                    }
                    write(w) {
                        Command::SetNeoPixel { index, rgb, auto_show } => {
                            w.bytes(&[index, rgb.r, rgb.g, rgb.b]);
                            w.flag(auto_show);
                        }
                    }
                    fields(view, w) {
                        Command::SetNeoPixel { index, rgb: colour, auto_show } => {
                            w.u("index", index);
                            rgb(w, colour);
                            w.flag("auto_show", auto_show);
                        }
                    }
                    read(f, dialect, buf, raw) {
                        Command::SetNeoPixel {
                            index: past_buffer(f, "index", 0, pixel_buffer(dialect) - 1, raw)?,
                            rgb: rgb(f)?,
                            auto_show: flag(f, "auto_show")?,
                        }
                    }
                    quirk(dialect, frame) {
                        past_buffer_at(frame, 2, pixel_buffer(dialect) - 1)
                    }
                };
            /// 22 CLEAR_ALL_NEO_PIXELS (always shows).
            22 CLEAR_ALL_NEO_PIXELS "clear_all_neo_pixels" [ClearAllNeoPixels] in [Mirte13, Mirte12, Upstream11] len (1, 2)
                plain ClearAllNeoPixels {
                    /// The ignored `auto_show` byte some hosts append.
                    auto_show: trailing_flag "auto_show",
                };
            /// 23 FILL_NEO_PIXELS.
            23 FILL_NEO_PIXELS "fill_neo_pixels" [FillNeoPixels] in [Mirte13, Mirte12, Upstream11] len (5, 5)
                plain FillNeoPixels {
                    /// Colour.
                    rgb: rgb "rgb",
                    /// Show at once.
                    auto_show: flag "auto_show",
                };
            /// 24 SPI_INIT.
            24 SPI_INIT "spi_init" [SpiInit] in [Mirte13, Mirte12, Upstream11] len (10, 30)
                plain SpiInit {
                    /// 0 or 1.
                    port: range(0, 1) "port",
                    /// MISO or MOSI GPIO (< 30).
                    pin_a: pin "pin_a",
                    /// MOSI or MISO GPIO (< 30).
                    pin_b: pin "pin_b",
                    /// Clock GPIO (< 30).
                    clk: pin "clk",
                    /// Clock frequency in Hz (≥ 1).
                    freq_hz: nonzero_u32 "freq_hz",
                    /// Chip-select GPIOs (each < 30), at most 20.
                    cs_pins: counted_pins("cs count", "cs_pin", 20) "cs_pins",
                };
            /// 25 SPI_WRITE_BLOCKING.
            25 SPI_WRITE_BLOCKING "spi_write_blocking" [SpiWrite] in [Mirte13, Mirte12, Upstream11] len (3, 30)
                plain SpiWrite {
                    /// 0 or 1.
                    port: range(0, 1) "port",
                    /// At most 27 bytes.
                    data: counted("len", 27) "data",
                };
            // More than 60 bytes overrun the firmware's report buffer: a real
            // host's frame all the same, flagged as a quirk.
            26 SPI_READ_BLOCKING "spi_read_blocking" [SpiRead] in [Mirte13, Mirte12, Upstream11] len (4, 4)
                custom {
                    variants {
                        /// 26 SPI_READ_BLOCKING: answered by report 13.
                        SpiRead {
                            /// 0 or 1.
                            port: u8,
                            /// Bytes to read, ≤ 60.
                            len: u8,
                            /// Byte clocked out while reading.
                            tx_fill: u8,
                        },
                    }
                    parse(dialect, r, cmd) {
                        Command::SpiRead { port: r.port()?, len: r.u8()?, tx_fill: r.u8()? }
                    }
                    write(w) {
                        Command::SpiRead { port, len, tx_fill } => w.bytes(&[port, len, tx_fill]),
                    }
                    fields(view, w) {
                        Command::SpiRead { port, len, tx_fill } => {
                            w.u("port", port);
                            w.u("n", len);
                            w.u("tx_fill", tx_fill);
                        }
                    }
                    read(f, dialect, buf, raw) {
                        Command::SpiRead {
                            port: ranged(f, "port", 0, 1)?,
                            len: past_buffer(f, "n", 0, SPI_READ_MAX, raw)?,
                            tx_fill: u8_(f, "tx_fill")?,
                        }
                    }
                    quirk(dialect, frame) {
                        past_buffer_at(frame, 3, SPI_READ_MAX)
                    }
                };
            // Data bits outside 4..=16 reach the Pico SDK unchecked: a real host's
            // frame, flagged as a quirk.
            27 SPI_SET_FORMAT "spi_set_format" [SpiSetFormat] in [Mirte13, Mirte12, Upstream11] len (5, 5)
                custom {
                    variants {
                        /// 27 SPI_SET_FORMAT.
                        SpiSetFormat {
                            /// 0 or 1.
                            port: u8,
                            /// 4..=16.
                            data_bits: u8,
                            /// Clock polarity.
                            cpol: bool,
                            /// Clock phase.
                            cpha: bool,
                        },
                    }
                    parse(dialect, r, cmd) {
                        Command::SpiSetFormat {
                            port: r.port()?,
                            data_bits: r.u8()?,
                            cpol: r.flag("cpol")?,
                            cpha: r.flag("cpha")?,
                        }
                    }
                    write(w) {
                        Command::SpiSetFormat { port, data_bits, cpol, cpha } => {
                            w.bytes(&[port, data_bits]);
                            w.flag(cpol);
                            w.flag(cpha);
                        }
                    }
                    fields(view, w) {
                        Command::SpiSetFormat { port, data_bits, cpol, cpha } => {
                            w.u("port", port);
                            w.u("data_bits", data_bits);
                            w.level("cpol", cpol);
                            w.level("cpha", cpha);
                        }
                    }
                    read(f, dialect, buf, raw) {
                        Command::SpiSetFormat {
                            port: ranged(f, "port", 0, 1)?,
                            data_bits: if raw.is(Quirk::SpiDataBitsOutOfRange) {
                                u8_(f, "data_bits")?
                            } else {
                                ranged(f, "data_bits", 4, 16)?
                            },
                            cpol: level(f, "cpol")?,
                            cpha: level(f, "cpha")?,
                        }
                    }
                    quirk(dialect, frame) {
                        match *frame {
                            [5, _, _, bits, ..] if !(4..=16).contains(&bits) => {
                                Some(Quirk::SpiDataBitsOutOfRange)
                            }
                            _ => None,
                        }
                    }
                };
            /// 28 SPI_CS_CONTROL.
            28 SPI_CS_CONTROL "spi_cs_control" [SpiCsControl] in [Mirte13, Mirte12, Upstream11] len (3, 3)
                plain SpiCsControl {
                    /// GPIO number (< 30).
                    cs_pin: pin "cs_pin",
                    /// Level, `true` for high (`level` `0`/`1` in JSON and `Display`:
                    /// [levels and flags](super#levels-and-flags)).
                    high: level "level",
                };
            /// 29 SET_SCAN_DELAY (mirte only).
            29 SET_SCAN_DELAY "set_scan_delay" [SetScanDelay] in [Mirte13, Mirte12] len (2, 2)
                plain SetScanDelay {
                    /// Scan period in ms.
                    delay_ms: u8 "delay_ms",
                };
            30 ENCODER_NEW "encoder_new" [EncoderNew] in [Mirte13, Mirte12] len { Dialect::Mirte12 => (4, 4), _ => (5, 5) }
                custom {
                    variants {
                        /// 30 ENCODER_NEW (mirte only). At most 4 are used.
                        EncoderNew {
                            /// Single or quadrature.
                            kind: EncoderKind,
                            /// GPIO A (< 30).
                            pin_a: u8,
                            /// GPIO B (< 30); 0 for [`EncoderKind::Single`].
                            pin_b: u8,
                            /// Pull resistors: present in mirte 1.3, whose frame carries the
                            /// byte; `None` in mirte 1.2, whose frame does not.
                            pulls: Option<Pulls>,
                        },
                    }
                    // The firmware sets up a quadrature encoder for any type but 1;
                    // type 3 is accepted as that, and flagged as a quirk.
                    parse(dialect, r, cmd) {
                        let kind = match r.u8()? {
                            1 => EncoderKind::Single,
                            2 | 3 => EncoderKind::Quadrature,
                            _ => return Err(Error::OutOfRange { id: cmd, field: "type" }),
                        };
                        let pin_a = r.pin("pin_a")?;
                        let pin_b = r.pin("pin_b")?;
                        ensure(kind == EncoderKind::Quadrature || pin_b == 0, cmd, "pin_b")?;
                        let pulls = if dialect == Dialect::Mirte13 {
                            let bits = r.u8()?;
                            ensure(bits <= 3, cmd, "pulls")?;
                            Some(Pulls { up: bits & 1 != 0, down: bits & 2 != 0 })
                        } else {
                            None
                        };
                        Command::EncoderNew { kind, pin_a, pin_b, pulls }
                    }
                    write(w) {
                        Command::EncoderNew { kind, pin_a, pin_b, pulls } => {
                            w.u8(match kind {
                                EncoderKind::Single => 1,
                                EncoderKind::Quadrature => 2,
                            });
                            w.bytes(&[pin_a, pin_b]);
                            if let Some(pulls) = pulls {
                                w.u8(u8::from(pulls.up) | (u8::from(pulls.down) << 1));
                            }
                        }
                    }
                    fields(view, w) {
                        Command::EncoderNew { kind, pin_a, pin_b, pulls } => {
                            w.s("kind", kind.name());
                            w.u("pin_a", pin_a);
                            w.u("pin_b", pin_b);
                            // Only mirte 1.3 sends the pulls byte.
                            if let Some(pulls) = pulls {
                                w.obj("pulls", &FnVisit(|o: &mut W<'_>| {
                                    o.flag("up", pulls.up);
                                    o.flag("down", pulls.down);
                                }));
                            }
                        }
                    }
                    read(f, dialect, buf, raw) {
                        Command::EncoderNew {
                            kind: if raw.is(Quirk::EncoderTypeNot1Or2) {
                                // The type byte as sent, which the firmware reads as
                                // quadrature unless it is 1.
                                let kind = u8_(f, "kind")?;
                                raw.byte = Some((2, kind));
                                if kind == 1 {
                                    EncoderKind::Single
                                } else {
                                    EncoderKind::Quadrature
                                }
                            } else {
                                match name(f, "kind", EncoderKind::NAMES)? {
                                    0 => EncoderKind::Single,
                                    _ => EncoderKind::Quadrature,
                                }
                            },
                            pin_a: pin_(f, "pin_a")?,
                            pin_b: pin_(f, "pin_b")?,
                            // Only mirte 1.3 has the pulls byte; elsewhere `pulls` is an
                            // unknown field.
                            pulls: if dialect == Dialect::Mirte13 {
                                Some(nested(f, "pulls", |p| {
                                    Ok(Pulls { up: flag(p, "up")?, down: flag(p, "down")? })
                                })?)
                            } else {
                                None
                            },
                        }
                    }
                    check(command, dialect) {
                        match command {
                            Command::EncoderNew { pulls: Some(_), .. }
                                if dialect != Dialect::Mirte13 =>
                            {
                                Err(EncodeError::Inconsistent {
                                    what: "mirte 1.2 firmware has no encoder pull setting",
                                })
                            }
                            Command::EncoderNew { pulls: None, .. }
                                if dialect == Dialect::Mirte13 =>
                            {
                                Err(EncodeError::Inconsistent {
                                    what: "mirte 1.3 firmware takes ENCODER_NEW with pulls",
                                })
                            }
                            _ => Ok(()),
                        }
                    }
                    home(command) {
                        match command {
                            Command::EncoderNew { pulls: Some(_), .. } => &[Dialect::Mirte13],
                            _ => &[Dialect::Mirte12],
                        }
                    }
                    quirk(dialect, frame) {
                        match *frame {
                            [_, _, kind, ..] if !matches!(kind, 1 | 2) => {
                                Some(Quirk::EncoderTypeNot1Or2)
                            }
                            _ => None,
                        }
                    }
                };
            31 SENSOR_NEW "sensor_new" [SensorNew] in [Mirte13, Mirte12] len { Dialect::Mirte12 => (3, 9), _ => (3, 10) }
                custom {
                    variants {
                        /// 31 SENSOR_NEW (mirte 1.3, and mirte 1.2's own layout
                        /// [`SensorNew::AddMirte12`]).
                        SensorNew(SensorNew),
                    }
                    parse(dialect, r, cmd) {
                        Command::SensorNew(SensorNew::parse(r, dialect)?)
                    }
                    write(w) {
                        Command::SensorNew(s) => s.write(w),
                    }
                    fields(view, w) {
                        Command::SensorNew(s) => s.visit(w),
                    }
                    read(f, dialect, buf, raw) {
                        Command::SensorNew(SensorNew::read_members(f, dialect)?)
                    }
                    check(command, dialect) {
                        match command {
                            Command::SensorNew(s) if s.dialect() != dialect => {
                                Err(EncodeError::Inconsistent {
                                    what: "SENSOR_NEW has mirte 1.3's layout in mirte 1.3 only, \
                                           mirte 1.2's in mirte 1.2 only",
                                })
                            }
                            _ => Ok(()),
                        }
                    }
                    home(command) {
                        match command {
                            Command::SensorNew(SensorNew::AddMirte12 { .. }) => &[Dialect::Mirte12],
                            _ => &[Dialect::Mirte13],
                        }
                    }
                };
            /// 32 PING (mirte only): answered by report 32.
            32 PING "ping" [Ping] in [Mirte13, Mirte12] len (2, 2)
                plain Ping {
                    /// Echoed in the reply.
                    counter: u8 "counter",
                };
            // Mirte 1.2's command table has 33 and 34 as empty stubs: a real host
            // sends them, decoded in mirte 1.3's layout and flagged.
            33 MODULE_NEW "module_new" [ModuleNew] in [Mirte13, Mirte12] len (3, 30)
                custom {
                    variants {
                        /// 33 MODULE_NEW (mirte 1.3).
                        ModuleNew(ModuleNew<'a>),
                    }
                    parse(dialect, r, cmd) {
                        Command::ModuleNew(ModuleNew::parse(r)?)
                    }
                    write(w) {
                        Command::ModuleNew(m) => m.write(w),
                    }
                    fields(view, w) {
                        Command::ModuleNew(m) => m.visit(w),
                    }
                    read(f, dialect, buf, raw) {
                        Command::ModuleNew(ModuleNew::read_members(f, buf)?)
                    }
                    check(command, dialect) {
                        match command {
                            Command::ModuleNew(m) => at_most(m.init_len(), MODULE_INIT_MAX),
                            _ => Ok(()),
                        }
                    }
                    quirk(dialect, frame) {
                        ignored_in_mirte12(dialect)
                    }
                };
            34 MODULE_DATA "module_data" [ModuleData] in [Mirte13, Mirte12] len (2, 30)
                custom {
                    variants {
                        /// 34 MODULE_DATA (mirte 1.3): build typed data with
                        /// [`Command::module_data`], read it with the module's `parse`.
                        ModuleData {
                            /// Module number (modules are numbered 0, 1, 2, … in creation order).
                            module_num: u8,
                            /// 1..=28 bytes for the module.
                            data: &'a [u8],
                        },
                    }
                    parse(dialect, r, cmd) {
                        let module_num = r.u8()?;
                        let data = r.rest();
                        ensure(!data.is_empty(), cmd, "data")?;
                        Command::ModuleData { module_num, data }
                    }
                    write(w) {
                        Command::ModuleData { module_num, data } => {
                            w.u8(module_num);
                            w.bytes(data);
                        }
                    }
                    fields(view, w) {
                        Command::ModuleData { module_num, data } => {
                            w.u("module_num", module_num);
                            let typed = view
                                .module_type
                                .and_then(|t| ModuleData::parse(t, data).map(|m| (t, m)));
                            match typed {
                                Some((module_type, message)) => {
                                    w.s("module_type", module_type.name());
                                    w.obj("message", &message);
                                }
                                None => w.bytes("data", data),
                            }
                        }
                    }
                    read(f, dialect, buf, raw) {
                        let module_num = u8_(f, "module_num")?;
                        let data: &[u8] = if f.has("module_type") {
                            let module_type = module_type(f)?;
                            let data = nested(f, "message", |m| module_data(module_type, m))?;
                            *buf = data.to_vec();
                            &buf[..]
                        } else {
                            bytes_in(f, "data", buf)?
                        };
                        Command::ModuleData { module_num, data }
                    }
                    check(command, dialect) {
                        match command {
                            Command::ModuleData { data, .. } => {
                                at_most(data.len(), COMMAND_PAYLOAD_MAX)
                            }
                            _ => Ok(()),
                        }
                    }
                    quirk(dialect, frame) {
                        ignored_in_mirte12(dialect)
                    }
                };
            /// 35 GET_ID (mirte 1.3): answered by report 35.
            35 GET_ID "get_id" [GetId] in [Mirte13] len (1, 1)
                plain GetId {};
            /// 36 SET_ID (mirte 1.3): answered by report 36.
            36 SET_ID "set_id" [SetId] in [Mirte13] len (2, 2)
                plain SetId {
                    /// The id to save.
                    id: u8 "id",
                };
            // The command is `feature_request` (the report is
            // `feature_check`), so that every name names one direction.
            /// 37 FEATURE_CHECK (mirte 1.3): answered by report 37.
            37 FEATURE_CHECK "feature_request" [FeatureCheck] in [Mirte13] len (2, 2)
                plain FeatureCheck {
                    /// The command id asked about.
                    msg_type: u8 "msg_type",
                };
            /// 38 BOOTLOADER_RESET (mirte 1.3).
            38 BOOTLOADER_RESET "bootloader_reset" [BootloaderReset] in [Mirte13] len (1, 1)
                plain BootloaderReset {};
        }
    };
}

pub(crate) use command_table;

/// Hand the report rows to `$callback!`. A row gives a report's id (spec §5), the name of its
/// [`report_id`](super::report_id) constant, the dialects that define it,
/// its `type` names with the [`Report`](super::Report) variants each names
/// (report 8 has one per dialect family), and its payload, as in the
/// command table: `plain { field: kind "key", … }` (one variant, named by
/// the row, with the row's docs) or `custom { … }` (its variants and code:
/// `parse(dialect, r, id)`, `write(w, dialect)`, `fields(view, w)`,
/// `read(f, dialect, buf, kind)`, and optionally `home(report)` and
/// `quirk(dialect, frame)`). Its `len` rule gives `report_len_ok`, which
/// looks at a frame's first bytes to end a streamed frame early.
macro_rules! report_table {
    ($callback:ident) => {
        $callback! {
            /// 0 SERIAL_LOOP_BACK_REPORT: loopback echo.
            0 SERIAL_LOOP_BACK in [Mirte13, Mirte12, Upstream11] len { 2 }
                { "serial_loop_back_report" [LoopBack] } plain {
                    /// The echoed byte.
                    byte: u8 "byte",
                };
            /// 2 DIGITAL_REPORT.
            2 DIGITAL in [Mirte13, Mirte12, Upstream11] len { 3 }
                { "digital_report" [Digital] } custom {
                    variants {
                        /// 2: a digital input changed.
                        Digital {
                            /// GPIO (< 30).
                            pin: u8,
                            /// Level, `true` for high: `1` on the wire, in JSON and in `Display`
                            /// (see [levels and flags](super#levels-and-flags)).
                            value: bool,
                        },
                    }
                    parse(dialect, r, rid) {
                        Report::Digital { pin: r.pin("pin")?, value: r.flag("value")? }
                    }
                    write(w, dialect) {
                        Report::Digital { pin, value } => {
                            w.u8(pin);
                            w.flag(value);
                        }
                    }
                    fields(view, w) {
                        Report::Digital { pin, value } => {
                            w.u("pin", pin);
                            w.level("value", value);
                        }
                    }
                    read(f, dialect, buf, kind) {
                        Report::Digital { pin: pin_(f, "pin")?, value: digital_value(f)? }
                    }
                };
            /// 3 ANALOG_REPORT.
            3 ANALOG in [Mirte13, Mirte12, Upstream11] len { 4 }
                { "analog_report" [Analog] } custom {
                    variants {
                        /// 3: an analog input changed.
                        Analog {
                            /// GPIO 26..=30 (mirte 1.3; ADC 0..=4 from older builds is accepted
                            /// too), ADC 0..=4 in older dialects.
                            pin: u8,
                            /// 0..=4095.
                            value: u16,
                        },
                    }
                    parse(dialect, r, rid) {
                        let pin = r.u8()?;
                        // mirte 1.3 builds before the GPIO renumbering still send ADC
                        // numbers, and the version was not bumped.
                        let ok = analog_pin_ok(dialect, pin)
                            || analog_pin_ok(Dialect::Mirte12, pin);
                        ensure(ok, rid, "pin")?;
                        let value = r.u16()?;
                        ensure(value <= 4095, rid, "value")?;
                        Report::Analog { pin, value }
                    }
                    write(w, dialect) {
                        Report::Analog { pin, value } => {
                            w.u8(pin);
                            w.u16(value);
                        }
                    }
                    fields(view, w) {
                        Report::Analog { pin, value } => {
                            w.u("pin", pin);
                            w.u("value", value);
                        }
                    }
                    read(f, dialect, buf, kind) {
                        Report::Analog {
                            pin: u8_(f, "pin")?,
                            value: f.int("value", 0, 4095)? as u16,
                        }
                    }
                };
            /// 5 FIRMWARE_REPORT: firmware version (mirte 1.3 sends 1.3).
            5 FIRMWARE in [Mirte13, Mirte12, Upstream11] len { 3 }
                { "firmware_version" [FirmwareVersion] } plain {
                    /// Major.
                    major: u8 "major",
                    /// Minor.
                    minor: u8 "minor",
                };
            /// 6 REPORT_PICO_UNIQUE_ID: unique id (6 board bytes, then `00 00` in mirte firmware).
            6 UNIQUE_ID in [Mirte13, Mirte12, Upstream11] len { 9 }
                { "pico_unique_id" [UniqueId] } plain {
                    /// The 8 bytes.
                    id: array(8) "id",
                };
            /// 8 I2C_WRITE_REPORT (upstream: I2C_WRITE_FAILED).
            8 I2C_WRITE in [Mirte13, Mirte12, Upstream11] len { 4 }
                { "i2c_write_report" [I2cWrite], "i2c_write_failed" [I2cWriteFailed] } custom {
                    variants {
                        /// 8 (mirte): I2C write result, always sent.
                        I2cWrite {
                            /// Port.
                            port: u8,
                            /// The command's `msg_id`.
                            msg_id: u8,
                            /// Bytes written, or −1 (error), −2 (timeout).
                            result: i8,
                        },
                        /// 8 (upstream): I2C_WRITE_FAILED, sent on failure only.
                        I2cWriteFailed {
                            /// Port.
                            port: u8,
                            /// Address.
                            addr: u8,
                            /// Meaningless byte.
                            stale: u8,
                        },
                    }
                    parse(dialect, r, rid) {
                        if dialect.is_mirte() {
                            Report::I2cWrite { port: r.port()?, msg_id: r.u8()?, result: r.i8()? }
                        } else {
                            Report::I2cWriteFailed {
                                port: r.port()?,
                                addr: r.i2c_addr()?,
                                stale: r.u8()?,
                            }
                        }
                    }
                    write(w, dialect) {
                        Report::I2cWrite { port, msg_id, result } => {
                            w.bytes(&[port, msg_id]);
                            w.i8(result);
                        }
                        Report::I2cWriteFailed { port, addr, stale } => {
                            w.bytes(&[port, addr, stale])
                        }
                    }
                    fields(view, w) {
                        Report::I2cWrite { port, msg_id, result } => {
                            w.u("port", port);
                            w.u("msg_id", msg_id);
                            w.i("result", result);
                        }
                        Report::I2cWriteFailed { port, addr, stale } => {
                            w.u("port", port);
                            w.u("addr", addr);
                            w.u("stale", stale);
                        }
                    }
                    read(f, dialect, buf, kind) {
                        let port = ranged(f, "port", 0, 1)?;
                        if kind == "i2c_write_report" {
                            Report::I2cWrite {
                                port,
                                msg_id: u8_(f, "msg_id")?,
                                result: i8_(f, "result")?,
                            }
                        } else {
                            Report::I2cWriteFailed {
                                port,
                                addr: ranged(f, "addr", 0, 0x7f)?,
                                stale: u8_(f, "stale")?,
                            }
                        }
                    }
                    home(report) {
                        match report {
                            Report::I2cWrite { .. } => &[Dialect::Mirte13, Dialect::Mirte12],
                            _ => &[Dialect::Upstream11],
                        }
                    }
                };
            /// 9 I2C_READ_FAILED: I2C read NAK.
            9 I2C_READ_FAILED in [Mirte13, Mirte12, Upstream11] len { 4 }
                { "i2c_read_failed" [I2cReadFailed] } plain {
                    /// Port.
                    port: range(0, 1) "port",
                    /// Address.
                    addr: range(0, 0x7f) "addr",
                    /// Leftover from the previous I2C report.
                    stale: u8 "stale",
                };
            /// 10 I2C_READ_REPORT.
            10 I2C_READ in [Mirte13, Mirte12, Upstream11] len {
                header(6) |dialect, len, frame, at| {
                    let extra = if dialect.is_mirte() { 6 } else { 5 };
                    match at(5) {
                        None => len > extra && len <= extra + I2C_READ_MAX,
                        Some(n) => (1..=I2C_READ_MAX).contains(&n) && len == extra + n,
                    }
                }
            }
                { "i2c_read_report" [I2cRead, I2cReadUpstream] } custom {
                    variants {
                        /// 10 (mirte): I2C read data, `port, msg_id, reg, n, 00, data`.
                        I2cRead {
                            /// Port.
                            port: u8,
                            /// The command's `msg_id`.
                            msg_id: u8,
                            /// Register.
                            reg: u8,
                            /// 1..=57 bytes.
                            data: &'a [u8],
                        },
                        /// 10 (upstream): I2C read data, `port, addr, reg, n, data`.
                        I2cReadUpstream {
                            /// Port.
                            port: u8,
                            /// Address.
                            addr: u8,
                            /// Register.
                            reg: u8,
                            /// 1..=57 bytes.
                            data: &'a [u8],
                        },
                    }
                    parse(dialect, r, rid) {
                        if dialect.is_mirte() {
                            let (port, msg_id, reg) = (r.port()?, r.u8()?, r.u8()?);
                            let n = r.u8()?;
                            ensure(r.u8()? == 0, rid, "pad")?;
                            Report::I2cRead { port, msg_id, reg, data: r.take(usize::from(n))? }
                        } else {
                            let (port, addr, reg) = (r.port()?, r.i2c_addr()?, r.u8()?);
                            let n = r.u8()?;
                            let data = r.take(usize::from(n))?;
                            Report::I2cReadUpstream { port, addr, reg, data }
                        }
                    }
                    write(w, dialect) {
                        Report::I2cRead { port, msg_id, reg, data } => {
                            w.bytes(&[port, msg_id, reg, data.len() as u8, 0]);
                            w.bytes(data);
                        }
                        Report::I2cReadUpstream { port, addr, reg, data } => {
                            w.bytes(&[port, addr, reg, data.len() as u8]);
                            w.bytes(data);
                        }
                    }
                    fields(view, w) {
                        Report::I2cRead { port, msg_id, reg, data } => {
                            w.u("port", port);
                            w.u("msg_id", msg_id);
                            w.u("reg", reg);
                            w.bytes("data", data);
                        }
                        Report::I2cReadUpstream { port, addr, reg, data } => {
                            w.u("port", port);
                            w.u("addr", addr);
                            w.u("reg", reg);
                            w.bytes("data", data);
                        }
                    }
                    read(f, dialect, buf, kind) {
                        let port = ranged(f, "port", 0, 1)?;
                        if dialect == Dialect::Upstream11 {
                            Report::I2cReadUpstream {
                                port,
                                addr: ranged(f, "addr", 0, 0x7f)?,
                                reg: u8_(f, "reg")?,
                                data: bytes_in(f, "data", buf)?,
                            }
                        } else {
                            Report::I2cRead {
                                port,
                                msg_id: u8_(f, "msg_id")?,
                                reg: u8_(f, "reg")?,
                                data: bytes_in(f, "data", buf)?,
                            }
                        }
                    }
                    home(report) {
                        match report {
                            Report::I2cRead { .. } => &[Dialect::Mirte13, Dialect::Mirte12],
                            _ => &[Dialect::Upstream11],
                        }
                    }
                };
            /// 11 SONAR_DISTANCE.
            11 SONAR in [Mirte13, Mirte12, Upstream11] len { |dialect, len, frame, at| len == 4 || (len == 5 && dialect == Dialect::Mirte13) }
                { "sonar_distance" [Sonar] } custom {
                    variants {
                        /// 11: sonar distance.
                        Sonar(Sonar),
                    }
                    parse(dialect, r, rid) {
                        let trig = r.pin("trig")?;
                        Report::Sonar(match dialect {
                            Dialect::Mirte13 if r.remaining() == 3 => {
                                Sonar::WithEcho { trig, echo: r.pin("echo")?, cm: sonar_cm(r)? }
                            }
                            Dialect::Mirte13 => Sonar::TrigOnly { trig, cm: sonar_cm(r)? },
                            Dialect::Mirte12 => {
                                let m = r.u8()?;
                                let cm = r.u8()?;
                                ensure(cm < 100, rid, "cm")?;
                                Sonar::MetresCm { trig, m, cm }
                            }
                            Dialect::Upstream11 => {
                                let cm = r.u8()?;
                                let hundredths = r.u8()?;
                                ensure(hundredths < 100, rid, "hundredths")?;
                                Sonar::CmHundredths { trig, cm, hundredths }
                            }
                        })
                    }
                    write(w, dialect) {
                        Report::Sonar(Sonar::WithEcho { trig, echo, cm }) => {
                            w.bytes(&[trig, echo]);
                            w.u16(cm);
                        }
                        Report::Sonar(Sonar::TrigOnly { trig, cm }) => {
                            w.u8(trig);
                            w.u16(cm);
                        }
                        Report::Sonar(Sonar::MetresCm { trig, m, cm }) => w.bytes(&[trig, m, cm]),
                        Report::Sonar(Sonar::CmHundredths { trig, cm, hundredths }) => {
                            w.bytes(&[trig, cm, hundredths])
                        }
                    }
                    fields(view, w) {
                        Report::Sonar(Sonar::WithEcho { trig, echo, cm }) => {
                            w.u("trig", trig);
                            w.u("echo", echo);
                            sonar_cm(w, cm);
                        }
                        Report::Sonar(Sonar::TrigOnly { trig, cm }) => {
                            w.u("trig", trig);
                            sonar_cm(w, cm);
                        }
                        Report::Sonar(Sonar::MetresCm { trig, m, cm }) => {
                            w.u("trig", trig);
                            w.u("m", m);
                            w.u("cm", cm);
                        }
                        Report::Sonar(Sonar::CmHundredths { trig, cm, hundredths }) => {
                            w.u("trig", trig);
                            w.u("cm", cm);
                            w.u("hundredths", hundredths);
                        }
                    }
                    read(f, dialect, buf, kind) {
                        Report::Sonar(match dialect {
                            Dialect::Mirte13 => {
                                let trig = pin_(f, "trig")?;
                                if f.has("echo") {
                                    Sonar::WithEcho {
                                        trig,
                                        echo: pin_(f, "echo")?,
                                        cm: sonar_cm(f)?,
                                    }
                                } else {
                                    Sonar::TrigOnly { trig, cm: sonar_cm(f)? }
                                }
                            }
                            Dialect::Mirte12 => Sonar::MetresCm {
                                trig: pin_(f, "trig")?,
                                m: u8_(f, "m")?,
                                cm: u8_(f, "cm")?,
                            },
                            Dialect::Upstream11 => Sonar::CmHundredths {
                                trig: pin_(f, "trig")?,
                                cm: u8_(f, "cm")?,
                                hundredths: u8_(f, "hundredths")?,
                            },
                        })
                    }
                    home(report) {
                        match report {
                            Report::Sonar(Sonar::WithEcho { .. } | Sonar::TrigOnly { .. }) => {
                                &[Dialect::Mirte13]
                            }
                            Report::Sonar(Sonar::MetresCm { .. }) => &[Dialect::Mirte12],
                            _ => &[Dialect::Upstream11],
                        }
                    }
                };
            /// 12 DHT_REPORT.
            12 DHT in [Mirte13, Mirte12, Upstream11] len { 6 }
                { "dht_report" [Dht] } custom {
                    variants {
                        /// 12: DHT reading (all zeros after a read error). Below 0 °C both
                        /// temperature parts are negative.
                        Dht {
                            /// GPIO (< 30).
                            pin: u8,
                            /// Humidity, integer part.
                            humidity: u8,
                            /// Humidity, hundredths (0..=99).
                            humidity_hundredths: u8,
                            /// Temperature in °C, integer part.
                            temp: i8,
                            /// Temperature, hundredths (−99..=99, same sign as `temp`).
                            temp_hundredths: i8,
                        },
                    }
                    parse(dialect, r, rid) {
                        let pin = r.pin("pin")?;
                        let humidity = r.u8()?;
                        let humidity_hundredths = r.u8()?;
                        ensure(humidity_hundredths < 100, rid, "humidity_hundredths")?;
                        let temp = r.i8()?;
                        let temp_hundredths = r.i8()?;
                        let same_sign = !(temp > 0 && temp_hundredths < 0
                            || temp < 0 && temp_hundredths > 0);
                        ensure(
                            (-99..=99).contains(&temp_hundredths) && same_sign,
                            rid,
                            "temp_hundredths",
                        )?;
                        Report::Dht { pin, humidity, humidity_hundredths, temp, temp_hundredths }
                    }
                    write(w, dialect) {
                        Report::Dht {
                            pin,
                            humidity,
                            humidity_hundredths,
                            temp,
                            temp_hundredths,
                        } => {
                            w.bytes(&[pin, humidity, humidity_hundredths]);
                            w.i8(temp);
                            w.i8(temp_hundredths);
                        }
                    }
                    fields(view, w) {
                        Report::Dht {
                            pin,
                            humidity,
                            humidity_hundredths,
                            temp,
                            temp_hundredths,
                        } => {
                            w.u("pin", pin);
                            w.u("hum_int", humidity);
                            w.u("hum_hundredths", humidity_hundredths);
                            w.i("temp_int", temp);
                            w.i("temp_hundredths", temp_hundredths);
                        }
                    }
                    read(f, dialect, buf, kind) {
                        Report::Dht {
                            pin: pin_(f, "pin")?,
                            humidity: u8_(f, "hum_int")?,
                            humidity_hundredths: u8_(f, "hum_hundredths")?,
                            temp: i8_(f, "temp_int")?,
                            temp_hundredths: i8_(f, "temp_hundredths")?,
                        }
                    }
                };
            /// 13 SPI_REPORT: SPI read data.
            13 SPI in [Mirte13, Mirte12, Upstream11] len {
                header(4) |dialect, len, frame, at| match at(3) {
                    None => (3..=3 + SPI_READ_MAX).contains(&len),
                    Some(n) => n <= SPI_READ_MAX && len == 3 + n,
                }
            }
                { "spi_report" [Spi] } plain {
                    /// Port.
                    port: range(0, 1) "port",
                    /// 0..=60 bytes.
                    data: counted("n") "data",
                };
            /// 14 ENCODER_REPORT.
            14 ENCODER in [Mirte13, Mirte12] len { 3 }
                { "encoder_report" [Encoder] } custom {
                    variants {
                        /// 14 (mirte): encoder steps since the last report (never 0).
                        Encoder {
                            /// GPIO A (< 30).
                            pin: u8,
                            /// Steps, never 0 (the firmware reports only
                            /// when the encoder moved).
                            steps: i8,
                        },
                    }
                    parse(dialect, r, rid) {
                        let pin = r.pin("pin")?;
                        let steps = r.i8()?;
                        ensure(steps != 0, rid, "steps")?;
                        Report::Encoder { pin, steps }
                    }
                    write(w, dialect) {
                        Report::Encoder { pin, steps } => {
                            w.u8(pin);
                            w.i8(steps);
                        }
                    }
                    fields(view, w) {
                        Report::Encoder { pin, steps } => {
                            w.u("pin_a", pin);
                            w.i("steps", steps);
                        }
                    }
                    read(f, dialect, buf, kind) {
                        Report::Encoder { pin: pin_(f, "pin_a")?, steps: steps_(f, "steps")? }
                    }
                };
            /// 20 SENSOR_REPORT.
            20 SENSOR in [Mirte13, Mirte12] len {
                header(4) |dialect, len, frame, at| match at(3) {
                    // mirte 1.2 reports its one sensor, the VEML6040 (spec §10.1).
                    None if dialect == Dialect::Mirte12 => len == 11,
                    Some(t) if dialect == Dialect::Mirte12 => {
                        t == SensorType::Veml6040.as_u8() && len == 11
                    }
                    None => (3..=56).contains(&len),
                    Some(t) => match SensorType::from_u8(t).and_then(SensorType::data_len) {
                        None => false,
                        Some((min, max)) => {
                            let data = usize::from(len).wrapping_sub(3);
                            len >= 3 && data >= min && data <= max && (t != 8 || data % 2 == 0)
                        }
                    },
                }
            }
                { "sensor_report" [Sensor] } custom {
                    variants {
                        /// 20 (mirte 1.3): a sensor reading.
                        Sensor {
                            /// The sensor's number.
                            sensor_num: u8,
                            /// Type and data.
                            reading: SensorReading,
                        },
                    }
                    parse(dialect, r, rid) {
                        let sensor_num = r.u8()?;
                        let sensor_type = SensorType::from_u8(r.u8()?)
                            .ok_or(Error::OutOfRange { id: rid, field: "sensor_type" })?;
                        Report::Sensor {
                            sensor_num,
                            reading: SensorReading::parse(r, sensor_type, dialect)?,
                        }
                    }
                    write(w, dialect) {
                        Report::Sensor { sensor_num, reading } => {
                            w.bytes(&[sensor_num, reading.sensor_type().as_u8()]);
                            reading.write(w, dialect);
                        }
                    }
                    fields(view, w) {
                        Report::Sensor { sensor_num, reading } => {
                            w.u("sensor_num", sensor_num);
                            w.s("sensor_type", reading.sensor_type().name());
                            w.obj("reading", &reading);
                        }
                    }
                    read(f, dialect, buf, kind) {
                        let sensor_num = u8_(f, "sensor_num")?;
                        let sensor_type = sensor_type(f)?;
                        Report::Sensor {
                            sensor_num,
                            reading: nested(f, "reading", |r| sensor_reading(sensor_type, r))?,
                        }
                    }
                };
            /// 21 SENSOR_MAIN_REPORT (mirte 1.3): answer to a sensor check.
            21 SENSOR_MAIN in [Mirte13] len { 4 }
                { "sensor_main_report" [SensorSupported] } plain {
                    /// The type asked about.
                    sensor_type: type_check(SensorType::NAMES) "sensor_type",
                    /// Supported.
                    supported: flag "supported",
                };
            /// 32 PONG_REPORT (mirte): answer to PING.
            32 PONG in [Mirte13, Mirte12] len { 3 }
                { "pong" [Pong] } plain {
                    /// The PING's counter.
                    counter: u8 "counter",
                    /// Random per boot, 0..=99: a change means the Pico rebooted.
                    boot_id: range(0, 99) "boot_id",
                };
            /// 33 MODULE_MAIN_REPORT (mirte 1.3): answer to a module check.
            33 MODULE_MAIN in [Mirte13] len { 4 }
                { "module_main_report" [ModuleSupported] } plain {
                    /// The type asked about.
                    module_type: type_check(ModuleType::NAMES) "module_type",
                    /// Supported.
                    supported: flag "supported",
                };
            /// 34 MODULE_REPORT.
            34 MODULE in [Mirte13] len { header(5) |dialect, len, frame, at| module_report_len_ok(len, frame) }
                { "module_report" [Module] } custom {
                    variants {
                        /// 34 (mirte 1.3): a module's report.
                        Module {
                            /// The module's number.
                            module_num: u8,
                            /// Type, subtype and data.
                            report: ModuleReport<'a>,
                        },
                    }
                    parse(dialect, r, rid) {
                        Report::Module { module_num: r.u8()?, report: ModuleReport::parse(r)? }
                    }
                    write(w, dialect) {
                        Report::Module { module_num, report } => {
                            w.u8(module_num);
                            report.write(w);
                        }
                    }
                    fields(view, w) {
                        Report::Module { module_num, report } => {
                            w.u("module_num", module_num);
                            w.s("module_type", report.module_type().name());
                            w.obj("message", &report);
                        }
                    }
                    read(f, dialect, buf, kind) {
                        let module_num = u8_(f, "module_num")?;
                        let module_type = module_type(f)?;
                        Report::Module {
                            module_num,
                            report: nested(f, "message", move |m| {
                                module_report(module_type, m, buf)
                            })?,
                        }
                    }
                    quirk(dialect, frame) {
                        match *frame {
                            // SSD1306 (type 3), display disabled.
                            [5, _, _, 3, sub, 254] if dialect == Dialect::Mirte13 && sub > 3 => {
                                Some(Quirk::EchoedRequestByte)
                            }
                            _ => None,
                        }
                    }
                };
            /// 35 GET_ID_REPORT (mirte 1.3): the saved id (`FF` if never set).
            35 GET_ID in [Mirte13] len { 2 }
                { "get_id_report" [Id] } plain {
                    /// The id.
                    id: u8 "id",
                };
            /// 36 SET_ID_REPORT (mirte 1.3): the id just saved.
            36 SET_ID in [Mirte13] len { 2 }
                { "set_id_report" [IdSet] } plain {
                    /// The id.
                    id: u8 "id",
                };
            /// 37 FEATURE_CHECK (mirte 1.3): answer to FEATURE_CHECK.
            37 FEATURE_CHECK in [Mirte13] len {
                header(8) |dialect, len, frame, at| match (at(2), at(3)) {
                    (Some(msg_type), Some(1)) => match feature_extras(msg_type) {
                        Extras::Counted => match at(7) {
                            // At most 8 pins follow, as checked once the count is in:
                            // a length refused then must be refused now (the framing
                            // answers the same for every longer input).
                            None => (7..=15).contains(&len),
                            Some(count) => count <= 8 && usize::from(len) == 7 + usize::from(count),
                        },
                        Extras::Len(a, b) => len == 3 + a || len == 3 + b,
                    },
                    (Some(_), Some(0)) => len == 3,
                    (Some(_), Some(_)) => false,
                    _ => (3..=15).contains(&len),
                }
            }
                { "feature_check" [Feature] } plain {
                    /// The command id asked about.
                    msg_type: u8 "msg_type",
                    /// Whether the firmware has it.
                    supported: flag "ok",
                    /// Extras (spec §5): for 1 `30 12 14 count pins…`, for 5 `1 3`, for
                    /// 7 `12`, for 10 `2`, for 13 `4`, for 30 `4 2 1`; none otherwise.
                    extras: rest "extras",
                };
            /// 99 DEBUG_PRINT (mirte): debug print.
            99 DEBUG_PRINT in [Mirte13, Mirte12] len { 4 }
                { "debug_print" [Debug] } plain {
                    /// Where it came from.
                    id: u8 "id",
                    /// Value.
                    value: u16 "value",
                };
        }
    };
}

pub(crate) use report_table;

/// Hand the rows of a module's data table to `$callback!`: the MODULE_DATA
/// messages of one module type whose first data byte is a subtype (spec
/// §7). The enum's docs and name come first, then one row per subtype: its
/// byte, its `subtype` name in the JSON-lines schema, its variants in
/// brackets, and its payload as a command row's (`plain` fields of the same
/// kinds, or `custom { … }` with its variants and code: `parse(r, id)`
/// after the subtype byte, `write(w)`, `fields(view, w)`, `read(f)`).
macro_rules! hiwonder_table {
    ($callback:ident) => {
        $callback! {
            /// Hiwonder servo data (module type 1), spec §7.1. Servos are addressed by
            /// their index in the init list. The firmware drops all of it unless the last
            /// PING is less than 2 s old.
            HiwonderCommand;
            1 "set_angle" [SetAngle] custom {
                variants {
                    /// 1 SET_ANGLE: 1..=5 moves.
                    SetAngle(List<ServoMove, 5>),
                }
                parse(r, id) {
                    let count = r.u8()?;
                    ensure((1..=5).contains(&count), id, "count")?;
                    let mut moves = List::new();
                    for _ in 0..count {
                        let m = ServoMove { idx: r.u8()?, centideg: r.u16()?, time_ms: r.u16()? };
                        ensure(m.centideg <= MAX_CENTIDEG, id, "centideg")?;
                        moves.push(m).map_err(|_| r.bad_length())?;
                    }
                    HiwonderCommand::SetAngle(moves)
                }
                write(w) {
                    HiwonderCommand::SetAngle(moves) => {
                        w.u8(moves.len() as u8);
                        for m in &moves {
                            w.u8(m.idx);
                            w.u16(m.centideg);
                            w.u16(m.time_ms);
                        }
                    }
                }
                fields(view, w) {
                    HiwonderCommand::SetAngle(moves) => w.objs("moves", &moves),
                }
                read(f) {
                    let moves = objects(f, "moves", |m| {
                        Ok(ServoMove {
                            idx: u8_(m, "idx")?,
                            centideg: u16_(m, "centideg")?,
                            time_ms: u16_(m, "time_ms")?,
                        })
                    })?;
                    HiwonderCommand::SetAngle(
                        List::from_slice(&moves)
                            .map_err(|_| format!("`moves` holds {}, at most 5", moves.len()))?,
                    )
                }
            };
            2 "enable" [Enable] custom {
                variants {
                    /// 2 ENABLE: an empty list means all servos.
                    Enable {
                        /// Torque on or off.
                        enabled: bool,
                        /// Servo indices (at most 25), or none for all.
                        servos: List<u8, 25>,
                    },
                }
                parse(r, id) {
                    let count = r.u8()?;
                    let enabled = r.flag("enabled")?;
                    let servos = List::from_slice(r.take(usize::from(count))?)
                        .map_err(|_| r.bad_length())?;
                    HiwonderCommand::Enable { enabled, servos }
                }
                write(w) {
                    HiwonderCommand::Enable { enabled, servos } => {
                        w.u8(servos.len() as u8);
                        w.flag(enabled);
                        w.bytes(&servos);
                    }
                }
                fields(view, w) {
                    HiwonderCommand::Enable { enabled, servos } => {
                        w.flag("enabled", enabled);
                        w.bytes("servos", &servos);
                    }
                }
                read(f) {
                    let enabled = flag(f, "enabled")?;
                    let servos = bytes(f, "servos")?;
                    HiwonderCommand::Enable {
                        enabled,
                        servos: List::from_slice(&servos)
                            .map_err(|_| format!("`servos` holds {}, at most 25", servos.len()))?,
                    }
                }
            };
            /// 3 ID_WRITE: sets the id of whatever servo is on the bus.
            3 "id_write" [IdWrite] plain IdWrite {
                /// The new bus id.
                new_id: u8 "new_id",
            };
            /// 4 ID_VERIFY: answered by [`ModuleReport::HiwonderIdVerify`].
            4 "id_verify" [IdVerify] plain IdVerify {
                /// Bus id to look for.
                bus_id: u8 "bus_id",
            };
            /// 5 RANGE_WRITE.
            5 "range_write" [RangeWrite] plain RangeWrite {
                /// Servo index.
                idx: u8 "idx",
                /// Lower limit in centidegrees, 0..=24000.
                min_cdeg: u16_max(24000) "min_cdeg",
                /// Upper limit in centidegrees, 0..=24000.
                max_cdeg: u16_max(24000) "max_cdeg",
            };
            /// 6 RANGE_READ: answered by [`ModuleReport::HiwonderRange`].
            6 "range_read" [RangeRead] plain RangeRead {
                /// Servo index.
                idx: u8 "idx",
            };
            /// 7 OFFSET_WRITE (saved on the servo).
            7 "offset_write" [OffsetWrite] plain OffsetWrite {
                /// Servo index.
                idx: u8 "idx",
                /// Offset in centidegrees.
                offset_cdeg: i16 "offset_cdeg",
            };
            /// 8 OFFSET_READ: answered by [`ModuleReport::HiwonderOffset`].
            8 "offset_read" [OffsetRead] plain OffsetRead {
                /// Servo index.
                idx: u8 "idx",
            };
            /// 9 VOLTAGE_LIMIT_WRITE (the firmware clamps to 4500..=14000 mV).
            9 "voltage_limit_write" [VoltageLimitWrite] plain VoltageLimitWrite {
                /// Servo index.
                idx: u8 "idx",
                /// Lower limit in mV.
                min_mv: u16 "min_mv",
                /// Upper limit in mV.
                max_mv: u16 "max_mv",
            };
            /// 10 MOTOR_MODE_WRITE (speed 0 = servo mode).
            10 "motor_mode_write" [MotorModeWrite] plain MotorModeWrite {
                /// Servo index.
                idx: u8 "idx",
                /// Speed.
                speed: i16 "speed",
            };
            /// 11 ADD_SERVO: answered by [`ModuleReport::HiwonderAdded`].
            11 "add_servo" [AddServo] plain AddServo {
                /// Bus id of the servo.
                bus_id: u8 "bus_id",
            };
        }
    };
}

pub(crate) use hiwonder_table;

/// The SSD1306's data table (see [`hiwonder_table`]).
macro_rules! ssd1306_table {
    ($callback:ident) => {
        $callback! {
            /// SSD1306 data (module type 3), spec §7.3.
            Ssd1306Command;
            0 "text" [Text] custom {
                variants {
                    /// 0 TEXT: at most 26 characters, appended to the text buffer.
                    Text(List<u8, 26>),
                }
                parse(r, id) {
                    let n = r.u8()?;
                    ensure(n <= 26, id, "len")?;
                    let text = List::from_slice(r.take(usize::from(n))?)
                        .map_err(|_| r.bad_length())?;
                    Ssd1306Command::Text(text)
                }
                write(w) {
                    Ssd1306Command::Text(text) => {
                        w.u8(text.len() as u8);
                        w.bytes(&text);
                    }
                }
                fields(view, w) {
                    Ssd1306Command::Text(text) => w.v("text", V::Latin1(&text)),
                }
                read(f) {
                    let value = f.value("text")?;
                    let text = value
                        .as_str()
                        .ok_or_else(|| format!("field `text` must be a string, found {value}"))?;
                    // One character per byte (ISO 8859-1), as it is written.
                    let bytes = text
                        .chars()
                        .map(u8::try_from)
                        .collect::<Result<Vec<u8>, _>>()
                        .map_err(|_| {
                            let latin1 = "characters U+0000..=U+00FF only";
                            format!("field `text` must hold {latin1}, found {value}")
                        })?;
                    Ssd1306Command::Text(
                        List::from_slice(&bytes)
                            .map_err(|_| {
                                format!("field `text` holds {} bytes, at most 26", bytes.len())
                            })?,
                    )
                }
            };
            /// 1 TEXT_DONE: render the text buffer, then clear it.
            1 "text_done" [TextDone] plain TextDone {};
            /// 2 BINARY: 16 framebuffer bytes at `chunk * 16`.
            2 "binary" [Binary] plain Binary {
                /// Chunk 0..=63.
                chunk: range(0, 63) "chunk",
                /// The bytes.
                data: array(16) "data",
            };
            /// 3 BINARY_DONE.
            3 "binary_done" [BinaryDone] plain BinaryDone {};
        }
    };
}

pub(crate) use ssd1306_table;

/// Hand the sensor rows to `$callback!`, after `$extra` (in brackets) when
/// given: one row per sensor type (spec §6), its type byte, its
/// [`SensorType`](super::SensorType) variant with that variant's docs and
/// its name, then, for a type the firmware sends readings of, `data` with
/// the length range of its SENSOR_REPORT data and its
/// [`SensorReading`](super::SensorReading), the variant of the same name:
/// its docs, then `plain` fields (of the command rows' kinds) or `custom`
/// code with `parse(r, dialect)`, `write(w, dialect)`, `fields(view, w)`
/// and `read(f)`.
macro_rules! sensor_table {
    ($callback:ident $(, $($extra:tt)+)?) => {
        $callback! {
            $([$($extra)+])?
            /// 0: GPS (not supported by the firmware; no report layout).
            0 Gps "gps";
            /// 1: HX711 load cell. Settings `dout, sck`.
            1 Hx711 "hx711" data (4, 4)
                /// HX711: raw `i32`.
                plain {
                    /// Raw reading.
                    raw: i32 "raw",
                };
            /// 2: MPU9250. Settings `port, addr`.
            2 Mpu9250 "mpu9250" data (52, 52)
                /// MPU9250: 13 floats.
                plain {
                    /// Acceleration x, y, z.
                    accel: f32s(3) "accel",
                    /// Angular rate x, y, z.
                    gyro: f32s(3) "gyro",
                    /// Magnetic field x, y, z.
                    mag: f32s(3) "mag",
                    /// Orientation quaternion x, y, z, w.
                    quat: f32s(4) "quat",
                };
            /// 3: VL53L0X. Settings `port`.
            3 Vl53l0x "vl53l0x" data (2, 2)
                /// VL53L0X: distance.
                plain {
                    /// Distance in mm.
                    mm: u16 "mm",
                };
            /// 4: VEML6040 (address 0x10). Settings `port`.
            4 Veml6040 "veml6040" data (8, 8)
                /// VEML6040: colour channels.
                custom {
                    variants {
                        Veml6040 {
                            /// Red.
                            r: u16,
                            /// Green.
                            g: u16,
                            /// Blue.
                            b: u16,
                            /// White.
                            w: u16,
                        },
                    }
                    // mirte 1.2 sends each colour register low byte first.
                    parse(r, dialect) {
                        let mut channel = || match dialect {
                            Dialect::Mirte12 => r.array().map(u16::from_le_bytes),
                            _ => r.u16(),
                        };
                        SensorReading::Veml6040 {
                            r: channel()?,
                            g: channel()?,
                            b: channel()?,
                            w: channel()?,
                        }
                    }
                    write(w, dialect) {
                        SensorReading::Veml6040 { r, g, b, w: white } => {
                            for v in [r, g, b, white] {
                                if dialect == Dialect::Mirte12 {
                                    w.bytes(&v.to_le_bytes());
                                } else {
                                    w.u16(v);
                                }
                            }
                        }
                    }
                    fields(view, w) {
                        SensorReading::Veml6040 { r, g, b, w: white } => {
                            w.u("r", r);
                            w.u("g", g);
                            w.u("b", b);
                            w.u("w", white);
                        }
                    }
                    read(f) {
                        SensorReading::Veml6040 {
                            r: u16_(f, "r")?,
                            g: u16_(f, "g")?,
                            b: u16_(f, "b")?,
                            w: u16_(f, "w")?,
                        }
                    }
                };
            /// 5: ADXL345 (not registered in the firmware). Settings `port`.
            5 Adxl345 "adxl345" data (6, 6)
                /// ADXL345 (never sent by the firmware; layout as the spec describes).
                plain {
                    /// Acceleration x, y, z.
                    accel: i16s(3) "accel",
                };
            /// 6: INA226. Settings `port, addr` (0x40..=0x4F).
            6 Ina226 "ina226" data (8, 8)
                /// INA226: bus voltage and current.
                plain {
                    /// Bus voltage in V.
                    volts: f32 "volts",
                    /// Current in A.
                    amps: f32 "amps",
                };
            /// 7: HMC5883L. Settings `port`.
            7 Hmc5883l "hmc5883l" data (12, 12)
                /// HMC5883L: normalised field.
                plain {
                    /// Field x, y, z.
                    field: f32s(3) "field",
                };
            /// 8: AS5600 behind a TCA9548 mux (0x70). Settings `port, channel_mask`.
            8 As5600 "as5600" data (0, 16)
                /// AS5600 behind a mux: one angle per channel set in the mask, lowest
                /// channel first.
                custom {
                    variants {
                        As5600 {
                            /// Angles 0..=4095.
                            angles: List<u16, 8>,
                        },
                    }
                    parse(r, dialect) {
                        let mut angles = List::new();
                        while r.remaining() > 0 {
                            let angle = r.u16()?;
                            ensure(angle <= 4095, r.id(), "angle")?;
                            angles.push(angle).map_err(|_| r.bad_length())?;
                        }
                        SensorReading::As5600 { angles }
                    }
                    write(w, dialect) {
                        SensorReading::As5600 { angles } => angles.iter().for_each(|&a| w.u16(a)),
                    }
                    fields(view, w) {
                        SensorReading::As5600 { angles } => w.v("angles", V::U16s(&angles)),
                    }
                    read(f) {
                        let value = f.value("angles")?;
                        let items = value
                            .as_array()
                            .ok_or_else(|| {
                                format!("field `angles` must be an array, found {value}")
                            })?;
                        let mut angles = List::new();
                        for (i, item) in items.iter().enumerate() {
                            let angle = read_int(item, 0, 65535)
                                .map_err(|e| format!("field `angles[{i}]` {e}"))?;
                            angles
                                .push(angle as u16)
                                .map_err(|_| {
                                    format!("field `angles` holds {}, at most 8", items.len())
                                })?;
                        }
                        SensorReading::As5600 { angles }
                    }
                };
            /// 9: MPU6050. Settings `port, addr`.
            9 Mpu6050 "mpu6050" data (14, 14)
                /// MPU6050: raw readings.
                plain {
                    /// Acceleration x, y, z.
                    accel: i16s(3) "accel",
                    /// Angular rate x, y, z.
                    gyro: i16s(3) "gyro",
                    /// Temperature.
                    temp: i16 "temp",
                };
            /// 10: BNO055. Settings `port`.
            10 Bno055 "bno055" data (53, 53)
                /// BNO055: 13 floats and a temperature.
                plain {
                    /// Angular rate x, y, z.
                    gyro: f32s(3) "gyro",
                    /// Magnetic field x, y, z.
                    mag: f32s(3) "mag",
                    /// Acceleration x, y, z.
                    accel: f32s(3) "accel",
                    /// Orientation quaternion x, y, z, w.
                    quat: f32s(4) "quat",
                    /// Temperature in °C.
                    temp: i8 "temp",
                };
        }
    };
}

pub(crate) use sensor_table;

/// Hand the sensor rows that have a reading to `$callback!` in the shape
/// `docs id Variant plain|custom { … };` (the reading's docs and payload).
macro_rules! sensor_readings {
    ([$callback:ident] $($rows:tt)*) => {
        $crate::telemetrix::table::sensor_readings!(@rows $callback [] $($rows)*);
    };
    (@rows $cb:ident [$($acc:tt)*]
        $(#[$tm:meta])* $n:literal $t:ident $name:literal; $($rest:tt)*) => {
        $crate::telemetrix::table::sensor_readings!(@rows $cb [$($acc)*] $($rest)*);
    };
    (@rows $cb:ident [$($acc:tt)*] $(#[$tm:meta])* $n:literal $t:ident $name:literal data $lens:tt
        $(#[$rm:meta])* $codec:ident { $($body:tt)* }; $($rest:tt)*) => {
        $crate::telemetrix::table::sensor_readings!(@rows $cb [
            $($acc)* $(#[$rm])* $n $t $codec { $($body)* };
        ] $($rest)*);
    };
    (@rows $cb:ident [$($acc:tt)*]) => {
        $cb! { $($acc)* }
    };
}

pub(crate) use sensor_readings;

/// Hand the module rows to `$callback!`: one row per module type (spec
/// §7), its type byte, its [`ModuleType`](super::ModuleType) variant with
/// that variant's docs, its name, then its MODULE_NEW init and, for a type
/// that sends MODULE_REPORTs, its reports. `init { … }` holds the
/// [`ModuleInit`](super::ModuleInit) variant named after the type and its
/// code as a `custom` row's (`parse(r, id)` after the type byte,
/// `write(w)`, `fields(view, w)`, `read(f, buf)`); `reports [Variants] { … }`
/// holds the [`ModuleReport`](super::ModuleReport) variants in brackets and
/// as declared, the `LEN` rule of a report of the type
/// (`len(len, at) { … }`, `at(i)` the frame's byte `i` if known), and its
/// code (`parse(r, id)` after the type byte, `write(w)`, `fields(view, w)`,
/// `read(f, buf)`). Between them, `data Type` names its MODULE_DATA's
/// [`ModuleCommand`](super::ModuleCommand) type: `table` for a type from a
/// data table ([`hiwonder_table`], [`ssd1306_table`]), or its code
/// (`parse(r, id)`, `write(w, data)`, `fields(w, data)` and `read(f)`, where
/// `data` is the message).
macro_rules! module_table {
    ($callback:ident) => {
        $callback! {
            /// 0: PCA9685 PWM expander.
            0 Pca9685 "pca9685"
                init {
                    variants {
                        /// `port [, addr, u16 freq_hz]`.
                        Pca9685 {
                            /// I2C port 0 or 1.
                            port: u8,
                            /// Address and frequency, or the defaults.
                            config: Option<Pca9685Config>,
                        },
                    }
                    parse(r, id) {
                        let port = r.port()?;
                        let config = if r.remaining() > 0 {
                            let addr = r.u8()?;
                            ensure(addr <= 0x7f, id, "addr")?;
                            Some(Pca9685Config { addr, freq_hz: r.u16()? })
                        } else {
                            None
                        };
                        ModuleInit::Pca9685 { port, config }
                    }
                    write(w) {
                        ModuleInit::Pca9685 { port, config } => {
                            w.u8(port);
                            if let Some(c) = config {
                                w.u8(c.addr);
                                w.u16(c.freq_hz);
                            }
                        }
                    }
                    fields(view, w) {
                        ModuleInit::Pca9685 { port, config } => {
                            w.u("port", port);
                            if let Some(config) = config {
                                w.u("addr", config.addr);
                                w.u("freq_hz", config.freq_hz);
                            }
                        }
                    }
                    read(f, buf) {
                        ModuleInit::Pca9685 {
                            port: u8_(f, "port")?,
                            config: match (f.has("addr"), f.has("freq_hz")) {
                                (false, false) => None,
                                _ => Some(Pca9685Config {
                                    addr: u8_(f, "addr")?,
                                    freq_hz: u16_(f, "freq_hz")?,
                                }),
                            },
                        }
                    }
                }
                data Pca9685Command {
                    parse(r, id) {
                        ensure(r.remaining() > 0, id, "channels")?;
                        let mut channels = List::new();
                        while r.remaining() > 0 {
                            let c = Pca9685Channel { channel: r.u8()?, on: r.u16()?, off: r.u16()? };
                            ensure(c.channel <= 15, id, "channel")?;
                            channels.push(c).map_err(|_| r.bad_length())?;
                        }
                        Pca9685Command { channels }
                    }
                    write(w, data) {
                        for c in &data.channels {
                            w.u8(c.channel);
                            w.u16(c.on);
                            w.u16(c.off);
                        }
                    }
                    fields(w, data) {
                        w.objs("channels", &data.channels)
                    }
                    read(f) {
                        let channels = objects(f, "channels", |c| {
                            Ok(Pca9685Channel {
                                channel: u8_(c, "channel")?,
                                on: u16_(c, "on")?,
                                off: u16_(c, "off")?,
                            })
                        })?;
                        let channels = List::from_slice(&channels)
                            .map_err(|_| format!("`channels` holds {}, at most 5", channels.len()))?;
                        Pca9685Command { channels }
                    }
                };
            /// 1: Hiwonder serial bus servos.
            1 HiwonderServo "hiwonder_servo"
                init {
                    variants {
                        /// `uart, rx, tx, count, count × bus_id`.
                        HiwonderServo {
                            /// UART 0 or 1.
                            uart: u8,
                            /// RX GPIO (< 30).
                            rx: u8,
                            /// TX GPIO (< 30).
                            tx: u8,
                            /// Bus ids of the servos, at most 22; later messages use their index.
                            bus_ids: &'a [u8],
                        },
                    }
                    parse(r, id) {
                        let uart = r.port()?;
                        let (rx, tx) = (r.pin("rx")?, r.pin("tx")?);
                        let count = r.u8()?;
                        ModuleInit::HiwonderServo { uart, rx, tx, bus_ids: r.take(usize::from(count))? }
                    }
                    write(w) {
                        ModuleInit::HiwonderServo { uart, rx, tx, bus_ids } => {
                            w.bytes(&[uart, rx, tx, bus_ids.len() as u8]);
                            w.bytes(bus_ids);
                        }
                    }
                    fields(view, w) {
                        ModuleInit::HiwonderServo { uart, rx, tx, bus_ids } => {
                            w.u("uart", uart);
                            w.u("rx", rx);
                            w.u("tx", tx);
                            w.bytes("bus_ids", bus_ids);
                        }
                    }
                    read(f, buf) {
                        ModuleInit::HiwonderServo {
                            uart: u8_(f, "uart")?,
                            rx: u8_(f, "rx")?,
                            tx: u8_(f, "tx")?,
                            bus_ids: bytes_in(f, "bus_ids", buf)?,
                        }
                    }
                }
                data HiwonderCommand table
                reports [
                    HiwonderPositions, HiwonderIdVerify, HiwonderRange, HiwonderOffset, HiwonderAdded
                ] {
                    variants {
                        /// Hiwonder subtype 0: positions of changed servos (and each at least once
                        /// a second).
                        HiwonderPositions(ServoPositions<'a>),
                        /// Hiwonder subtype 4: ID_VERIFY reply.
                        HiwonderIdVerify {
                            /// The bus id asked about.
                            bus_id: u8,
                            /// Whether it answered.
                            ok: bool,
                        },
                        /// Hiwonder subtype 6: RANGE_READ reply.
                        HiwonderRange {
                            /// Servo index.
                            idx: u8,
                            /// Lower limit in centidegrees.
                            min_cdeg: u16,
                            /// Upper limit in centidegrees.
                            max_cdeg: u16,
                        },
                        /// Hiwonder subtype 8: OFFSET_READ reply.
                        HiwonderOffset {
                            /// Servo index.
                            idx: u8,
                            /// Offset in centidegrees.
                            offset_cdeg: i16,
                        },
                        /// Hiwonder subtype 11: ADD_SERVO reply.
                        HiwonderAdded {
                            /// The bus id added.
                            bus_id: u8,
                            /// Its index.
                            idx: u8,
                        },
                    }
                    len(len, at) {
                        match at(4) {
                            None => len >= 6,
                            Some(0) => len >= 7 && (len - 4) % 3 == 0,
                            Some(4 | 11) => len == 6,
                            Some(6) => len == 9,
                            Some(8) => len == 7,
                            Some(_) => false,
                        }
                    }
                    parse(r, id) {
                        match r.u8()? {
                            0 => {
                                let raw = r.rest();
                                if raw.is_empty() || raw.len() % 3 != 0 {
                                    return Err(r.bad_length());
                                }
                                ModuleReport::HiwonderPositions(ServoPositions::from_raw(raw))
                            }
                            4 => ModuleReport::HiwonderIdVerify { bus_id: r.u8()?, ok: r.flag("ok")? },
                            6 => ModuleReport::HiwonderRange {
                                idx: r.u8()?,
                                min_cdeg: r.u16()?,
                                max_cdeg: r.u16()?,
                            },
                            8 => ModuleReport::HiwonderOffset { idx: r.u8()?, offset_cdeg: r.i16()? },
                            11 => ModuleReport::HiwonderAdded { bus_id: r.u8()?, idx: r.u8()? },
                            _ => return Err(Error::OutOfRange { id, field: "subtype" }),
                        }
                    }
                    write(w) {
                        ModuleReport::HiwonderPositions(p) => {
                            w.u8(0);
                            w.bytes(p.raw());
                        }
                        ModuleReport::HiwonderIdVerify { bus_id, ok } => {
                            w.bytes(&[4, bus_id]);
                            w.flag(ok);
                        }
                        ModuleReport::HiwonderRange { idx, min_cdeg, max_cdeg } => {
                            w.bytes(&[6, idx]);
                            w.u16(min_cdeg);
                            w.u16(max_cdeg);
                        }
                        ModuleReport::HiwonderOffset { idx, offset_cdeg } => {
                            w.bytes(&[8, idx]);
                            w.i16(offset_cdeg);
                        }
                        ModuleReport::HiwonderAdded { bus_id, idx } => w.bytes(&[11, bus_id, idx]),
                    }
                    fields(view, w) {
                        ModuleReport::HiwonderPositions(positions) => {
                            w.s("subtype", "positions");
                            w.objs("positions", &positions);
                        }
                        ModuleReport::HiwonderIdVerify { bus_id, ok } => {
                            w.s("subtype", "id_verify");
                            w.u("bus_id", bus_id);
                            w.flag("ok", ok);
                        }
                        ModuleReport::HiwonderRange { idx, min_cdeg, max_cdeg } => {
                            w.s("subtype", "range");
                            w.u("idx", idx);
                            w.u("min_cdeg", min_cdeg);
                            w.u("max_cdeg", max_cdeg);
                        }
                        ModuleReport::HiwonderOffset { idx, offset_cdeg } => {
                            w.s("subtype", "offset");
                            w.u("idx", idx);
                            w.i("offset_cdeg", offset_cdeg);
                        }
                        ModuleReport::HiwonderAdded { bus_id, idx } => {
                            w.s("subtype", "added");
                            w.u("bus_id", bus_id);
                            w.u("idx", idx);
                        }
                    }
                    read(f, buf) {
                        let subtypes = ["positions", "id_verify", "range", "offset", "added"];
                        match name(f, "subtype", &subtypes)? {
                            0 => {
                                let positions = objects(f, "positions", |p| {
                                    Ok((u8_(p, "idx")?, u16_(p, "centideg")?))
                                })?;
                                *buf = positions
                                    .iter()
                                    .flat_map(|&(idx, cdeg)| {
                                        let [hi, lo] = cdeg.to_be_bytes();
                                        [idx, hi, lo]
                                    })
                                    .collect();
                                ModuleReport::HiwonderPositions(ServoPositions::from_raw(buf))
                            }
                            1 => ModuleReport::HiwonderIdVerify {
                                bus_id: u8_(f, "bus_id")?,
                                ok: flag(f, "ok")?,
                            },
                            2 => ModuleReport::HiwonderRange {
                                idx: u8_(f, "idx")?,
                                min_cdeg: u16_(f, "min_cdeg")?,
                                max_cdeg: u16_(f, "max_cdeg")?,
                            },
                            3 => ModuleReport::HiwonderOffset {
                                idx: u8_(f, "idx")?,
                                offset_cdeg: i16_(f, "offset_cdeg")?,
                            },
                            _ => ModuleReport::HiwonderAdded {
                                bus_id: u8_(f, "bus_id")?,
                                idx: u8_(f, "idx")?,
                            },
                        }
                    }
                };
            /// 2: shutdown relay.
            2 ShutdownRelay "shutdown_relay"
                init {
                    variants {
                        /// `pin, active_level, wait_s`.
                        ShutdownRelay {
                            /// Relay GPIO (< 30).
                            pin: u8,
                            /// Level that drives the relay.
                            active_high: bool,
                            /// Countdown in s.
                            wait_s: u8,
                        },
                    }
                    parse(r, id) {
                        ModuleInit::ShutdownRelay {
                            pin: r.pin("pin")?,
                            active_high: r.flag("active_level")?,
                            wait_s: r.u8()?,
                        }
                    }
                    write(w) {
                        ModuleInit::ShutdownRelay { pin, active_high, wait_s } => {
                            w.u8(pin);
                            w.flag(active_high);
                            w.u8(wait_s);
                        }
                    }
                    fields(view, w) {
                        ModuleInit::ShutdownRelay { pin, active_high, wait_s } => {
                            w.u("pin", pin);
                            w.level("active_level", active_high);
                            w.u("wait_s", wait_s);
                        }
                    }
                    read(f, buf) {
                        ModuleInit::ShutdownRelay {
                            pin: u8_(f, "pin")?,
                            active_high: level(f, "active_level")?,
                            wait_s: u8_(f, "wait_s")?,
                        }
                    }
                }
                data RelayCommand {
                    parse(r, id) {
                        if r.flag("start")? {
                            RelayCommand::Start
                        } else {
                            RelayCommand::Cancel
                        }
                    }
                    write(w, data) {
                        w.flag(*data == RelayCommand::Start)
                    }
                    fields(w, data) {
                        let subtype = match data {
                            RelayCommand::Start => "start",
                            RelayCommand::Cancel => "cancel",
                        };
                        w.s("subtype", subtype)
                    }
                    read(f) {
                        match name(f, "subtype", &["start", "cancel"])? {
                            0 => RelayCommand::Start,
                            _ => RelayCommand::Cancel,
                        }
                    }
                };
            /// 3: SSD1306 OLED display.
            3 Ssd1306 "ssd1306"
                init {
                    variants {
                        /// `port [, addr]`.
                        Ssd1306 {
                            /// I2C port 0 or 1.
                            port: u8,
                            /// 7-bit address (default 0x3C).
                            addr: Option<u8>,
                        },
                    }
                    parse(r, id) {
                        let port = r.port()?;
                        let addr = if r.remaining() > 0 { Some(r.i2c_addr()?) } else { None };
                        ModuleInit::Ssd1306 { port, addr }
                    }
                    write(w) {
                        ModuleInit::Ssd1306 { port, addr } => {
                            w.u8(port);
                            if let Some(a) = addr {
                                w.u8(a);
                            }
                        }
                    }
                    fields(view, w) {
                        ModuleInit::Ssd1306 { port, addr } => {
                            w.u("port", port);
                            if let Some(addr) = addr {
                                w.u("addr", addr);
                            }
                        }
                    }
                    read(f, buf) {
                        ModuleInit::Ssd1306 {
                            port: u8_(f, "port")?,
                            addr: if f.has("addr") { Some(u8_(f, "addr")?) } else { None },
                        }
                    }
                }
                data Ssd1306Command table
                reports [Ssd1306Done, Ssd1306Disabled] {
                    variants {
                        /// SSD1306: a text or binary transfer completed.
                        Ssd1306Done {
                            /// Which transfer.
                            kind: Ssd1306Done,
                            /// Text length, or 1.
                            len: u8,
                            /// Display x position.
                            display_x: u8,
                            /// Whether the display is enabled.
                            enabled: bool,
                        },
                        /// SSD1306: a request was refused because the display is disabled.
                        Ssd1306Disabled {
                            /// Subtype of the refused request, echoed: 0..=3, or whatever a
                            /// request carried ([`Quirk::EchoedRequestByte`](super::Quirk::EchoedRequestByte);
                            /// the encoder sends 0..=3 only).
                            request_sub: u8,
                        },
                    }
                    len(len, at) {
                        len == 5 || len == 7
                    }
                    parse(r, id) {
                        match r.remaining() {
                            4 => {
                                let kind = match r.u8()? {
                                    1 => Ssd1306Done::Text,
                                    3 => Ssd1306Done::Binary,
                                    _ => return Err(Error::OutOfRange { id, field: "msg_type" }),
                                };
                                ModuleReport::Ssd1306Done {
                                    kind,
                                    len: r.u8()?,
                                    display_x: r.u8()?,
                                    enabled: r.flag("enabled")?,
                                }
                            }
                            2 => {
                                // The firmware echoes the request's subtype byte, whatever
                                // it was: accepted, and flagged as a quirk above 3.
                                let request_sub = r.u8()?;
                                ensure(r.u8()? == 254, id, "disabled marker")?;
                                ModuleReport::Ssd1306Disabled { request_sub }
                            }
                            _ => return Err(r.bad_length()),
                        }
                    }
                    write(w) {
                        ModuleReport::Ssd1306Done { kind, len, display_x, enabled } => {
                            let kind = match kind {
                                Ssd1306Done::Text => 1,
                                Ssd1306Done::Binary => 3,
                            };
                            w.bytes(&[kind, len, display_x]);
                            w.flag(enabled);
                        }
                        ModuleReport::Ssd1306Disabled { request_sub } => w.bytes(&[request_sub, 254]),
                    }
                    fields(view, w) {
                        ModuleReport::Ssd1306Done { kind, len, display_x, enabled } => {
                            let subtype = match kind {
                                Ssd1306Done::Text => "text_done",
                                Ssd1306Done::Binary => "binary_done",
                            };
                            w.s("subtype", subtype);
                            w.u("len", len);
                            w.u("display_x", display_x);
                            w.flag("enabled", enabled);
                        }
                        ModuleReport::Ssd1306Disabled { request_sub } => {
                            w.s("subtype", "disabled");
                            w.u("request_sub", request_sub);
                        }
                    }
                    read(f, buf) {
                        let subtypes = ["text_done", "binary_done", "disabled"];
                        match name(f, "subtype", &subtypes)? {
                            kind @ (0 | 1) => ModuleReport::Ssd1306Done {
                                kind: if kind == 0 { Ssd1306Done::Text } else { Ssd1306Done::Binary },
                                len: u8_(f, "len")?,
                                display_x: u8_(f, "display_x")?,
                                enabled: flag(f, "enabled")?,
                            },
                            _ => ModuleReport::Ssd1306Disabled {
                                request_sub: u8_(f, "request_sub")?,
                            },
                        }
                    }
                };
        }
    };
}

pub(crate) use module_table;
