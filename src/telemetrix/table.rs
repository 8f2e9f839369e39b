//! The command table: every Telemetrix command (host → Pico) described once.
//!
//! Each row gives a command's id, the name of its id constant, its `type`
//! name in the JSON-lines schema, the [`Command`](super::Command) variants
//! that carry it, the dialects that define it, its `LEN` range (one pair, or
//! a `match` on the dialect) and its payload: `plain { field: kind "key", … }`
//! for a command whose fields are fixed bytes in wire order (its variant is
//! built from them, with the row's docs), or `custom { variants }` for one
//! whose layout depends on its content or dialect (its variants as written,
//! and a hand-written arm in each consumer).
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
//! | `counted(name)` | `&[u8]`| a count byte (`name` in errors), then the bytes | array |
//! | `trailing_flag` | `Option<bool>` | a last `0`/`1` byte, or nothing | `true`/`false`, or absent |
//! | `nonzero_u32`   | `u32`  | four bytes, big-endian, not 0  | number          |
//! | `counted_pins(name, each)` | `&[u8]` | as `counted`, each byte a GPIO `< 30` (`each` in errors) | array |
//! | `trailing_u16_pair(a, b)` | `Option<(u16, u16)>` | two last `u16`s, or nothing | `a` and `b`, or absent |
//! | `array(n)`      | `[u8; n]` | `n` bytes                   | array           |
//! | `rest`          | `&[u8]`| every byte left                | array           |
//! | `i16`           | `i16`  | two bytes, big-endian          | number          |
//! | `u16_max(max)`  | `u16`  | two bytes, big-endian, `<= max` | number         |
//!
//! A row has at most one `counted` field (the serde reader borrows one buffer
//! for it), and a `trailing_flag` only last.
//!
//! The table is a `macro_rules!` macro that hands its rows to a callback
//! macro: each consumer (the id constants in `wire`, the enum, parser and
//! writer in `command`, the fields in `fields`, the names in `names`, the
//! serde reader in `schema`) expands the rows where its private helpers are
//! in scope. The parser's consumer is a muncher that takes the hand-written
//! `custom` arms too, so that all arms are one `match`: split in two
//! functions the Pico's command decoder linked 9,096 B instead of 7,736 B
//! (`python3 size/report.py`). A
//! `macro_rules!` table rather than a generator: it needs no build script, no
//! checked-in output to keep current and no extra CI step, and the rows are
//! read by the compiler itself, so a typo is a compile error at the row.
//! The wire layouts stay checked against the protocol spec by the tests
//! (golden vectors in `tests/telemetrix.rs`), not by the table.
//!
//! The module data tables (`hiwonder_table`, `ssd1306_table`) describe the
//! MODULE_DATA messages of a module type that starts with a subtype byte
//! the same way, one row per subtype: the enum, its encode and parse
//! (`ModuleCommand`), its JSON fields and its serde reader come from them.

