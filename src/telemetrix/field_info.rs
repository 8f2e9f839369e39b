//! What Telemetrix report fields mean (spec §5 to §7): units, ranges and
//! names, declared once for the tool's schemas, CSV and plots and for the
//! Python items. The message table (`table.rs`) says how each field is on
//! the wire; this says what it measures.

use super::buf::Message;
use super::module::ModuleType;
use super::quirk::Quirk;
use super::sensor::SensorType;
use crate::units::{FieldInfo, FieldTable, Unit};

const fn doc(doc: &'static str) -> FieldInfo {
    FieldInfo::new(doc)
}

/// Every Telemetrix field with a unit, a range or names to declare, the
/// reports' first: sensor readings are under `reading.`, module reports
/// under `message.`. A field every message of its kind shares (`pin`,
/// `port`) is declared once for all.
///
/// ```
/// use robowire::telemetrix::FIELD_INFO;
/// use robowire::units::Unit;
/// assert_eq!(FIELD_INFO.get("sonar_distance", "cm").unwrap().unit, Some(Unit::Centimetre));
/// assert_eq!(FIELD_INFO.get("sensor_report", "reading.volts").unwrap().unit, Some(Unit::Volt));
/// assert_eq!(FIELD_INFO.get("analog_report", "value").unwrap().range, Some((0, 4095)));
/// ```
pub static FIELD_INFO: FieldTable = FieldTable {
    protocol: "telemetrix",
    entries: &[
        ("*", "type", doc("The message type.").names(Message::NAMES)),
        (
            "*",
            "quirk",
            doc("What is unusual about the frame, that the firmware does differently.")
                .names(Quirk::NAMES)
                .optional(),
        ),
        (
            "*",
            "trailing",
            doc("Bytes after PWM_WRITE's last whole pin and value.").optional(),
        ),
        // Reports.
        (
            "serial_loop_back_report",
            "byte",
            doc("The byte echoed back."),
        ),
        ("digital_report", "pin", doc("GPIO.").entity()),
        (
            "digital_report",
            "value",
            doc("Level: 1 high, 0 low (another byte only with its quirk)."),
        ),
        (
            "analog_report",
            "pin",
            doc("GPIO 26..=30 (ADC 0..=4 in older dialects).").entity(),
        ),
        (
            "analog_report",
            "value",
            doc("12-bit reading.").unit(Unit::AdcCount).range(0, 4095),
        ),
        ("firmware_version", "major", doc("Firmware major version.")),
        ("firmware_version", "minor", doc("Firmware minor version.")),
        ("pico_unique_id", "id", doc("The board's unique id bytes.")),
        ("*", "port", doc("I2C or SPI port, 0 or 1.")),
        ("*", "addr", doc("7-bit I2C address.")),
        ("*", "msg_id", doc("The request's message id, echoed.")),
        ("*", "reg", doc("The register read.")),
        ("*", "data", doc("The bytes read.")),
        (
            "i2c_write_report",
            "result",
            doc("Bytes written, or −1 (error), −2 (timeout).").unit(Unit::Byte),
        ),
        ("*", "stale", doc("A byte without meaning.")),
        ("sonar_distance", "trig", doc("Trigger GPIO.").entity()),
        (
            "sonar_distance",
            "echo",
            doc("Echo GPIO (mirte 1.3).").optional(),
        ),
        (
            "sonar_distance",
            "cm",
            doc("Distance (echo µs / 58), or no_echo, out_of_range (over 30 ms), stale.")
                .unit(Unit::Centimetre)
                .names_or_number(&["no_echo", "out_of_range", "stale"]),
        ),
        (
            "sonar_distance",
            "m",
            doc("Whole metres (mirte 1.2 form).").optional(),
        ),
        (
            "sonar_distance",
            "hundredths",
            doc("Hundredths of a centimetre (upstream form).").optional(),
        ),
        ("dht_report", "pin", doc("GPIO.").entity()),
        (
            "dht_report",
            "hum_int",
            doc("Relative humidity, whole percent."),
        ),
        (
            "dht_report",
            "hum_hundredths",
            doc("Relative humidity, hundredths of a percent."),
        ),
        (
            "dht_report",
            "temp_int",
            doc("Temperature, whole degrees.").unit(Unit::DegreeCelsius),
        ),
        (
            "dht_report",
            "temp_hundredths",
            doc("Temperature, hundredths of a degree."),
        ),
        (
            "encoder_report",
            "pin_a",
            doc("The encoder's A GPIO.").entity(),
        ),
        (
            "encoder_report",
            "steps",
            doc("Steps since the last report.").unit(Unit::Step),
        ),
        (
            "sensor_report",
            "sensor_num",
            doc("The sensor's number, in the order of SENSOR_NEW.").entity(),
        ),
        (
            "module_report",
            "module_num",
            doc("The module's number, in the order of MODULE_NEW.").entity(),
        ),
        (
            "module_data",
            "module_num",
            doc("The module's number, in the order of MODULE_NEW.").entity(),
        ),
        (
            "*",
            "sensor_num",
            doc("The sensor's number, in the order of SENSOR_NEW."),
        ),
        (
            "*",
            "sensor_type",
            doc("The sensor's type, by name (its number if unknown).")
                .names_or_number(SensorType::NAMES),
        ),
        (
            "*",
            "module_num",
            doc("The module's number, in the order of MODULE_NEW."),
        ),
        (
            "*",
            "module_type",
            doc("The module's type, by name (its number if unknown).")
                .names_or_number(ModuleType::NAMES),
        ),
        ("*", "supported", doc("Whether the firmware supports it.")),
        ("pong", "counter", doc("The ping's counter, echoed.")),
        (
            "pong",
            "boot_id",
            doc("A number the firmware draws at boot, 0..99."),
        ),
        ("get_id_report", "id", doc("The saved id.")),
        ("set_id_report", "id", doc("The id saved.")),
        (
            "feature_check",
            "msg_type",
            doc("The command id asked about."),
        ),
        ("feature_check", "ok", doc("Whether the firmware has it.")),
        ("feature_check", "extras", doc("Bytes after the answer.")),
        ("debug_print", "id", doc("The firmware's debug message id.")),
        ("debug_print", "value", doc("Its value.")),
        // Sensor readings.
        (
            "sensor_report",
            "reading",
            doc("The reading, by the sensor's type.").by_type(),
        ),
        (
            "sensor_report",
            "reading.raw",
            doc("HX711 raw reading.").unit(Unit::AdcCount),
        ),
        (
            "sensor_report",
            "reading.mm",
            doc("VL53L0X distance.").unit(Unit::Millimetre),
        ),
        (
            "sensor_report",
            "reading.volts",
            doc("INA226 bus voltage.").unit(Unit::Volt),
        ),
        (
            "sensor_report",
            "reading.amps",
            doc("INA226 current.").unit(Unit::Ampere),
        ),
        (
            "sensor_report",
            "reading.angles",
            doc("AS5600 angles, one per mux channel, lowest first."),
        ),
        (
            "sensor_report",
            "reading.angles.*",
            doc("AS5600 angle, 4096 steps a turn.")
                .unit(Unit::Step)
                .range(0, 4095),
        ),
        (
            "sensor_report",
            "reading.temp",
            doc("Temperature (BNO055 in °C; MPU6050 raw)."),
        ),
        (
            "sensor_report",
            "reading.accel",
            doc("Acceleration x, y, z, in the driver's unit."),
        ),
        (
            "sensor_report",
            "reading.gyro",
            doc("Angular rate x, y, z, in the driver's unit."),
        ),
        (
            "sensor_report",
            "reading.mag",
            doc("Magnetic field x, y, z, in the driver's unit."),
        ),
        (
            "sensor_report",
            "reading.quat",
            doc("Orientation quaternion x, y, z, w."),
        ),
        (
            "sensor_report",
            "reading.field",
            doc("HMC5883L normalised field x, y, z."),
        ),
        ("sensor_report", "reading.r", doc("VEML6040 red.")),
        ("sensor_report", "reading.g", doc("VEML6040 green.")),
        ("sensor_report", "reading.b", doc("VEML6040 blue.")),
        ("sensor_report", "reading.w", doc("VEML6040 white.")),
        // Module reports.
        (
            "*",
            "message",
            doc("The module's message, by the module's type.").by_type(),
        ),
        (
            "module_report",
            "message.subtype",
            doc("The report's kind within its module type."),
        ),
        (
            "module_report",
            "message.positions",
            doc("Positions of the servos that changed."),
        ),
        (
            "module_report",
            "message.positions.*.idx",
            doc("Servo index."),
        ),
        (
            "module_report",
            "message.positions.*.centideg",
            doc("Servo position.").unit(Unit::Centidegree),
        ),
        (
            "module_report",
            "message.min_cdeg",
            doc("Lower limit.").unit(Unit::Centidegree),
        ),
        (
            "module_report",
            "message.max_cdeg",
            doc("Upper limit.").unit(Unit::Centidegree),
        ),
        (
            "module_report",
            "message.offset_cdeg",
            doc("Offset.").unit(Unit::Centidegree),
        ),
        (
            "module_data",
            "message.moves.*.centideg",
            doc("Servo target, 0..24000.").unit(Unit::Centidegree),
        ),
        (
            "module_data",
            "message.moves.*.time_ms",
            doc("Move time.").unit(Unit::Millisecond),
        ),
        ("*", "delay_ms", doc("Scan period.").unit(Unit::Millisecond)),
    ],
};
