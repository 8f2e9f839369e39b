//! The command table: every Telemetrix command (host → Pico) described once.
//!
//! Each row gives a command's id, the name of its id constant, its `type`
//! name in the JSON-lines schema, the [`Command`](super::Command) variants
//! that carry it, the dialects that define it, its `LEN` range (one pair, or
//! a `match` on the dialect) and its payload: `plain { field: kind "key", … }`
//! for a command whose fields are fixed bytes in wire order, or `custom` for
//! one whose layout depends on its content or dialect (a hand-written arm in
//! each consumer).
//!
//! A field kind says how the field is read, checked, written and named:
//!
//! | kind            | Rust   | wire                           | JSON            |
//! |-----------------|--------|--------------------------------|-----------------|
//! | `u8`            | `u8`   | one byte                       | number          |
//! | `pin`           | `u8`   | one byte, a GPIO `< 30`        | number          |
//! | `range(lo, hi)` | `u8`   | one byte in `lo..=hi`          | number          |
//! | `only(pat)`     | `u8`   | one byte matching `pat`        | number          |
//! | `u16`           | `u16`  | two bytes, big-endian          | number          |
//! | `flag`          | `bool` | one byte, `0` or `1`           | `true`/`false`  |
//! | `level`         | `bool` | one byte, `0` or `1`           | `0`/`1`         |
//! | `rgb`           | `Rgb`  | three bytes                    | `r`, `g`, `b`   |
//!
//! The table is a `macro_rules!` macro that hands its rows to a callback
//! macro: each consumer (the id constants in `wire`, the parser and writer in
//! `command`, the fields in `fields`, the names in `names`, the serde reader
//! in `schema`) expands the rows where its private helpers are in scope. A
//! `macro_rules!` table rather than a generator: it needs no build script, no
//! checked-in output to keep current and no extra CI step, and the rows are
//! read by the compiler itself, so a typo is a compile error at the row.
//! The wire layouts stay checked against the protocol spec by the tests
//! (golden vectors in `tests/telemetrix.rs`), not by the table.