/// Hand the command rows to `$callback!`, after `$extra` (in brackets) when
/// given: a consumer that expands in expression position takes its
/// call-site names and hand-written arms there.
macro_rules! command_table {
    ($callback:ident $(, $($extra:tt)+)?) => {
        $callback! {
            $([$($extra)+])?
            /// 0 SERIAL_LOOP_BACK: the Pico echoes `byte` in report 0.
            0 SERIAL_LOOP_BACK "serial_loop_back" [LoopBack] in [Mirte13, Mirte12, Upstream11] len (2, 2)
                plain LoopBack {
                    /// The byte to echo.
                    byte: u8 "byte",
                };
            1 SET_PIN_MODE "set_pin_mode" [SetPinMode] in [Mirte13, Mirte12, Upstream11] len (3, 6)
                custom {
                    /// 1 SET_PIN_MODE.
                    SetPinMode {
                        /// GPIO number (< 30), or the analog pin for [`PinMode::AnalogInput`].
                        pin: u8,
                        /// Mode and tail.
                        mode: PinMode,
                    },
                };
            2 DIGITAL_WRITE "digital_write" [DigitalWrite] in [Mirte13, Mirte12, Upstream11] len (3, 3)
                custom {
                    /// 2 DIGITAL_WRITE.
                    DigitalWrite {
                        /// GPIO number (< 30).
                        pin: u8,
                        /// Level, `true` for high: `1` on the wire, in JSON and in `Display`
                        /// (see [levels and flags](super#levels-and-flags)).
                        value: bool,
                    },
                };
            // Up to 9 pins and, as a real host may send, 1 or 2 trailing
            // bytes that the firmware ignores (it takes (LEN - 1) / 3 pins).
            3 PWM_WRITE "pwm_write" [PwmWrite] in [Mirte13, Mirte12, Upstream11] len { Dialect::Mirte13 => (4, 30), _ => (4, 4) }
                custom {
                    /// 3 PWM_WRITE (k pins at once in mirte 1.3).
                    PwmWrite(PwmPins),
                };
            4 MODIFY_REPORTING "modify_reporting" [ModifyReporting] in [Mirte13, Mirte12, Upstream11] len (3, 3)
                custom {
                    /// 4 MODIFY_REPORTING.
                    ModifyReporting(ModifyReporting),
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
                };
            12 I2C_WRITE "i2c_write" [I2cWrite, I2cWriteUpstream] in [Mirte13, Mirte12, Upstream11] len { Dialect::Upstream11 => (6, 30), _ => (7, 30) }
                custom {
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
            /// 19 INITIALIZE_NEO_PIXELS: fills and shows.
            19 INITIALIZE_NEO_PIXELS "initialize_neo_pixels" [InitNeoPixels] in [Mirte13, Mirte12, Upstream11] len (6, 6)
                plain InitNeoPixels {
                    /// GPIO number (< 30).
                    pin: pin "pin",
                    /// Number of pixels, ≤ 100.
                    count: range(0, 100) "count",
                    /// Fill colour.
                    rgb: rgb "rgb",
                };
            /// 20 SHOW_NEO_PIXELS.
            20 SHOW_NEO_PIXELS "show_neo_pixels" [ShowNeoPixels] in [Mirte13, Mirte12, Upstream11] len (1, 1)
                plain ShowNeoPixels {};
            /// 21 SET_NEO_PIXEL.
            21 SET_NEO_PIXEL "set_neo_pixel" [SetNeoPixel] in [Mirte13, Mirte12, Upstream11] len (6, 6)
                plain SetNeoPixel {
                    /// Pixel index (< 100).
                    index: range(0, 99) "index",
                    /// Colour.
                    rgb: rgb "rgb",
                    /// Show at once.
                    auto_show: flag "auto_show",
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
                    cs_pins: counted_pins("cs count", "cs_pin") "cs_pins",
                };
            /// 25 SPI_WRITE_BLOCKING.
            25 SPI_WRITE_BLOCKING "spi_write_blocking" [SpiWrite] in [Mirte13, Mirte12, Upstream11] len (3, 30)
                plain SpiWrite {
                    /// 0 or 1.
                    port: range(0, 1) "port",
                    /// At most 27 bytes.
                    data: counted("len") "data",
                };
            /// 26 SPI_READ_BLOCKING: answered by report 13.
            26 SPI_READ_BLOCKING "spi_read_blocking" [SpiRead] in [Mirte13, Mirte12, Upstream11] len (4, 4)
                plain SpiRead {
                    /// 0 or 1.
                    port: range(0, 1) "port",
                    /// Bytes to read, ≤ 60.
                    len: range(0, 60) "n",
                    /// Byte clocked out while reading.
                    tx_fill: u8 "tx_fill",
                };
            /// 27 SPI_SET_FORMAT.
            27 SPI_SET_FORMAT "spi_set_format" [SpiSetFormat] in [Mirte13, Mirte12, Upstream11] len (5, 5)
                plain SpiSetFormat {
                    /// 0 or 1.
                    port: range(0, 1) "port",
                    /// 4..=16.
                    data_bits: range(4, 16) "data_bits",
                    /// Clock polarity.
                    cpol: level "cpol",
                    /// Clock phase.
                    cpha: level "cpha",
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
                };
            31 SENSOR_NEW "sensor_new" [SensorNew] in [Mirte13, Mirte12] len { Dialect::Mirte12 => (3, 9), _ => (3, 10) }
                custom {
                    /// 31 SENSOR_NEW (mirte 1.3, and mirte 1.2's own layout
                    /// [`SensorNew::AddMirte12`]).
                    SensorNew(SensorNew),
                };
            /// 32 PING (mirte only): answered by report 32.
            32 PING "ping" [Ping] in [Mirte13, Mirte12] len (2, 2)
                plain Ping {
                    /// Echoed in the reply.
                    counter: u8 "counter",
                };
            33 MODULE_NEW "module_new" [ModuleNew] in [Mirte13] len (3, 30)
                custom {
                    /// 33 MODULE_NEW (mirte 1.3).
                    ModuleNew(ModuleNew<'a>),
                };
            34 MODULE_DATA "module_data" [ModuleData] in [Mirte13] len (2, 30)
                custom {
                    /// 34 MODULE_DATA (mirte 1.3): build typed data with
                    /// [`Command::module_data`], read it with the module's `parse`.
                    ModuleData {
                        /// Module number (modules are numbered 0, 1, 2, … in creation order).
                        module_num: u8,
                        /// 1..=28 bytes for the module.
                        data: &'a [u8],
                    },
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

/// Hand the report rows to `$callback!`, after `$extra` (in brackets) when
/// given. A row gives a report's id (spec §5), the name of its
/// [`report_id`](super::report_id) constant, the dialects that define it,
/// its `type` names with the [`Report`](super::Report) variants each names
/// (report 8 has one per dialect family), and its payload, as in the
/// command table: `plain { field: kind "key", … }` (one variant, named by
/// the row, with the row's docs) or `custom { variants }` (a hand-written
/// arm in each consumer). A report's `LEN` check is `report_len_ok`, which
/// looks at a frame's first bytes to end a streamed frame early.
macro_rules! report_table {
    ($callback:ident $(, $($extra:tt)+)?) => {
        $callback! {
            $([$($extra)+])?
            /// 0 SERIAL_LOOP_BACK_REPORT: loopback echo.
            0 SERIAL_LOOP_BACK in [Mirte13, Mirte12, Upstream11]
                { "serial_loop_back_report" [LoopBack] } plain {
                    /// The echoed byte.
                    byte: u8 "byte",
                };
            /// 2 DIGITAL_REPORT.
            2 DIGITAL in [Mirte13, Mirte12, Upstream11]
                { "digital_report" [Digital] } custom {
                    /// 2: a digital input changed.
                    Digital {
                        /// GPIO (< 30).
                        pin: u8,
                        /// Level, `true` for high: `1` on the wire, in JSON and in `Display`
                        /// (see [levels and flags](super#levels-and-flags)).
                        value: bool,
                    },
                };
            /// 3 ANALOG_REPORT.
            3 ANALOG in [Mirte13, Mirte12, Upstream11]
                { "analog_report" [Analog] } custom {
                    /// 3: an analog input changed.
                    Analog {
                        /// GPIO 26..=30 (mirte 1.3; ADC 0..=4 from older builds is accepted
                        /// too), ADC 0..=4 in older dialects.
                        pin: u8,
                        /// 0..=4095.
                        value: u16,
                    },
                };
            /// 5 FIRMWARE_REPORT: firmware version (mirte 1.3 sends 1.3).
            5 FIRMWARE in [Mirte13, Mirte12, Upstream11]
                { "firmware_version" [FirmwareVersion] } plain {
                    /// Major.
                    major: u8 "major",
                    /// Minor.
                    minor: u8 "minor",
                };
            /// 6 REPORT_PICO_UNIQUE_ID: unique id (6 board bytes, then `00 00` in mirte firmware).
            6 UNIQUE_ID in [Mirte13, Mirte12, Upstream11]
                { "pico_unique_id" [UniqueId] } plain {
                    /// The 8 bytes.
                    id: array(8) "id",
                };
            /// 8 I2C_WRITE_REPORT (upstream: I2C_WRITE_FAILED).
            8 I2C_WRITE in [Mirte13, Mirte12, Upstream11]
                { "i2c_write_report" [I2cWrite], "i2c_write_failed" [I2cWriteFailed] } custom {
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
                };
            /// 9 I2C_READ_FAILED (mirte): I2C read NAK.
            9 I2C_READ_FAILED in [Mirte13, Mirte12]
                { "i2c_read_failed" [I2cReadFailed] } plain {
                    /// Port.
                    port: range(0, 1) "port",
                    /// Address.
                    addr: range(0, 0x7f) "addr",
                    /// Leftover from the previous I2C report.
                    stale: u8 "stale",
                };
            /// 10 I2C_READ_REPORT.
            10 I2C_READ in [Mirte13, Mirte12, Upstream11]
                { "i2c_read_report" [I2cRead, I2cReadUpstream] } custom {
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
                };
            /// 11 SONAR_DISTANCE.
            11 SONAR in [Mirte13, Mirte12, Upstream11]
                { "sonar_distance" [Sonar] } custom {
                    /// 11: sonar distance.
                    Sonar(Sonar),
                };
            /// 12 DHT_REPORT.
            12 DHT in [Mirte13, Mirte12, Upstream11]
                { "dht_report" [Dht] } custom {
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
                };
            /// 13 SPI_REPORT: SPI read data.
            13 SPI in [Mirte13, Mirte12, Upstream11]
                { "spi_report" [Spi] } plain {
                    /// Port.
                    port: range(0, 1) "port",
                    /// 0..=60 bytes.
                    data: counted("n") "data",
                };
            /// 14 ENCODER_REPORT.
            14 ENCODER in [Mirte13, Mirte12]
                { "encoder_report" [Encoder] } custom {
                    /// 14 (mirte): encoder steps since the last report (never 0).
                    Encoder {
                        /// GPIO A (< 30).
                        pin: u8,
                        /// Steps.
                        steps: i8,
                    },
                };
            /// 20 SENSOR_REPORT.
            20 SENSOR in [Mirte13, Mirte12]
                { "sensor_report" [Sensor] } custom {
                    /// 20 (mirte 1.3): a sensor reading.
                    Sensor {
                        /// The sensor's number.
                        sensor_num: u8,
                        /// Type and data.
                        reading: SensorReading,
                    },
                };
            /// 21 SENSOR_MAIN_REPORT.
            21 SENSOR_MAIN in [Mirte13]
                { "sensor_main_report" [SensorSupported] } custom {
                    /// 21 (mirte 1.3): answer to a sensor check.
                    SensorSupported {
                        /// The type asked about.
                        sensor_type: u8,
                        /// Supported.
                        supported: bool,
                    },
                };
            /// 32 PONG_REPORT (mirte): answer to PING.
            32 PONG in [Mirte13, Mirte12]
                { "pong" [Pong] } plain {
                    /// The PING's counter.
                    counter: u8 "counter",
                    /// Random per boot, 0..=99: a change means the Pico rebooted.
                    boot_id: range(0, 99) "boot_id",
                };
            /// 33 MODULE_MAIN_REPORT.
            33 MODULE_MAIN in [Mirte13]
                { "module_main_report" [ModuleSupported] } custom {
                    /// 33 (mirte 1.3): answer to a module check.
                    ModuleSupported {
                        /// The type asked about.
                        module_type: u8,
                        /// Supported.
                        supported: bool,
                    },
                };
            /// 34 MODULE_REPORT.
            34 MODULE in [Mirte13]
                { "module_report" [Module] } custom {
                    /// 34 (mirte 1.3): a module's report.
                    Module {
                        /// The module's number.
                        module_num: u8,
                        /// Type, subtype and data.
                        report: ModuleReport<'a>,
                    },
                };
            /// 35 GET_ID_REPORT (mirte 1.3): the saved id (`FF` if never set).
            35 GET_ID in [Mirte13]
                { "get_id_report" [Id] } plain {
                    /// The id.
                    id: u8 "id",
                };
            /// 36 SET_ID_REPORT (mirte 1.3): the id just saved.
            36 SET_ID in [Mirte13]
                { "set_id_report" [IdSet] } plain {
                    /// The id.
                    id: u8 "id",
                };
            /// 37 FEATURE_CHECK (mirte 1.3): answer to FEATURE_CHECK.
            37 FEATURE_CHECK in [Mirte13]
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
            99 DEBUG_PRINT in [Mirte13, Mirte12]
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
/// kinds, or `custom` variants with hand-written arms).
macro_rules! hiwonder_table {
    ($callback:ident) => {
        $callback! {
            /// Hiwonder servo data (module type 1), spec §7.1. Servos are addressed by
            /// their index in the init list. The firmware drops all of it unless the last
            /// PING is less than 2 s old.
            HiwonderCommand;
            1 "set_angle" [SetAngle] custom {
                /// 1 SET_ANGLE: 1..=5 moves.
                SetAngle(List<ServoMove, 5>),
            };
            2 "enable" [Enable] custom {
                /// 2 ENABLE: an empty list means all servos.
                Enable {
                    /// Torque on or off.
                    enabled: bool,
                    /// Servo indices (at most 25), or none for all.
                    servos: List<u8, 25>,
                },
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
                /// 0 TEXT: at most 26 characters, appended to the text buffer.
                Text(List<u8, 26>),
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
