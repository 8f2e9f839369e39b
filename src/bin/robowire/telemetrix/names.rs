//! The names the JSON schema gives to message types, sensor and module types
//! and enumerated fields: snake case after the spec's names.

use robowire::telemetrix::{Command, Dialect, ModuleType, PinMode, Pull, Report, SensorType};

/// Every command `type`, in id order (ids 0..=38).
pub const COMMAND_TYPES: [&str; 39] = [
    "serial_loop_back",
    "set_pin_mode",
    "digital_write",
    "pwm_write",
    "modify_reporting",
    "get_firmware_version",
    "get_pico_unique_id",
    "servo_attach",
    "servo_write",
    "servo_detach",
    "i2c_begin",
    "i2c_read",
    "i2c_write",
    "sonar_new",
    "dht_new",
    "stop_all_reports",
    "enable_all_reports",
    "reset_data",
    "reset_board",
    "initialize_neo_pixels",
    "show_neo_pixels",
    "set_neo_pixel",
    "clear_all_neo_pixels",
    "fill_neo_pixels",
    "spi_init",
    "spi_write_blocking",
    "spi_read_blocking",
    "spi_set_format",
    "spi_cs_control",
    "set_scan_delay",
    "encoder_new",
    "sensor_new",
    "ping",
    "module_new",
    "module_data",
    "get_id",
    "set_id",
    // The report with id 37 is `feature_check`; the command takes the
    // reference page's name so that every `type` names one direction.
    "feature_request",
    "bootloader_reset",
];

/// The `type` of a command.
pub fn command_type<B>(command: &Command<B>) -> &'static str {
    COMMAND_TYPES[usize::from(command.id())]
}

/// The `type` of a report.
pub fn report_type<B>(report: &Report<B>) -> &'static str {
    match report {
        Report::LoopBack { .. } => "serial_loop_back_report",
        Report::Digital { .. } => "digital_report",
        Report::Analog { .. } => "analog_report",
        Report::FirmwareVersion { .. } => "firmware_version",
        Report::UniqueId { .. } => "pico_unique_id",
        Report::I2cWrite { .. } => "i2c_write_report",
        Report::I2cWriteFailed { .. } => "i2c_write_failed",
        Report::I2cReadFailed { .. } => "i2c_read_failed",
        Report::I2cRead { .. } | Report::I2cReadUpstream { .. } => "i2c_read_report",
        Report::Sonar(_) => "sonar_distance",
        Report::Dht { .. } => "dht_report",
        Report::Spi { .. } => "spi_report",
        Report::Encoder { .. } => "encoder_report",
        Report::Sensor { .. } => "sensor_report",
        Report::SensorSupported { .. } => "sensor_main_report",
        Report::Pong { .. } => "pong",
        Report::ModuleSupported { .. } => "module_main_report",
        Report::Module { .. } => "module_report",
        Report::Id { .. } => "get_id_report",
        Report::IdSet { .. } => "set_id_report",
        Report::Feature { .. } => "feature_check",
        Report::Debug { .. } => "debug_print",
        Report::Unknown { .. } => "unknown_report",
    }
}

/// Every report `type`.
pub const REPORT_TYPES: [&str; 22] = [
    "serial_loop_back_report",
    "digital_report",
    "analog_report",
    "firmware_version",
    "pico_unique_id",
    "i2c_write_report",
    "i2c_write_failed",
    "i2c_read_failed",
    "i2c_read_report",
    "sonar_distance",
    "dht_report",
    "spi_report",
    "encoder_report",
    "sensor_report",
    "sensor_main_report",
    "pong",
    "module_main_report",
    "module_report",
    "get_id_report",
    "set_id_report",
    "feature_check",
    "debug_print",
];

/// The name of a dialect, as `--dialect` spells it.
pub const fn dialect_name(dialect: Dialect) -> &'static str {
    match dialect {
        Dialect::Mirte13 => "mirte13",
        Dialect::Mirte12 => "mirte12",
        Dialect::Upstream11 => "upstream11",
    }
}

/// Sensor type names, in id order (0..=10).
pub const SENSOR_TYPES: [&str; 11] = [
    "gps", "hx711", "mpu9250", "vl53l0x", "veml6040", "adxl345", "ina226", "hmc5883l", "as5600",
    "mpu6050", "bno055",
];

/// The name of a sensor type.
pub fn sensor_name(sensor_type: SensorType) -> &'static str {
    SENSOR_TYPES[usize::from(sensor_type.as_u8())]
}

/// Module type names, in id order (0..=3).
pub const MODULE_TYPES: [&str; 4] = ["pca9685", "hiwonder_servo", "shutdown_relay", "ssd1306"];

/// The name of a module type.
pub fn module_name(module_type: ModuleType) -> &'static str {
    MODULE_TYPES[usize::from(module_type.as_u8())]
}

/// SET_PIN_MODE `mode` names (spec §4.1): modes 0, 3, 4, 1, 2, 5.
pub const PIN_MODES: [&str; 6] = [
    "digital_input",
    "digital_input_pull_up",
    "digital_input_pull_down",
    "digital_output",
    "pwm_output",
    "analog_input",
];

/// The `mode` name of a pin mode.
pub fn pin_mode_name(mode: &PinMode) -> &'static str {
    match mode {
        PinMode::DigitalInput {
            pull: Pull::None, ..
        } => PIN_MODES[0],
        PinMode::DigitalInput { pull: Pull::Up, .. } => PIN_MODES[1],
        PinMode::DigitalInput {
            pull: Pull::Down, ..
        } => PIN_MODES[2],
        PinMode::DigitalOutput => PIN_MODES[3],
        PinMode::PwmOutput => PIN_MODES[4],
        PinMode::AnalogInput { .. } => PIN_MODES[5],
    }
}

/// MODIFY_REPORTING `action` names (spec §4.2), by the wire's type byte.
pub const REPORTING_ACTIONS: [&str; 5] = [
    "disable_all",
    "enable_analog",
    "enable_digital",
    "disable_analog",
    "disable_digital",
];
