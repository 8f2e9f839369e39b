//! The serde form of every Telemetrix message is the `robowire` tool's
//! JSON-lines schema: for every command and report kind (and the dialect
//! forms), `serde_json` writes the tool's line for the frame (without
//! `offset` and `len`), and the line reads back to the same frame; bad lines
//! give the tool's messages.

#![cfg(feature = "serde")]

use robowire::telemetrix::{
    both_decoder, device_decoder, CaptureContext, Command, CommandBuf, Dialect, MessageBuf, Report,
    ReportBuf,
};
use serde::Deserialize;

const M13: Dialect = Dialect::Mirte13;
const M12: Dialect = Dialect::Mirte12;
const U11: Dialect = Dialect::Upstream11;
const HOST: bool = true;
const PICO: bool = false;

/// The tool's lines (of robowire 0.1) for one frame of every kind: dialect,
/// direction (host: a command), frame, line.
const CASES: &[(Dialect, bool, &str, &str)] = &[
    // mirte 1.2's sensors (spec §10.1): SENSOR_NEW without a subtype byte and
    // with the settings bytes sent, the VEML6040 report little-endian.
    (
        M12,
        HOST,
        "04 1f 00 04 01",
        r#"{"type":"sensor_new","subtype":"add","sensor_num":0,"sensor_type":"veml6040","settings":[1]}"#,
    ),
    (
        M12,
        HOST,
        "03 1f 02 04",
        r#"{"type":"sensor_new","subtype":"add","sensor_num":2,"sensor_type":"veml6040","settings":[]}"#,
    ),
    (
        M12,
        PICO,
        "0b 14 00 04 10 27 20 4e 30 75 40 9c",
        r#"{"type":"sensor_report","sensor_num":0,"sensor_type":"veml6040","reading":{"r":10000,"g":20000,"b":30000,"w":40000}}"#,
    ),
    (
        M13,
        HOST,
        "02 00 41",
        r#"{"type":"serial_loop_back","byte":65}"#,
    ),
    (
        M13,
        HOST,
        "04 01 0A 00 01",
        r#"{"type":"set_pin_mode","pin":10,"mode":"digital_input","report_enable":true}"#,
    ),
    (
        M13,
        HOST,
        "04 01 0A 03 01",
        r#"{"type":"set_pin_mode","pin":10,"mode":"digital_input_pull_up","report_enable":true}"#,
    ),
    (
        M13,
        HOST,
        "04 01 0A 04 00",
        r#"{"type":"set_pin_mode","pin":10,"mode":"digital_input_pull_down","report_enable":false}"#,
    ),
    (
        M13,
        HOST,
        "03 01 19 01",
        r#"{"type":"set_pin_mode","pin":25,"mode":"digital_output"}"#,
    ),
    (
        M13,
        HOST,
        "03 01 10 02",
        r#"{"type":"set_pin_mode","pin":16,"mode":"pwm_output"}"#,
    ),
    (
        M13,
        HOST,
        "06 01 1A 05 00 05 01",
        r#"{"type":"set_pin_mode","pin":26,"mode":"analog_input","differential":5,"report_enable":true}"#,
    ),
    (
        M13,
        HOST,
        "03 02 19 01",
        r#"{"type":"digital_write","pin":25,"value":1}"#,
    ),
    (
        M13,
        HOST,
        "03 02 19 00",
        r#"{"type":"digital_write","pin":25,"value":0}"#,
    ),
    (
        M13,
        HOST,
        "07 03 0F 05 DC 10 05 DC",
        r#"{"type":"pwm_write","pins":[{"pin":15,"value":1500},{"pin":16,"value":1500}]}"#,
    ),
    (
        M13,
        HOST,
        "03 04 00 00",
        r#"{"type":"modify_reporting","action":"disable_all"}"#,
    ),
    (
        M13,
        HOST,
        "03 04 01 1A",
        r#"{"type":"modify_reporting","action":"enable_analog","pin":26}"#,
    ),
    (
        M13,
        HOST,
        "03 04 03 1A",
        r#"{"type":"modify_reporting","action":"disable_analog","pin":26}"#,
    ),
    (M13, HOST, "01 05", r#"{"type":"get_firmware_version"}"#),
    (M13, HOST, "01 06", r#"{"type":"get_pico_unique_id"}"#),
    (M13, HOST, "02 07 05", r#"{"type":"servo_attach","pin":5}"#),
    (
        M13,
        HOST,
        "06 07 05 01 F4 09 C4",
        r#"{"type":"servo_attach","pin":5,"min_us":500,"max_us":2500}"#,
    ),
    (
        M13,
        HOST,
        "04 08 05 05 DC",
        r#"{"type":"servo_write","pin":5,"pulse_us":1500}"#,
    ),
    (M13, HOST, "02 09 05", r#"{"type":"servo_detach","pin":5}"#),
    (
        M13,
        HOST,
        "04 0A 00 04 05",
        r#"{"type":"i2c_begin","port":0,"sda":4,"scl":5}"#,
    ),
    (
        M13,
        HOST,
        "07 0B 00 68 03 75 01 00",
        r#"{"type":"i2c_read","port":0,"addr":104,"msg_id":3,"reg":117,"n":1,"no_stop":0}"#,
    ),
    (
        M13,
        HOST,
        "08 0C 00 3C 07 02 00 00 AF",
        r#"{"type":"i2c_write","port":0,"addr":60,"msg_id":7,"no_stop":0,"data":[0,175]}"#,
    ),
    (
        M13,
        HOST,
        "03 0D 09 0A",
        r#"{"type":"sonar_new","trig":9,"echo":10}"#,
    ),
    (M13, HOST, "02 0E 04", r#"{"type":"dht_new","pin":4}"#),
    (M13, HOST, "01 0F", r#"{"type":"stop_all_reports"}"#),
    (M13, HOST, "01 10", r#"{"type":"enable_all_reports"}"#),
    (M13, HOST, "01 11", r#"{"type":"reset_data"}"#),
    (M13, HOST, "01 12", r#"{"type":"reset_board"}"#),
    (
        M13,
        HOST,
        "06 13 10 08 FF 00 00",
        r#"{"type":"initialize_neo_pixels","pin":16,"count":8,"r":255,"g":0,"b":0}"#,
    ),
    (M13, HOST, "01 14", r#"{"type":"show_neo_pixels"}"#),
    (
        M13,
        HOST,
        "06 15 03 00 FF 00 01",
        r#"{"type":"set_neo_pixel","index":3,"r":0,"g":255,"b":0,"auto_show":true}"#,
    ),
    (M13, HOST, "01 16", r#"{"type":"clear_all_neo_pixels"}"#),
    (
        M13,
        HOST,
        "02 16 01",
        r#"{"type":"clear_all_neo_pixels","auto_show":true}"#,
    ),
    (
        M13,
        HOST,
        "05 17 00 00 FF 00",
        r#"{"type":"fill_neo_pixels","r":0,"g":0,"b":255,"auto_show":false}"#,
    ),
    (
        M13,
        HOST,
        "0C 18 00 10 13 12 00 0F 42 40 02 11 14",
        r#"{"type":"spi_init","port":0,"pin_a":16,"pin_b":19,"clk":18,"freq_hz":1000000,"cs_pins":[17,20]}"#,
    ),
    (
        M13,
        HOST,
        "05 19 00 02 AA BB",
        r#"{"type":"spi_write_blocking","port":0,"data":[170,187]}"#,
    ),
    (
        M13,
        HOST,
        "04 1A 00 04 FF",
        r#"{"type":"spi_read_blocking","port":0,"n":4,"tx_fill":255}"#,
    ),
    (
        M13,
        HOST,
        "05 1B 00 08 00 01",
        r#"{"type":"spi_set_format","port":0,"data_bits":8,"cpol":0,"cpha":1}"#,
    ),
    (
        M13,
        HOST,
        "03 1C 11 01",
        r#"{"type":"spi_cs_control","cs_pin":17,"level":1}"#,
    ),
    (
        M13,
        HOST,
        "02 1D 32",
        r#"{"type":"set_scan_delay","delay_ms":50}"#,
    ),
    (
        M13,
        HOST,
        "05 1E 02 0E 0F 01",
        r#"{"type":"encoder_new","kind":"quadrature","pin_a":14,"pin_b":15,"pulls":{"up":true,"down":false}}"#,
    ),
    (
        M13,
        HOST,
        "03 1F 00 02",
        r#"{"type":"sensor_new","subtype":"check","sensor_type":"mpu9250"}"#,
    ),
    (
        M13,
        HOST,
        "03 1F 00 63",
        r#"{"type":"sensor_new","subtype":"check","sensor_type":99}"#,
    ),
    (
        M13,
        HOST,
        "0A 1F 01 00 06 01 40 00 00 00 00",
        r#"{"type":"sensor_new","subtype":"add","sensor_num":0,"sensor_type":"ina226","settings":[1,64,0,0,0,0]}"#,
    ),
    (M13, HOST, "02 20 07", r#"{"type":"ping","counter":7}"#),
    (
        M13,
        HOST,
        "03 21 00 01",
        r#"{"type":"module_new","subtype":"check","module_type":"hiwonder_servo"}"#,
    ),
    (
        M13,
        HOST,
        "03 21 00 63",
        r#"{"type":"module_new","subtype":"check","module_type":99}"#,
    ),
    (
        M13,
        HOST,
        "0A 21 01 00 01 00 01 00 02 01 02",
        r#"{"type":"module_new","subtype":"add","module_num":0,"module_type":"hiwonder_servo","init":{"uart":0,"rx":1,"tx":0,"bus_ids":[1,2]}}"#,
    ),
    (
        M13,
        HOST,
        "08 21 01 01 00 00 41 00 32",
        r#"{"type":"module_new","subtype":"add","module_num":1,"module_type":"pca9685","init":{"port":0,"addr":65,"freq_hz":50}}"#,
    ),
    (
        M13,
        HOST,
        "07 21 01 02 02 05 01 0A",
        r#"{"type":"module_new","subtype":"add","module_num":2,"module_type":"shutdown_relay","init":{"pin":5,"active_level":1,"wait_s":10}}"#,
    ),
    (
        M13,
        HOST,
        "06 21 01 03 03 00 3C",
        r#"{"type":"module_new","subtype":"add","module_num":3,"module_type":"ssd1306","init":{"port":0,"addr":60}}"#,
    ),
    (
        M13,
        HOST,
        "05 21 01 03 03 00",
        r#"{"type":"module_new","subtype":"add","module_num":3,"module_type":"ssd1306","init":{"port":0}}"#,
    ),
    (
        M13,
        HOST,
        "07 22 01 03 00 00 01 2C",
        r#"{"type":"module_data","module_num":1,"data":[3,0,0,1,44]}"#,
    ),
    (M13, HOST, "01 23", r#"{"type":"get_id"}"#),
    (M13, HOST, "02 24 05", r#"{"type":"set_id","id":5}"#),
    (
        M13,
        HOST,
        "02 25 05",
        r#"{"type":"feature_request","msg_type":5}"#,
    ),
    (M13, HOST, "01 26", r#"{"type":"bootloader_reset"}"#),
    (
        M12,
        HOST,
        "03 04 02 05",
        r#"{"type":"modify_reporting","action":"enable_digital","pin":5}"#,
    ),
    (
        M12,
        HOST,
        "03 04 04 05",
        r#"{"type":"modify_reporting","action":"disable_digital","pin":5}"#,
    ),
    (
        M12,
        HOST,
        "04 1E 01 0E 00",
        r#"{"type":"encoder_new","kind":"single","pin_a":14,"pin_b":0}"#,
    ),
    (
        U11,
        HOST,
        "06 0B 00 68 75 01 00",
        r#"{"type":"i2c_read","port":0,"addr":104,"reg":117,"n":1,"no_stop":0}"#,
    ),
    (
        U11,
        HOST,
        "07 0C 00 3C 02 00 00 AF",
        r#"{"type":"i2c_write","port":0,"addr":60,"no_stop":0,"data":[0,175]}"#,
    ),
    (
        M13,
        PICO,
        "02 00 41",
        r#"{"type":"serial_loop_back_report","byte":65}"#,
    ),
    (
        M13,
        PICO,
        "03 02 0A 01",
        r#"{"type":"digital_report","pin":10,"value":1}"#,
    ),
    (
        M13,
        PICO,
        "04 03 1A 08 00",
        r#"{"type":"analog_report","pin":26,"value":2048}"#,
    ),
    (
        M13,
        PICO,
        "03 05 01 03",
        r#"{"type":"firmware_version","major":1,"minor":3}"#,
    ),
    (
        M13,
        PICO,
        "09 06 b0 b1 b2 b3 b4 b5 00 00",
        r#"{"type":"pico_unique_id","id":[176,177,178,179,180,181,0,0]}"#,
    ),
    (
        M13,
        PICO,
        "04 08 00 07 02",
        r#"{"type":"i2c_write_report","port":0,"msg_id":7,"result":2}"#,
    ),
    (
        M13,
        PICO,
        "04 08 00 07 FE",
        r#"{"type":"i2c_write_report","port":0,"msg_id":7,"result":-2}"#,
    ),
    (
        M13,
        PICO,
        "04 09 00 3C 00",
        r#"{"type":"i2c_read_failed","port":0,"addr":60,"stale":0}"#,
    ),
    (
        M13,
        PICO,
        "08 0A 00 03 75 02 00 AA BB",
        r#"{"type":"i2c_read_report","port":0,"msg_id":3,"reg":117,"data":[170,187]}"#,
    ),
    (
        M13,
        PICO,
        "05 0B 09 0A 00 64",
        r#"{"type":"sonar_distance","trig":9,"echo":10,"cm":100}"#,
    ),
    (
        M13,
        PICO,
        "05 0B 09 0A FF FC",
        r#"{"type":"sonar_distance","trig":9,"echo":10,"cm":"no_echo"}"#,
    ),
    (
        M13,
        PICO,
        "05 0B 09 0A FF FD",
        r#"{"type":"sonar_distance","trig":9,"echo":10,"cm":"out_of_range"}"#,
    ),
    (
        M13,
        PICO,
        "05 0B 09 0A FF FE",
        r#"{"type":"sonar_distance","trig":9,"echo":10,"cm":"stale"}"#,
    ),
    (
        M13,
        PICO,
        "04 0B 09 00 64",
        r#"{"type":"sonar_distance","trig":9,"cm":100}"#,
    ),
    (
        M13,
        PICO,
        "06 0C 04 37 05 17 02",
        r#"{"type":"dht_report","pin":4,"hum_int":55,"hum_hundredths":5,"temp_int":23,"temp_hundredths":2}"#,
    ),
    (
        M13,
        PICO,
        "06 0C 04 37 05 FE FB",
        r#"{"type":"dht_report","pin":4,"hum_int":55,"hum_hundredths":5,"temp_int":-2,"temp_hundredths":-5}"#,
    ),
    (
        M13,
        PICO,
        "05 0D 00 02 AA BB",
        r#"{"type":"spi_report","port":0,"data":[170,187]}"#,
    ),
    (
        M13,
        PICO,
        "03 0E 0E FD",
        r#"{"type":"encoder_report","pin_a":14,"steps":-3}"#,
    ),
    (
        M13,
        PICO,
        "0B 14 00 06 00 00 48 41 00 00 80 3E",
        r#"{"type":"sensor_report","sensor_num":0,"sensor_type":"ina226","reading":{"volts":12.5,"amps":0.25}}"#,
    ),
    (
        M13,
        PICO,
        "0B 14 00 06 00 00 80 7F 00 00 C0 7F",
        r#"{"type":"sensor_report","sensor_num":0,"sensor_type":"ina226","reading":{"volts":"inf","amps":"nan:0x7fc00000"}}"#,
    ),
    (
        M13,
        PICO,
        "05 14 01 03 01 9A",
        r#"{"type":"sensor_report","sensor_num":1,"sensor_type":"vl53l0x","reading":{"mm":410}}"#,
    ),
    (
        M13,
        PICO,
        "07 14 00 01 FF FF FF 9C",
        r#"{"type":"sensor_report","sensor_num":0,"sensor_type":"hx711","reading":{"raw":-100}}"#,
    ),
    (
        M13,
        PICO,
        "07 14 02 08 00 10 0F FF",
        r#"{"type":"sensor_report","sensor_num":2,"sensor_type":"as5600","reading":{"angles":[16,4095]}}"#,
    ),
    (
        M13,
        PICO,
        "11 14 03 09 00 01 00 02 00 03 FF FF FF FE FF FD 00 64",
        r#"{"type":"sensor_report","sensor_num":3,"sensor_type":"mpu6050","reading":{"accel":[1,2,3],"gyro":[-1,-2,-3],"temp":100}}"#,
    ),
    (
        M13,
        PICO,
        "0B 14 04 04 00 01 00 02 00 03 00 04",
        r#"{"type":"sensor_report","sensor_num":4,"sensor_type":"veml6040","reading":{"r":1,"g":2,"b":3,"w":4}}"#,
    ),
    (
        M13,
        PICO,
        "0F 14 05 07 00 00 80 3F 00 00 00 BF CD CC CC 3D",
        r#"{"type":"sensor_report","sensor_num":5,"sensor_type":"hmc5883l","reading":{"field":[1.0,-0.5,0.1]}}"#,
    ),
    (
        M13,
        PICO,
        "09 14 06 05 00 01 FF FF 00 00",
        r#"{"type":"sensor_report","sensor_num":6,"sensor_type":"adxl345","reading":{"accel":[1,-1,0]}}"#,
    ),
    (
        M13,
        PICO,
        "04 15 00 02 01",
        r#"{"type":"sensor_main_report","sensor_type":"mpu9250","supported":true}"#,
    ),
    (
        M13,
        PICO,
        "04 15 00 63 00",
        r#"{"type":"sensor_main_report","sensor_type":99,"supported":false}"#,
    ),
    (
        M13,
        PICO,
        "03 20 07 2A",
        r#"{"type":"pong","counter":7,"boot_id":42}"#,
    ),
    (
        M13,
        PICO,
        "04 21 00 01 01",
        r#"{"type":"module_main_report","module_type":"hiwonder_servo","supported":true}"#,
    ),
    (
        M13,
        PICO,
        "04 21 00 63 00",
        r#"{"type":"module_main_report","module_type":99,"supported":false}"#,
    ),
    (
        M13,
        PICO,
        "07 22 00 01 00 00 2E E0",
        r#"{"type":"module_report","module_num":0,"module_type":"hiwonder_servo","message":{"subtype":"positions","positions":[{"idx":0,"centideg":12000}]}}"#,
    ),
    (
        M13,
        PICO,
        "06 22 00 01 04 05 01",
        r#"{"type":"module_report","module_num":0,"module_type":"hiwonder_servo","message":{"subtype":"id_verify","bus_id":5,"ok":true}}"#,
    ),
    (
        M13,
        PICO,
        "09 22 00 01 06 00 00 64 5D C0",
        r#"{"type":"module_report","module_num":0,"module_type":"hiwonder_servo","message":{"subtype":"range","idx":0,"min_cdeg":100,"max_cdeg":24000}}"#,
    ),
    (
        M13,
        PICO,
        "07 22 00 01 08 00 FF 9C",
        r#"{"type":"module_report","module_num":0,"module_type":"hiwonder_servo","message":{"subtype":"offset","idx":0,"offset_cdeg":-100}}"#,
    ),
    (
        M13,
        PICO,
        "06 22 00 01 0B 05 00",
        r#"{"type":"module_report","module_num":0,"module_type":"hiwonder_servo","message":{"subtype":"added","bus_id":5,"idx":0}}"#,
    ),
    (
        M13,
        PICO,
        "07 22 01 03 01 05 00 01",
        r#"{"type":"module_report","module_num":1,"module_type":"ssd1306","message":{"subtype":"text_done","len":5,"display_x":0,"enabled":true}}"#,
    ),
    (
        M13,
        PICO,
        "07 22 01 03 03 01 00 00",
        r#"{"type":"module_report","module_num":1,"module_type":"ssd1306","message":{"subtype":"binary_done","len":1,"display_x":0,"enabled":false}}"#,
    ),
    (
        M13,
        PICO,
        "05 22 01 03 02 FE",
        r#"{"type":"module_report","module_num":1,"module_type":"ssd1306","message":{"subtype":"disabled","request_sub":2}}"#,
    ),
    (M13, PICO, "02 23 05", r#"{"type":"get_id_report","id":5}"#),
    (M13, PICO, "02 24 05", r#"{"type":"set_id_report","id":5}"#),
    (
        M13,
        PICO,
        "05 25 05 01 01 03",
        r#"{"type":"feature_check","msg_type":5,"ok":true,"extras":[1,3]}"#,
    ),
    (
        M13,
        PICO,
        "03 25 32 00",
        r#"{"type":"feature_check","msg_type":50,"ok":false,"extras":[]}"#,
    ),
    (
        M13,
        PICO,
        "04 63 1E 00 01",
        r#"{"type":"debug_print","id":30,"value":1}"#,
    ),
    (
        M12,
        PICO,
        "04 0B 09 01 17",
        r#"{"type":"sonar_distance","trig":9,"m":1,"cm":23}"#,
    ),
    (
        M12,
        PICO,
        "04 08 00 07 02",
        r#"{"type":"i2c_write_report","port":0,"msg_id":7,"result":2}"#,
    ),
    (
        U11,
        PICO,
        "04 08 00 3C 00",
        r#"{"type":"i2c_write_failed","port":0,"addr":60,"stale":0}"#,
    ),
    (
        U11,
        PICO,
        "07 0A 00 68 75 02 AA BB",
        r#"{"type":"i2c_read_report","port":0,"addr":104,"reg":117,"data":[170,187]}"#,
    ),
    (
        U11,
        PICO,
        "04 0B 09 17 32",
        r#"{"type":"sonar_distance","trig":9,"cm":23,"hundredths":50}"#,
    ),
    (
        M13,
        PICO,
        "04 28 01 02 03",
        r#"{"type":"unknown_report","id":40,"payload":[1,2,3]}"#,
    ),
];

fn hex(text: &str) -> Vec<u8> {
    text.split_whitespace()
        .map(|b| u8::from_str_radix(b, 16).unwrap())
        .collect()
}

fn read_in(line: &str, dialect: Dialect) -> Result<MessageBuf, String> {
    let mut json = serde_json::Deserializer::from_str(line);
    MessageBuf::deserialize_in(&mut json, dialect).map_err(|e| without_position(&e))
}

/// A `serde_json` error's message without its ` at line 1 column N`.
fn without_position(error: &serde_json::Error) -> String {
    let text = error.to_string();
    match text.rfind(" at line ") {
        Some(at) => text[..at].to_owned(),
        None => text,
    }
}

#[test]
fn every_kind_serializes_as_the_tool_line_and_reads_back() {
    for &(dialect, host, frame, line) in CASES {
        let frame = hex(frame);
        let lenient = line.contains("unknown_report");
        let json = if host {
            let command = Command::parse_in(&frame, dialect).unwrap();
            let owned = CommandBuf::parse_in(&frame, dialect).unwrap();
            assert_eq!(serde_json::to_string(&owned).unwrap(), line);
            assert_eq!(
                serde_json::to_string(&MessageBuf::from(owned)).unwrap(),
                line
            );
            serde_json::to_string(&command).unwrap()
        } else {
            let report = if lenient {
                Report::parse_lenient_in(&frame, dialect).unwrap()
            } else {
                Report::parse_in(&frame, dialect).unwrap()
            };
            let owned = ReportBuf::parse_in(&frame, dialect, lenient).unwrap();
            assert_eq!(serde_json::to_string(&owned).unwrap(), line);
            assert_eq!(
                serde_json::to_string(&MessageBuf::from(owned)).unwrap(),
                line
            );
            serde_json::to_string(&report).unwrap()
        };
        assert_eq!(json, line, "{frame:02x?} in {dialect}");
        // And back, to the same frame and message.
        let back = read_in(line, dialect).unwrap_or_else(|e| panic!("{line}: {e}"));
        assert_eq!(back.frame(), &frame[..], "{line}");
        assert_eq!(back.is_command(), host, "{line}");
        // offset and len are ignored.
        let framed = line.replacen('{', r#"{"offset":12,"len":3,"#, 1);
        assert_eq!(read_in(&framed, dialect).unwrap().frame(), &frame[..]);
        if dialect == M13 {
            let direct: MessageBuf = serde_json::from_str(line).unwrap();
            assert_eq!(direct.frame(), &frame[..]);
            if host {
                let command: CommandBuf = serde_json::from_str(line).unwrap();
                assert_eq!(command.frame(), &frame[..]);
                assert!(serde_json::from_str::<ReportBuf>(line).is_err());
            } else {
                let report: ReportBuf = serde_json::from_str(line).unwrap();
                assert_eq!(report.frame(), &frame[..]);
            }
        }
    }
}

#[test]
fn the_cases_cover_every_type() {
    for name in Command::NAMES.iter().chain(Report::NAMES) {
        let tag = format!(r#"{{"type":"{name}""#);
        assert!(
            CASES.iter().any(|(_, _, _, line)| line.starts_with(&tag)),
            "no case for {name}"
        );
    }
}

#[test]
fn module_data_is_typed_in_a_capture() {
    let bytes = hex("0A 21 01 00 01 00 01 00 02 01 02 09 22 00 01 01 00 2E E0 01 F4");
    let lines = capture_lines(&bytes);
    let typed = r#"{"type":"module_data","module_num":0,"module_type":"hiwonder_servo","message":{"subtype":"set_angle","moves":[{"idx":0,"centideg":12000,"time_ms":500}]}}"#;
    assert_eq!(lines[1], typed);
    let back: MessageBuf = serde_json::from_str(typed).unwrap();
    assert_eq!(back.frame(), &bytes[11..]);
}

/// The lines of a capture of commands, each annotated by what came before.
/// Each message rebuilt from its frame and attribution gives the same line.
fn capture_lines(bytes: &[u8]) -> Vec<String> {
    let mut decoder = device_decoder();
    let mut context = CaptureContext::new(decoder.framing());
    decoder
        .feed(bytes)
        .map(|event| {
            let mut message = MessageBuf::from(event.unwrap().message);
            context.annotate(&mut message);
            let line = serde_json::to_string(&message).unwrap();
            assert_eq!(serde_json::to_string(&rebuilt(&message)).unwrap(), line);
            line
        })
        .collect()
}

/// `message` again from its frame and its attribution alone.
fn rebuilt(message: &MessageBuf) -> MessageBuf {
    let again = MessageBuf::from_attribution(message.frame(), message.attribution()).unwrap();
    assert_eq!(again.attribution(), message.attribution());
    assert_eq!(again.frame(), message.frame());
    again
}

#[test]
fn a_message_rebuilt_from_its_attribution_reads_the_same() {
    for &(dialect, host, frame, line) in CASES {
        let message = read_in(line, dialect).unwrap();
        let again = rebuilt(&message);
        assert_eq!(again.is_command(), host, "{frame}");
        assert_eq!(again.dialect(), dialect, "{frame}");
        assert_eq!(again.to_string(), message.to_string(), "{frame}");
        assert_eq!(serde_json::to_string(&again).unwrap(), line, "{frame}");
    }
    // Valid both ways: `also` is kept.
    let mut context = CaptureContext::new(both_decoder().framing());
    let mut message = MessageBuf::try_from(&hex("03 02 19 01")[..]).unwrap();
    context.annotate(&mut message);
    assert!(rebuilt(&message).also().is_some());
    // Not one whole frame: refused.
    let attribution = message.attribution();
    for cut in [
        &[][..],
        &[0x03, 0x02, 0x19],
        &[0x03, 0x02, 0x19, 0x01, 0x00],
    ] {
        assert!(
            MessageBuf::from_attribution(cut, attribution).is_err(),
            "{cut:?}"
        );
    }
}

/// Every subtype of the module data tables (Hiwonder servo, SSD1306): the
/// tool's `message` object for its data, typed in a capture.
const MODULE_DATA_CASES: &[(&str, &str)] = &[
    (
        "hiwonder_servo",
        r#"{"subtype":"set_angle","moves":[{"idx":0,"centideg":12000,"time_ms":500},{"idx":1,"centideg":0,"time_ms":0}]}"#,
    ),
    (
        "hiwonder_servo",
        r#"{"subtype":"enable","enabled":true,"servos":[0,2]}"#,
    ),
    (
        "hiwonder_servo",
        r#"{"subtype":"enable","enabled":false,"servos":[]}"#,
    ),
    ("hiwonder_servo", r#"{"subtype":"id_write","new_id":7}"#),
    ("hiwonder_servo", r#"{"subtype":"id_verify","bus_id":254}"#),
    (
        "hiwonder_servo",
        r#"{"subtype":"range_write","idx":1,"min_cdeg":0,"max_cdeg":24000}"#,
    ),
    ("hiwonder_servo", r#"{"subtype":"range_read","idx":3}"#),
    (
        "hiwonder_servo",
        r#"{"subtype":"offset_write","idx":0,"offset_cdeg":-125}"#,
    ),
    ("hiwonder_servo", r#"{"subtype":"offset_read","idx":0}"#),
    (
        "hiwonder_servo",
        r#"{"subtype":"voltage_limit_write","idx":2,"min_mv":4500,"max_mv":14000}"#,
    ),
    (
        "hiwonder_servo",
        r#"{"subtype":"motor_mode_write","idx":2,"speed":-1000}"#,
    ),
    ("hiwonder_servo", r#"{"subtype":"add_servo","bus_id":9}"#),
    ("ssd1306", r#"{"subtype":"text","text":"Hé"}"#),
    ("ssd1306", r#"{"subtype":"text_done"}"#),
    (
        "ssd1306",
        r#"{"subtype":"binary","chunk":63,"data":[0,1,2,3,4,5,6,7,8,9,10,11,12,13,14,255]}"#,
    ),
    ("ssd1306", r#"{"subtype":"binary_done"}"#),
];

#[test]
fn every_module_data_subtype_has_its_json() {
    let modules = [
        r#"{"type":"module_new","subtype":"add","module_num":0,"module_type":"hiwonder_servo","init":{"uart":0,"rx":1,"tx":0,"bus_ids":[1,2]}}"#,
        r#"{"type":"module_new","subtype":"add","module_num":1,"module_type":"ssd1306","init":{"port":0,"addr":60}}"#,
    ];
    for (module_type, message) in MODULE_DATA_CASES {
        let num = u8::from(*module_type == "ssd1306");
        let line = format!(
            r#"{{"type":"module_data","module_num":{num},"module_type":"{module_type}","message":{message}}}"#
        );
        // The line reads back to a frame, ...
        let frame = read_in(&line, M13).unwrap_or_else(|e| panic!("{line}: {e}"));
        // ... which a capture that saw the module created prints as the line.
        let mut bytes: Vec<u8> = Vec::new();
        for module in modules {
            bytes.extend_from_slice(read_in(module, M13).unwrap().frame());
        }
        bytes.extend_from_slice(frame.frame());
        let lines = capture_lines(&bytes);
        assert_eq!(lines.len(), 3, "{line}");
        assert_eq!(lines[2], line);
    }
    // An out-of-range field is refused when the line is encoded.
    for (message, error) in [
        (
            r#"{"subtype":"range_write","idx":1,"min_cdeg":24001,"max_cdeg":0}"#,
            "min_cdeg",
        ),
        (
            r#"{"subtype":"binary","chunk":64,"data":[0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0]}"#,
            "chunk",
        ),
        (r#"{"subtype":"swing"}"#, "subtype"),
    ] {
        let module_type = if message.contains("binary") {
            "ssd1306"
        } else {
            "hiwonder_servo"
        };
        let line = format!(
            r#"{{"type":"module_data","module_num":0,"module_type":"{module_type}","message":{message}}}"#
        );
        let refused = read_in(&line, M13).expect_err(&line);
        assert!(refused.contains(error), "{line}: {refused}");
    }
}

#[test]
fn a_frame_valid_both_ways_names_the_other_reading() {
    let mut context = CaptureContext::new(both_decoder().framing());
    let mut message = MessageBuf::try_from(&hex("03 02 19 01")[..]).unwrap();
    context.annotate(&mut message);
    let line = r#"{"type":"digital_report","also":"digital_write","pin":25,"value":1}"#;
    assert_eq!(serde_json::to_string(&message).unwrap(), line);
    assert_eq!(
        message.to_string(),
        "digital_report also=digital_write pin=25 value=1"
    );
    assert_eq!(read_in(line, M13).unwrap().frame(), &hex("03 02 19 01")[..]);
}

/// The bad lines of tests/cli_telemetrix.rs that are about the schema (not
/// about JSON itself), with the tool's messages.
const BAD_LINES: &[(Dialect, &str, &str)] = &[
    (M13, r#"[1,2]"#, "expected a JSON object, found [1,2]"),
    (M13, r#"{"counter":3}"#, "missing field `type`"),
    (M13, r#"{"type":"pling"}"#, "unknown type `pling` (did you mean `ping`?)"),
    (M13, r#"{"type":"ping"}"#, "missing field `counter`"),
    (
        M13,
        r#"{"type":"ping","counter":256}"#,
        "field `counter` must be an integer 0..=255, found 256",
    ),
    (
        M13,
        r#"{"type":"ping","counter":1,"boot_id":2}"#,
        "unknown field `boot_id` for type ping",
    ),
    (
        M13,
        r#"{"type":"digital_write","pin":30,"value":1}"#,
        "field `pin` must be an integer 0..=29, found 30",
    ),
    (
        M13,
        r#"{"type":"i2c_read","port":2,"addr":104,"msg_id":3,"reg":117,"n":1,"no_stop":0}"#,
        "field `port` must be an integer 0..=1, found 2",
    ),
    (
        M13,
        r#"{"type":"i2c_read","port":0,"addr":128,"msg_id":3,"reg":117,"n":1,"no_stop":0}"#,
        "field `addr` must be an integer 0..=127, found 128",
    ),
    (
        M13,
        r#"{"type":"i2c_read","port":0,"addr":104,"msg_id":3,"reg":117,"n":58,"no_stop":0}"#,
        "field `n` must be an integer 1..=57, found 58 (a frame a real peer sends, which decode \
         marks \"quirk\":\"past_firmware_buffer\": add that to the line to encode it anyway)",
    ),
    (
        M13,
        r#"{"type":"set_pin_mode","pin":25,"mode":"analog_input","differential":1,"report_enable":true}"#,
        "field `pin` must be an integer 26..=30, found 25",
    ),
    (
        Dialect::Mirte12,
        r#"{"type":"modify_reporting","action":"enable_analog","pin":26}"#,
        "field `pin` must be an integer 0..=4, found 26 (a frame a real peer sends, which \
         decode marks \"quirk\":\"analog_reporting_pin_not_adc\": add that to the line to \
         encode it anyway)",
    ),
    (
        Dialect::Mirte12,
        r#"{"type":"modify_reporting","action":"enable_analog","pin":3,"quirk":"analog_reporting_pin_not_adc"}"#,
        "the line says \"quirk\":\"analog_reporting_pin_not_adc\", but its frame for mirte12 has \
         no quirk: leave `quirk` out",
    ),
    (
        M13,
        r#"{"type":"digital_write","pin":5,"value":1,"quirk":"level_not_binary"}"#,
        "the line says \"quirk\":\"level_not_binary\", but its frame for mirte13 has no quirk: \
         leave `quirk` out",
    ),
    (
        M13,
        r#"{"type":"ping","counter":1,"quirk":"odd"}"#,
        "field `quirk` must be one of digital_reporting_pin_minus_26, level_not_binary, \
         pwm_trailing_bytes, encoder_type_not_1_or_2, echoed_request_byte, \
         analog_reporting_pin_not_adc, ignored_by_firmware, past_firmware_buffer, \
         spi_data_bits_out_of_range, found \"odd\"",
    ),
    (
        M13,
        r#"{"type":"sonar_new","trig":9,"echo":40}"#,
        "field `echo` must be an integer 0..=29, found 40",
    ),
    (
        M13,
        r#"{"type":"digital_report","pin":40,"value":1}"#,
        "field `pin` must be an integer 0..=29, found 40",
    ),
    (
        M13,
        r#"{"type":"analog_report","pin":26,"value":4096}"#,
        "field `value` must be an integer 0..=4095, found 4096",
    ),
    (
        M13,
        r#"{"type":"i2c_write_report","port":2,"msg_id":7,"result":2}"#,
        "field `port` must be an integer 0..=1, found 2",
    ),
    (
        M13,
        r#"{"type":"digital_write","pin":3,"value":true}"#,
        "field `value` must be an integer 0..=1, found true",
    ),
    (
        M13,
        r#"{"type":"set_pin_mode","pin":3,"mode":"digital_input_pull_up","report_enable":1}"#,
        "field `report_enable` must be true or false, found 1",
    ),
    (
        M13,
        r#"{"type":"set_pin_mode","pin":3,"mode":"input"}"#,
        "field `mode` must be one of digital_input, digital_input_pull_up, digital_input_pull_down, digital_output, pwm_output, analog_input, found \"input\"",
    ),
    (
        M13,
        r#"{"type":"pwm_write","pins":[{"pin":3,"value":70000}]}"#,
        "in `pins[0]`: field `value` must be an integer 0..=65535, found 70000",
    ),
    (
        M13,
        r#"{"type":"pwm_write","pins":[{"pin":3,"value":7,"duty":1}]}"#,
        "unknown field `duty` in `pins[0]`",
    ),
    (
        M13,
        r#"{"type":"i2c_write","port":0,"addr":60,"msg_id":1,"no_stop":0,"data":[1,2,300]}"#,
        "field `data[2]` must be an integer 0..=255, found 300",
    ),
    (
        M13,
        r#"{"type":"i2c_write","port":0,"addr":60,"msg_id":1,"no_stop":0,"data":[]}"#,
        "cannot encode i2c_write for mirte13: fields do not match the message's layout: \
         the payload length does not fit the message's layout",
    ),
    (
        M13,
        r#"{"type":"encoder_new","kind":"quadrature","pin_a":14,"pin_b":15}"#,
        "missing field `pulls`",
    ),
    (
        M13,
        r#"{"type":"encoder_new","kind":"quadrature","pin_a":14,"pin_b":15,"pulls":{"up":true}}"#,
        "in `pulls`: missing field `down`",
    ),
    (
        M13,
        r#"{"type":"sensor_new","subtype":"add","sensor_num":0,"sensor_type":"bmp280","settings":[0,0,0,0,0,0]}"#,
        "field `sensor_type` must be one of gps, hx711, mpu9250, vl53l0x, veml6040, adxl345, ina226, hmc5883l, as5600, mpu6050, bno055 or a number 0..=255, found \"bmp280\"",
    ),
    (
        M13,
        r#"{"type":"encoder_report","pin_a":14,"steps":0}"#,
        "field `steps` must not be 0: the firmware reports an encoder only when it moved \
         (-128..=-1 or 1..=127)",
    ),
    (
        M13,
        r#"{"type":"sonar_distance","trig":9,"echo":10,"cm":"far"}"#,
        "field `cm` must be an integer or \"no_echo\", \"out_of_range\" or \"stale\", found \"far\"",
    ),
    (
        M13,
        r#"{"type":"sonar_distance","trig":9,"echo":10,"cm":2000}"#,
        "cannot encode sonar_distance for mirte13: cm is out of range",
    ),
    (
        M13,
        r#"{"type":"module_report","module_num":1,"module_type":"pca9685","message":{}}"#,
        "in `message`: module type pca9685 sends no reports",
    ),
    (
        M13,
        r#"{"type":"module_data","module_num":0,"module_type":"hiwonder_servo","message":{"subtype":"set_angle","moves":[{"idx":0,"centideg":30000,"time_ms":5}]}}"#,
        "in `message`: centideg is out of range",
    ),
    (
        M13,
        r#"{"type":"digital_report","also":"mystery","pin":1,"value":0}"#,
        "field `also` must name a command or report type, found \"mystery\"",
    ),
    (
        M13,
        r#"{"type":"get_id","offset":3,"len":2,"also":"get_id_report","id":1}"#,
        "unknown field `id` for type get_id",
    ),
    (
        U11,
        r#"{"type":"i2c_read","port":0,"addr":104,"msg_id":3,"reg":117,"n":1,"no_stop":0}"#,
        "unknown field `msg_id` for type i2c_read",
    ),
    (
        U11,
        r#"{"type":"ping","counter":1}"#,
        "cannot encode ping for upstream11: fields do not match the message's layout: \
         the command does not exist in this dialect",
    ),
    (
        M12,
        r#"{"type":"encoder_new","kind":"single","pin_a":14,"pin_b":0,"pulls":{"up":false,"down":false}}"#,
        "unknown field `pulls` for type encoder_new",
    ),
    (
        M13,
        r#"{"type":"i2c_read","port":0,"addr":104,"reg":117,"n":1,"no_stop":0}"#,
        "missing field `msg_id`",
    ),
];

#[test]
fn bad_lines_give_the_tool_messages() {
    for &(dialect, line, message) in BAD_LINES {
        assert_eq!(read_in(line, dialect).unwrap_err(), message, "{line}");
        if dialect == M13 {
            let error = serde_json::from_str::<MessageBuf>(line).unwrap_err();
            assert_eq!(without_position(&error), message, "{line}");
        }
    }
    // A float that does not fit an f32 is refused with its value.
    let line = r#"{"type":"sensor_report","sensor_num":0,"sensor_type":"ina226","reading":{"volts":1e39,"amps":0}}"#;
    let error = read_in(line, M13).unwrap_err();
    assert!(
        error.starts_with("in `reading`: field `volts` 1e")
            && error.ends_with("does not fit in an f32 (write \"inf\" for infinity)"),
        "{error}"
    );
}

#[test]
fn digital_levels_also_read_high_for_one_release() {
    for (line, frame) in [
        (
            r#"{"type":"digital_write","pin":3,"high":true}"#,
            "03 02 03 01",
        ),
        (
            r#"{"type":"digital_write","pin":3,"high":0}"#,
            "03 02 03 00",
        ),
        (
            r#"{"type":"digital_report","pin":3,"high":false}"#,
            "03 02 03 00",
        ),
    ] {
        assert_eq!(
            read_in(line, M13).unwrap().frame(),
            &hex(frame)[..],
            "{line}"
        );
    }
    assert_eq!(
        read_in(r#"{"type":"digital_write","pin":3,"high":2}"#, M13).unwrap_err(),
        "field `high` must be true, false, 0 or 1, found 2"
    );
}

#[test]
fn display_is_one_line_of_the_schema_words() {
    assert_eq!(Command::Ping { counter: 7 }.to_string(), "ping counter=7");
    let pwm = CommandBuf::try_from(&hex("07 03 0F 05 DC 10 05 DC")[..]).unwrap();
    assert_eq!(
        pwm.to_string(),
        "pwm_write pins=[{pin=15 value=1500},{pin=16 value=1500}]"
    );
    let pong = Report::Pong {
        counter: 7,
        boot_id: 42,
    };
    assert_eq!(pong.to_string(), "pong counter=7 boot_id=42");
}

#[test]
fn names_parse_and_display() {
    for dialect in Dialect::ALL {
        assert_eq!(dialect.to_string().parse::<Dialect>(), Ok(dialect));
        let json = serde_json::to_string(&dialect).unwrap();
        assert_eq!(json, format!("\"{dialect}\""));
        assert_eq!(serde_json::from_str::<Dialect>(&json).unwrap(), dialect);
    }
    assert_eq!("mirte13".parse::<Dialect>(), Ok(M13));
    let error = "mirte14".parse::<Dialect>().unwrap_err();
    assert_eq!(
        error.to_string(),
        "unknown dialect name; expected one of mirte13, mirte12, upstream11"
    );
    use robowire::telemetrix::{EncoderKind, ModuleType, SensorType};
    for t in SensorType::ALL {
        assert_eq!(t.to_string().parse::<SensorType>(), Ok(t));
    }
    for t in ModuleType::ALL {
        assert_eq!(t.to_string().parse::<ModuleType>(), Ok(t));
    }
    assert_eq!(
        "quadrature".parse::<EncoderKind>(),
        Ok(EncoderKind::Quadrature)
    );
    assert!("bmp280".parse::<SensorType>().is_err());
}

type Value = serde_json::Value;

#[test]
fn deserialize_needs_an_owned_form() {
    // The borrowed messages serialize only; an owned form deserializes from
    // any self-describing format, here a JSON value.
    let value: Value = serde_json::from_str(r#"{"type":"ping","counter":7}"#).unwrap();
    let owned = CommandBuf::deserialize(&value).unwrap();
    assert_eq!(owned, Command::Ping { counter: 7 });
}
