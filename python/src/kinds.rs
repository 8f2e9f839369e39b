//! A class per message `type`: `robowire.telemetrix.AnalogReport`,
//! `robowire.pixy2.Blocks`, ... Each is an empty subclass of its protocol's
//! `Message`, itself an empty subclass of [`Item`](crate::item::Item), so an item reads its fields straight from
//! the frame as every `Item` does, while `isinstance` and the stubs' typed
//! fields tell the kinds apart. A class is the `type` in CamelCase
//! (`i2c_read_report` → `I2cReadReport`), in the protocol's module.
//!
//! The lists are the library's `type` names (`Message::NAMES` of each
//! protocol); a Python test checks that every name has its class. After
//! each name, the fields only some of its frames carry (a dialect's, a
//! mode's, a trailing one's); with the protocol's common ones (the receive
//! time `t`, `quirk`, Telemetrix's `also`), they read as `None` as
//! attributes when a frame lacks them, as the stubs type them `Optional`.
//! As keys they stay absent: the mapping is the frame's dict.

use pyo3::prelude::*;
use pyo3::sync::PyOnceLock;
use pyo3::types::{PyString, PyType};

use crate::item::Item;
use crate::typed::untracked_init;

/// The classes of one protocol: a zero-sized `#[pyclass]` per `type`, the
/// function that wraps an item in its type's class, and the one that adds
/// them all to the protocol's module.
macro_rules! kinds {
    (
        $protocol:ident, $module:literal, [$($common:literal),*],
        { $($class:ident = $name:literal $([$($optional:literal),*])?,)* }
    ) => {
        pub mod $protocol {
            use super::*;

            /// The optional fields every message of the protocol may lack.
            const COMMON: &[&str] = &[$($common),*];

            /// The base of the protocol's message classes (``isinstance(item,
            /// Message)``): an :class:`robowire.Item` whose fields the
            /// protocol declares, optional ones reading ``None``.
            #[pyclass(module = $module, extends = Item, frozen, subclass)]
            pub struct Message;

            $(
                #[doc = concat!("A `", $name, "` message (see its stub for the fields).")]
                #[pyclass(module = $module, extends = Message, frozen)]
                pub struct $class;
            )*

            /// `item` as an object of the class of `type` `name` (an
            /// `Item` for a name without one, which no decoded frame has).
            pub fn wrap<'py>(py: Python<'py>, name: &str, item: Item) -> PyResult<Bound<'py, PyAny>> {
                match name {
                    $($name => {
                        static KIND: PyOnceLock<Py<PyString>> = PyOnceLock::new();
                        let kind = KIND.get_or_init(py, || PyString::intern(py, $name).unbind());
                        let item = item.classed(kind, COMMON, &[$($($optional),*)?]);
                        let init = PyClassInitializer::from(item).add_subclass(Message);
                        untracked_init(py, init.add_subclass($class))
                    })*
                    _ => untracked_init(py, PyClassInitializer::from(item)),
                }
            }

            /// Add every class to `module`.
            pub fn add(module: &Bound<'_, PyModule>) -> PyResult<()> {
                module.add_class::<Message>()?;
                $(module.add_class::<$class>()?;)*
                Ok(())
            }

            /// Whether `class` is one of this protocol's classes.
            pub fn owns(class: &Bound<'_, PyType>) -> bool {
                class.is_subclass_of::<Message>().unwrap_or(false)
            }
        }
    };
}

kinds!(telemetrix, "robowire.telemetrix", ["t", "quirk", "also"], {
        SerialLoopBack = "serial_loop_back",
        SetPinMode = "set_pin_mode" ["differential", "report_enable"],
        DigitalWrite = "digital_write",
        PwmWrite = "pwm_write" ["trailing"],
        ModifyReporting = "modify_reporting" ["pin"],
        GetFirmwareVersion = "get_firmware_version",
        GetPicoUniqueId = "get_pico_unique_id",
        ServoAttach = "servo_attach" ["min_us", "max_us"],
        ServoWrite = "servo_write",
        ServoDetach = "servo_detach",
        I2cBegin = "i2c_begin",
        I2cRead = "i2c_read" ["msg_id"],
        I2cWrite = "i2c_write" ["msg_id"],
        SonarNew = "sonar_new",
        DhtNew = "dht_new",
        StopAllReports = "stop_all_reports",
        EnableAllReports = "enable_all_reports",
        ResetData = "reset_data",
        ResetBoard = "reset_board",
        InitializeNeoPixels = "initialize_neo_pixels",
        ShowNeoPixels = "show_neo_pixels",
        SetNeoPixel = "set_neo_pixel",
        ClearAllNeoPixels = "clear_all_neo_pixels" ["auto_show"],
        FillNeoPixels = "fill_neo_pixels",
        SpiInit = "spi_init",
        SpiWriteBlocking = "spi_write_blocking",
        SpiReadBlocking = "spi_read_blocking",
        SpiSetFormat = "spi_set_format",
        SpiCsControl = "spi_cs_control",
        SetScanDelay = "set_scan_delay",
        EncoderNew = "encoder_new" ["pulls"],
        SensorNew = "sensor_new" ["sensor_num", "settings"],
        Ping = "ping",
        ModuleNew = "module_new" ["module_num", "init"],
        ModuleData = "module_data" ["module_type", "message", "data"],
        GetId = "get_id",
        SetId = "set_id",
        FeatureRequest = "feature_request",
        BootloaderReset = "bootloader_reset",
        SerialLoopBackReport = "serial_loop_back_report",
        DigitalReport = "digital_report",
        AnalogReport = "analog_report",
        FirmwareVersion = "firmware_version",
        PicoUniqueId = "pico_unique_id",
        I2cWriteReport = "i2c_write_report",
        I2cWriteFailed = "i2c_write_failed",
        I2cReadFailed = "i2c_read_failed",
        I2cReadReport = "i2c_read_report" ["addr", "msg_id"],
        SonarDistance = "sonar_distance" ["echo", "m", "hundredths"],
        DhtReport = "dht_report",
        SpiReport = "spi_report",
        EncoderReport = "encoder_report",
        SensorReport = "sensor_report",
        SensorMainReport = "sensor_main_report",
        Pong = "pong",
        ModuleMainReport = "module_main_report",
        ModuleReport = "module_report",
        GetIdReport = "get_id_report",
        SetIdReport = "set_id_report",
        FeatureCheck = "feature_check",
        DebugPrint = "debug_print",
        UnknownReport = "unknown_report",
});

kinds!(pixy2, "robowire.pixy2", ["t", "quirk"], {
        ChangeProg = "change_prog" ["payload_len"],
        GetResolution = "get_resolution" ["reserved"],
        GetVersion = "get_version",
        SetCameraBrightness = "set_camera_brightness",
        SetServos = "set_servos",
        SetLed = "set_led",
        SetLamp = "set_lamp",
        GetFps = "get_fps",
        GetBlocks = "get_blocks",
        GetFeatures = "get_features",
        SetMode = "set_mode",
        SetVector = "set_vector",
        SetNextTurn = "set_next_turn",
        SetDefaultTurn = "set_default_turn",
        ReverseVector = "reverse_vector",
        GetRgb = "get_rgb",
        Result = "result",
        Error = "error",
        Resolution = "resolution",
        Version = "version",
        Blocks = "blocks",
        Features = "features",
});