/// Hand the command rows to `$callback!`, after `$extra` (in brackets) when
/// given: a consumer that expands in expression position takes its
/// call-site names and hand-written arms there.
macro_rules! command_table {
    ($callback:ident $(, $($extra:tt)+)?) => {
        $callback! {
            $([$($extra)+])?
            0 SERIAL_LOOP_BACK "serial_loop_back" [LoopBack] in [Mirte13, Mirte12, Upstream11]
                len (2, 2) plain LoopBack { byte: u8 "byte" };
            1 SET_PIN_MODE "set_pin_mode" [SetPinMode] in [Mirte13, Mirte12, Upstream11]
                len (3, 6) custom;
            2 DIGITAL_WRITE "digital_write" [DigitalWrite] in [Mirte13, Mirte12, Upstream11]
                len (3, 3) custom;
            // Up to 9 pins and, as a real host may send, 1 or 2 trailing
            // bytes that the firmware ignores (it takes (LEN - 1) / 3 pins).
            3 PWM_WRITE "pwm_write" [PwmWrite] in [Mirte13, Mirte12, Upstream11]
                len { Dialect::Mirte13 => (4, 30), _ => (4, 4) } custom;
            4 MODIFY_REPORTING "modify_reporting" [ModifyReporting] in [Mirte13, Mirte12, Upstream11]
                len (3, 3) custom;
            5 GET_FIRMWARE_VERSION "get_firmware_version" [GetFirmwareVersion] in [Mirte13, Mirte12, Upstream11]
                len (1, 1) plain GetFirmwareVersion {};
            6 GET_PICO_UNIQUE_ID "get_pico_unique_id" [GetUniqueId] in [Mirte13, Mirte12, Upstream11]
                len (1, 1) plain GetUniqueId {};
            7 SERVO_ATTACH "servo_attach" [ServoAttach] in [Mirte13, Mirte12, Upstream11]
                len (2, 6) custom;
            8 SERVO_WRITE "servo_write" [ServoWrite] in [Mirte13, Mirte12, Upstream11]
                len (4, 4) plain ServoWrite { pin: pin "pin", pulse_us: u16 "pulse_us" };
            9 SERVO_DETACH "servo_detach" [ServoDetach] in [Mirte13, Mirte12, Upstream11]
                len (2, 2) plain ServoDetach { pin: pin "pin" };
            10 I2C_BEGIN "i2c_begin" [I2cBegin] in [Mirte13, Mirte12, Upstream11]
                len (4, 4) plain I2cBegin { port: range(0, 1) "port", sda: pin "sda", scl: pin "scl" };
            11 I2C_READ "i2c_read" [I2cRead, I2cReadUpstream] in [Mirte13, Mirte12, Upstream11]
                len { Dialect::Upstream11 => (6, 6), _ => (7, 7) } custom;
            12 I2C_WRITE "i2c_write" [I2cWrite, I2cWriteUpstream] in [Mirte13, Mirte12, Upstream11]
                len { Dialect::Upstream11 => (6, 30), _ => (7, 30) } custom;
            13 SONAR_NEW "sonar_new" [SonarNew] in [Mirte13, Mirte12, Upstream11]
                len (3, 3) plain SonarNew { trig: pin "trig", echo: pin "echo" };
            14 DHT_NEW "dht_new" [DhtNew] in [Mirte13, Mirte12, Upstream11]
                len (2, 2) plain DhtNew { pin: pin "pin" };
            15 STOP_ALL_REPORTS "stop_all_reports" [StopAllReports] in [Mirte13, Mirte12, Upstream11]
                len (1, 1) plain StopAllReports {};
            16 ENABLE_ALL_REPORTS "enable_all_reports" [EnableAllReports] in [Mirte13, Mirte12, Upstream11]
                len (1, 1) plain EnableAllReports {};
            17 RESET_DATA "reset_data" [ResetData] in [Mirte13, Mirte12, Upstream11]
                len (1, 1) plain ResetData {};
            18 RESET_BOARD "reset_board" [ResetBoard] in [Mirte13, Mirte12, Upstream11]
                len (1, 1) plain ResetBoard {};
            19 INITIALIZE_NEO_PIXELS "initialize_neo_pixels" [InitNeoPixels] in [Mirte13, Mirte12, Upstream11]
                len (6, 6) plain InitNeoPixels { pin: pin "pin", count: range(0, 100) "count", rgb: rgb "rgb" };
            20 SHOW_NEO_PIXELS "show_neo_pixels" [ShowNeoPixels] in [Mirte13, Mirte12, Upstream11]
                len (1, 1) plain ShowNeoPixels {};
            21 SET_NEO_PIXEL "set_neo_pixel" [SetNeoPixel] in [Mirte13, Mirte12, Upstream11]
                len (6, 6) plain SetNeoPixel {
                    index: range(0, 99) "index", rgb: rgb "rgb", auto_show: flag "auto_show"
                };
            22 CLEAR_ALL_NEO_PIXELS "clear_all_neo_pixels" [ClearAllNeoPixels] in [Mirte13, Mirte12, Upstream11]
                len (1, 2) custom;
            23 FILL_NEO_PIXELS "fill_neo_pixels" [FillNeoPixels] in [Mirte13, Mirte12, Upstream11]
                len (5, 5) plain FillNeoPixels { rgb: rgb "rgb", auto_show: flag "auto_show" };
            24 SPI_INIT "spi_init" [SpiInit] in [Mirte13, Mirte12, Upstream11]
                len (10, 30) custom;
            25 SPI_WRITE_BLOCKING "spi_write_blocking" [SpiWrite] in [Mirte13, Mirte12, Upstream11]
                len (3, 30) custom;
            26 SPI_READ_BLOCKING "spi_read_blocking" [SpiRead] in [Mirte13, Mirte12, Upstream11]
                len (4, 4) plain SpiRead { port: range(0, 1) "port", len: range(0, 60) "n", tx_fill: u8 "tx_fill" };
            27 SPI_SET_FORMAT "spi_set_format" [SpiSetFormat] in [Mirte13, Mirte12, Upstream11]
                len (5, 5) plain SpiSetFormat {
                    port: range(0, 1) "port", data_bits: range(4, 16) "data_bits",
                    cpol: level "cpol", cpha: level "cpha"
                };
            28 SPI_CS_CONTROL "spi_cs_control" [SpiCsControl] in [Mirte13, Mirte12, Upstream11]
                len (3, 3) plain SpiCsControl { cs_pin: pin "cs_pin", high: level "level" };
            29 SET_SCAN_DELAY "set_scan_delay" [SetScanDelay] in [Mirte13, Mirte12]
                len (2, 2) plain SetScanDelay { delay_ms: u8 "delay_ms" };
            30 ENCODER_NEW "encoder_new" [EncoderNew] in [Mirte13, Mirte12]
                len { Dialect::Mirte12 => (4, 4), _ => (5, 5) } custom;
            31 SENSOR_NEW "sensor_new" [SensorNew] in [Mirte13, Mirte12]
                len { Dialect::Mirte12 => (3, 9), _ => (3, 10) } custom;
            32 PING "ping" [Ping] in [Mirte13, Mirte12]
                len (2, 2) plain Ping { counter: u8 "counter" };
            33 MODULE_NEW "module_new" [ModuleNew] in [Mirte13]
                len (3, 30) custom;
            34 MODULE_DATA "module_data" [ModuleData] in [Mirte13]
                len (2, 30) custom;
            35 GET_ID "get_id" [GetId] in [Mirte13]
                len (1, 1) plain GetId {};
            36 SET_ID "set_id" [SetId] in [Mirte13]
                len (2, 2) plain SetId { id: u8 "id" };
            // The command is `feature_request` (the report is
            // `feature_check`), so that every name names one direction.
            37 FEATURE_CHECK "feature_request" [FeatureCheck] in [Mirte13]
                len (2, 2) plain FeatureCheck { msg_type: u8 "msg_type" };
            38 BOOTLOADER_RESET "bootloader_reset" [BootloaderReset] in [Mirte13]
                len (1, 1) plain BootloaderReset {};
        }
    };
}

pub(crate) use command_table;
