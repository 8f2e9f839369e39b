//! Telemetrix messages as JSON: `type`, then the fields after the spec.

use super::names::{
    command_type, module_name, pin_mode_name, report_type, sensor_name, MODULE_TYPES,
    REPORTING_ACTIONS, SENSOR_TYPES,
};
use super::{Kind, Message};
use crate::json::{JsonLine, Scalar};
use robowire::telemetrix::{
    Command, CommandRef, Dialect, EncoderKind, HiwonderCommand, ModifyReporting, ModuleCommand,
    ModuleInit, ModuleNew, ModuleReport, ModuleType, Pca9685Command, PinMode, RelayCommand, Report,
    ReportRef, SensorNew, SensorReading, Sonar, Ssd1306Command, Ssd1306Done, SONAR_NO_ECHO,
    SONAR_OUT_OF_RANGE, SONAR_STALE,
};

/// A flag (a 0/1 byte that switches something on): `true` or `false`.
pub struct Flag(pub bool);

impl Scalar for Flag {
    fn write(&self, buf: &mut Vec<u8>) {
        buf.extend_from_slice(if self.0 { b"true" } else { b"false" });
    }
}

/// JSON text that is already written.
struct RawJson<'a>(&'a [u8]);

impl Scalar for RawJson<'_> {
    fn write(&self, buf: &mut Vec<u8>) {
        buf.extend_from_slice(self.0);
    }
}

/// A type byte: its name where it names a known type, its number otherwise.
struct TypeByte(u8, &'static [&'static str]);

impl Scalar for TypeByte {
    fn write(&self, buf: &mut Vec<u8>) {
        match self.1.get(usize::from(self.0)) {
            Some(name) => name.write(buf),
            None => self.0.write(buf),
        }
    }
}

/// A mirte 1.3 sonar distance: centimetres, or the name of a sentinel.
struct SonarCm(u16);

impl Scalar for SonarCm {
    fn write(&self, buf: &mut Vec<u8>) {
        match self.0 {
            SONAR_NO_ECHO => "no_echo".write(buf),
            SONAR_OUT_OF_RANGE => "out_of_range".write(buf),
            SONAR_STALE => "stale".write(buf),
            cm => cm.write(buf),
        }
    }
}

/// Bytes as a string, one character per byte (ISO 8859-1), so that any bytes
/// survive the round trip.
struct Latin1<'a>(&'a [u8]);

impl Scalar for Latin1<'_> {
    fn write(&self, buf: &mut Vec<u8>) {
        let text: String = self.0.iter().map(|&b| char::from(b)).collect();
        text.as_str().write(buf);
    }
}

/// A JSON array of objects, each written by `each`.
fn objects<T>(
    items: impl IntoIterator<Item = T>,
    mut each: impl FnMut(&mut JsonLine, T),
) -> Vec<u8> {
    let mut out = vec![b'['];
    let mut object = JsonLine::default();
    for (i, item) in items.into_iter().enumerate() {
        if i > 0 {
            out.push(b',');
        }
        object.begin();
        each(&mut object, item);
        let text = object.end();
        // Without the line's newline.
        out.extend_from_slice(&text[..text.len() - 1]);
    }
    out.push(b']');
    out
}

/// Write `type` (and `also`) and the fields of a decoded frame.
pub fn message(m: &Message, line: &mut JsonLine) {
    match &m.kind {
        Kind::Command(c) => command(&c.as_ref(), m, None, line),
        Kind::Report(r) => report(&r.as_ref(), None, line),
        Kind::Both {
            command: c,
            report: r,
            as_command: true,
        } => command(&c.as_ref(), m, Some(report_type(r)), line),
        Kind::Both {
            command: c,
            report: r,
            as_command: false,
        } => report(&r.as_ref(), Some(command_type(c)), line),
    }
}

fn rgb_fields(line: &mut JsonLine, rgb: robowire::telemetrix::Rgb) {
    line.field("r", rgb.r);
    line.field("g", rgb.g);
    line.field("b", rgb.b);
}

fn command(c: &CommandRef<'_>, m: &Message, also: Option<&str>, line: &mut JsonLine) {
    line.field("type", command_type(c));
    if let Some(also) = also {
        line.field("also", also);
    }
    match *c {
        Command::LoopBack { byte } => line.field("byte", byte),
        Command::SetPinMode { pin, mode } => {
            line.field("pin", pin);
            line.field("mode", pin_mode_name(&mode));
            match mode {
                PinMode::DigitalInput { report, .. } => line.field("report_enable", Flag(report)),
                PinMode::AnalogInput {
                    differential,
                    report,
                } => {
                    line.field("differential", differential);
                    line.field("report_enable", Flag(report));
                }
                PinMode::DigitalOutput | PinMode::PwmOutput => {}
            }
        }
        Command::DigitalWrite { pin, high } => {
            line.field("pin", pin);
            line.field("value", u8::from(high));
        }
        Command::PwmWrite(pins) => {
            let pins = objects(pins.iter(), |o, p| {
                o.field("pin", p.pin);
                o.field("value", p.value);
            });
            line.field("pins", RawJson(&pins));
        }
        Command::ModifyReporting(action) => {
            let (kind, pin) = match action {
                ModifyReporting::DisableAll => (0, None),
                ModifyReporting::EnableAnalog { pin } => (1, Some(pin)),
                ModifyReporting::EnableDigital { pin } => (2, Some(pin)),
                ModifyReporting::DisableAnalog { pin } => (3, Some(pin)),
                ModifyReporting::DisableDigital { pin } => (4, Some(pin)),
            };
            line.field("action", REPORTING_ACTIONS[kind]);
            if let Some(pin) = pin {
                line.field("pin", pin);
            }
        }
        Command::GetFirmwareVersion
        | Command::GetUniqueId
        | Command::StopAllReports
        | Command::EnableAllReports
        | Command::ResetData
        | Command::ResetBoard
        | Command::ShowNeoPixels
        | Command::GetId
        | Command::BootloaderReset => {}
        Command::ServoAttach { pin, pulse_range } => {
            line.field("pin", pin);
            if let Some((min_us, max_us)) = pulse_range {
                line.field("min_us", min_us);
                line.field("max_us", max_us);
            }
        }
        Command::ServoWrite { pin, pulse_us } => {
            line.field("pin", pin);
            line.field("pulse_us", pulse_us);
        }
        Command::ServoDetach { pin } | Command::DhtNew { pin } => line.field("pin", pin),
        Command::I2cBegin { port, sda, scl } => {
            line.field("port", port);
            line.field("sda", sda);
            line.field("scl", scl);
        }
        Command::I2cRead {
            port,
            addr,
            msg_id,
            reg,
            len,
            no_stop,
        } => {
            line.field("port", port);
            line.field("addr", addr);
            line.field("msg_id", msg_id);
            line.field("reg", reg);
            line.field("n", len);
            line.field("no_stop", no_stop);
        }
        Command::I2cReadUpstream {
            port,
            addr,
            reg,
            len,
            no_stop,
        } => {
            line.field("port", port);
            line.field("addr", addr);
            line.field("reg", reg);
            line.field("n", len);
            line.field("no_stop", no_stop);
        }
        Command::I2cWrite {
            port,
            addr,
            msg_id,
            no_stop,
            data,
        } => {
            line.field("port", port);
            line.field("addr", addr);
            line.field("msg_id", msg_id);
            line.field("no_stop", no_stop);
            line.array("data", data.iter().copied());
        }
        Command::I2cWriteUpstream {
            port,
            addr,
            no_stop,
            data,
        } => {
            line.field("port", port);
            line.field("addr", addr);
            line.field("no_stop", no_stop);
            line.array("data", data.iter().copied());
        }
        Command::SonarNew { trig, echo } => {
            line.field("trig", trig);
            line.field("echo", echo);
        }
        Command::InitNeoPixels { pin, count, rgb } => {
            line.field("pin", pin);
            line.field("count", count);
            rgb_fields(line, rgb);
        }
        Command::SetNeoPixel {
            index,
            rgb,
            auto_show,
        } => {
            line.field("index", index);
            rgb_fields(line, rgb);
            line.field("auto_show", Flag(auto_show));
        }
        Command::ClearAllNeoPixels { auto_show } => {
            if let Some(auto_show) = auto_show {
                line.field("auto_show", Flag(auto_show));
            }
        }
        Command::FillNeoPixels { rgb, auto_show } => {
            rgb_fields(line, rgb);
            line.field("auto_show", Flag(auto_show));
        }
        Command::SpiInit {
            port,
            pin_a,
            pin_b,
            clk,
            freq_hz,
            cs_pins,
        } => {
            line.field("port", port);
            line.field("pin_a", pin_a);
            line.field("pin_b", pin_b);
            line.field("clk", clk);
            line.field("freq_hz", freq_hz);
            line.array("cs_pins", cs_pins.iter().copied());
        }
        Command::SpiWrite { port, data } => {
            line.field("port", port);
            line.array("data", data.iter().copied());
        }
        Command::SpiRead { port, len, tx_fill } => {
            line.field("port", port);
            line.field("n", len);
            line.field("tx_fill", tx_fill);
        }
        Command::SpiSetFormat {
            port,
            data_bits,
            cpol,
            cpha,
        } => {
            line.field("port", port);
            line.field("data_bits", data_bits);
            line.field("cpol", u8::from(cpol));
            line.field("cpha", u8::from(cpha));
        }
        Command::SpiCsControl { cs_pin, high } => {
            line.field("cs_pin", cs_pin);
            line.field("level", u8::from(high));
        }
        Command::SetScanDelay { delay_ms } => line.field("delay_ms", delay_ms),
        Command::EncoderNew {
            kind,
            pin_a,
            pin_b,
            pulls,
        } => {
            let kind = match kind {
                EncoderKind::Single => "single",
                EncoderKind::Quadrature => "quadrature",
            };
            line.field("kind", kind);
            line.field("pin_a", pin_a);
            line.field("pin_b", pin_b);
            // Only mirte 1.3 sends the pulls byte.
            if m.dialect == Dialect::Mirte13 {
                line.object("pulls", |o| {
                    o.field("up", Flag(pulls.up));
                    o.field("down", Flag(pulls.down));
                });
            }
        }
        Command::SensorNew(SensorNew::Check { sensor_type }) => {
            line.field("subtype", "check");
            line.field("sensor_type", TypeByte(sensor_type, &SENSOR_TYPES));
        }
        Command::SensorNew(SensorNew::Add {
            sensor_num,
            sensor_type,
            settings,
        }) => {
            line.field("subtype", "add");
            line.field("sensor_num", sensor_num);
            line.field("sensor_type", sensor_name(sensor_type));
            line.array("settings", settings);
        }
        Command::Ping { counter } => line.field("counter", counter),
        Command::ModuleNew(ModuleNew::Check { module_type }) => {
            line.field("subtype", "check");
            line.field("module_type", TypeByte(module_type, &MODULE_TYPES));
        }
        Command::ModuleNew(ModuleNew::Add { module_num, init }) => {
            line.field("subtype", "add");
            line.field("module_num", module_num);
            line.field("module_type", module_name(init_type(&init)));
            line.object("init", |o| module_init(&init, o));
        }
        Command::ModuleData { module_num, data } => {
            line.field("module_num", module_num);
            if !m.module_type.is_some_and(|t| module_data(t, data, line)) {
                line.array("data", data.iter().copied());
            }
        }
        Command::SetId { id } => line.field("id", id),
        Command::FeatureCheck { msg_type } => line.field("msg_type", msg_type),
    }
}

/// The module type a MODULE_NEW init is for.
pub fn init_type<B>(init: &ModuleInit<B>) -> ModuleType {
    match init {
        ModuleInit::Pca9685 { .. } => ModuleType::Pca9685,
        ModuleInit::HiwonderServo { .. } => ModuleType::HiwonderServo,
        ModuleInit::ShutdownRelay { .. } => ModuleType::ShutdownRelay,
        ModuleInit::Ssd1306 { .. } => ModuleType::Ssd1306,
    }
}

fn module_init(init: &ModuleInit<&[u8]>, o: &mut JsonLine) {
    match *init {
        ModuleInit::Pca9685 { port, config } => {
            o.field("port", port);
            if let Some(config) = config {
                o.field("addr", config.addr);
                o.field("freq_hz", config.freq_hz);
            }
        }
        ModuleInit::HiwonderServo {
            uart,
            rx,
            tx,
            bus_ids,
        } => {
            o.field("uart", uart);
            o.field("rx", rx);
            o.field("tx", tx);
            o.array("bus_ids", bus_ids.iter().copied());
        }
        ModuleInit::ShutdownRelay {
            pin,
            active_high,
            wait_s,
        } => {
            o.field("pin", pin);
            o.field("active_level", u8::from(active_high));
            o.field("wait_s", wait_s);
        }
        ModuleInit::Ssd1306 { port, addr } => {
            o.field("port", port);
            if let Some(addr) = addr {
                o.field("addr", addr);
            }
        }
    }
}

/// MODULE_DATA parsed as the data of one module type.
enum ModuleData {
    Hiwonder(HiwonderCommand),
    Pca9685(Pca9685Command),
    Ssd1306(Ssd1306Command),
    Relay(RelayCommand),
}

impl ModuleData {
    fn parse(module_type: ModuleType, data: &[u8]) -> Option<Self> {
        match module_type {
            ModuleType::HiwonderServo => HiwonderCommand::parse(data).ok().map(Self::Hiwonder),
            ModuleType::Pca9685 => Pca9685Command::parse(data).ok().map(Self::Pca9685),
            ModuleType::Ssd1306 => Ssd1306Command::parse(data).ok().map(Self::Ssd1306),
            ModuleType::ShutdownRelay => RelayCommand::parse(data).ok().map(Self::Relay),
        }
    }
}

/// MODULE_DATA for a module of a known type: `module_type` and `message`,
/// if the bytes parse as that module's data. Returns whether they did.
fn module_data(module_type: ModuleType, data: &[u8], line: &mut JsonLine) -> bool {
    let Some(message) = ModuleData::parse(module_type, data) else {
        return false;
    };
    line.field("module_type", module_name(module_type));
    line.object("message", |o| match &message {
        ModuleData::Hiwonder(m) => hiwonder_command(m, o),
        ModuleData::Pca9685(m) => {
            let channels = objects(m.channels.iter(), |c, ch| {
                c.field("channel", ch.channel);
                c.field("on", ch.on);
                c.field("off", ch.off);
            });
            o.field("channels", RawJson(&channels));
        }
        ModuleData::Ssd1306(m) => ssd1306_command(m, o),
        ModuleData::Relay(m) => {
            let subtype = match m {
                RelayCommand::Start => "start",
                RelayCommand::Cancel => "cancel",
            };
            o.field("subtype", subtype);
        }
    });
    true
}

fn hiwonder_command(message: &HiwonderCommand, o: &mut JsonLine) {
    match message {
        HiwonderCommand::SetAngle(moves) => {
            o.field("subtype", "set_angle");
            let moves = objects(moves.iter(), |m, mv| {
                m.field("idx", mv.idx);
                m.field("centideg", mv.centideg);
                m.field("time_ms", mv.time_ms);
            });
            o.field("moves", RawJson(&moves));
        }
        HiwonderCommand::Enable { enabled, servos } => {
            o.field("subtype", "enable");
            o.field("enabled", Flag(*enabled));
            o.array("servos", servos.iter().copied());
        }
        HiwonderCommand::IdWrite { new_id } => {
            o.field("subtype", "id_write");
            o.field("new_id", *new_id);
        }
        HiwonderCommand::IdVerify { bus_id } => {
            o.field("subtype", "id_verify");
            o.field("bus_id", *bus_id);
        }
        HiwonderCommand::RangeWrite {
            idx,
            min_cdeg,
            max_cdeg,
        } => {
            o.field("subtype", "range_write");
            o.field("idx", *idx);
            o.field("min_cdeg", *min_cdeg);
            o.field("max_cdeg", *max_cdeg);
        }
        HiwonderCommand::RangeRead { idx } => {
            o.field("subtype", "range_read");
            o.field("idx", *idx);
        }
        HiwonderCommand::OffsetWrite { idx, offset_cdeg } => {
            o.field("subtype", "offset_write");
            o.field("idx", *idx);
            o.field("offset_cdeg", *offset_cdeg);
        }
        HiwonderCommand::OffsetRead { idx } => {
            o.field("subtype", "offset_read");
            o.field("idx", *idx);
        }
        HiwonderCommand::VoltageLimitWrite {
            idx,
            min_mv,
            max_mv,
        } => {
            o.field("subtype", "voltage_limit_write");
            o.field("idx", *idx);
            o.field("min_mv", *min_mv);
            o.field("max_mv", *max_mv);
        }
        HiwonderCommand::MotorModeWrite { idx, speed } => {
            o.field("subtype", "motor_mode_write");
            o.field("idx", *idx);
            o.field("speed", *speed);
        }
        HiwonderCommand::AddServo { bus_id } => {
            o.field("subtype", "add_servo");
            o.field("bus_id", *bus_id);
        }
    }
}

fn ssd1306_command(message: &Ssd1306Command, o: &mut JsonLine) {
    match message {
        Ssd1306Command::Text(text) => {
            o.field("subtype", "text");
            o.field("text", Latin1(text));
        }
        Ssd1306Command::TextDone => o.field("subtype", "text_done"),
        Ssd1306Command::Binary { chunk, data } => {
            o.field("subtype", "binary");
            o.field("chunk", *chunk);
            o.array("data", *data);
        }
        Ssd1306Command::BinaryDone => o.field("subtype", "binary_done"),
    }
}

fn report(r: &ReportRef<'_>, also: Option<&str>, line: &mut JsonLine) {
    line.field("type", report_type(r));
    if let Some(also) = also {
        line.field("also", also);
    }
    match *r {
        Report::LoopBack { byte } => line.field("byte", byte),
        Report::Digital { pin, high } => {
            line.field("pin", pin);
            line.field("value", u8::from(high));
        }
        Report::Analog { pin, value } => {
            line.field("pin", pin);
            line.field("value", value);
        }
        Report::FirmwareVersion { major, minor } => {
            line.field("major", major);
            line.field("minor", minor);
        }
        Report::UniqueId { id } => line.array("id", id),
        Report::I2cWrite {
            port,
            msg_id,
            result,
        } => {
            line.field("port", port);
            line.field("msg_id", msg_id);
            line.field("result", result);
        }
        Report::I2cWriteFailed { port, addr, stale }
        | Report::I2cReadFailed { port, addr, stale } => {
            line.field("port", port);
            line.field("addr", addr);
            line.field("stale", stale);
        }
        Report::I2cRead {
            port,
            msg_id,
            reg,
            data,
        } => {
            line.field("port", port);
            line.field("msg_id", msg_id);
            line.field("reg", reg);
            line.array("data", data.iter().copied());
        }
        Report::I2cReadUpstream {
            port,
            addr,
            reg,
            data,
        } => {
            line.field("port", port);
            line.field("addr", addr);
            line.field("reg", reg);
            line.array("data", data.iter().copied());
        }
        Report::Sonar(sonar) => match sonar {
            Sonar::WithEcho { trig, echo, cm } => {
                line.field("trig", trig);
                line.field("echo", echo);
                line.field("cm", SonarCm(cm));
            }
            Sonar::TrigOnly { trig, cm } => {
                line.field("trig", trig);
                line.field("cm", SonarCm(cm));
            }
            Sonar::MetresCm { trig, m, cm } => {
                line.field("trig", trig);
                line.field("m", m);
                line.field("cm", cm);
            }
            Sonar::CmHundredths {
                trig,
                cm,
                hundredths,
            } => {
                line.field("trig", trig);
                line.field("cm", cm);
                line.field("hundredths", hundredths);
            }
        },
        Report::Dht {
            pin,
            humidity,
            humidity_hundredths,
            temp,
            temp_hundredths,
        } => {
            line.field("pin", pin);
            line.field("hum_int", humidity);
            line.field("hum_hundredths", humidity_hundredths);
            line.field("temp_int", temp);
            line.field("temp_hundredths", temp_hundredths);
        }
        Report::Spi { port, data } => {
            line.field("port", port);
            line.array("data", data.iter().copied());
        }
        Report::Encoder { pin, steps } => {
            line.field("pin_a", pin);
            line.field("steps", steps);
        }
        Report::Sensor {
            sensor_num,
            reading,
        } => {
            line.field("sensor_num", sensor_num);
            line.field("sensor_type", sensor_name(reading.sensor_type()));
            line.object("reading", |o| sensor_reading(&reading, o));
        }
        Report::SensorSupported {
            sensor_type,
            supported,
        } => {
            line.field("sensor_type", TypeByte(sensor_type, &SENSOR_TYPES));
            line.field("supported", Flag(supported));
        }
        Report::Pong { counter, boot_id } => {
            line.field("counter", counter);
            line.field("boot_id", boot_id);
        }
        Report::ModuleSupported {
            module_type,
            supported,
        } => {
            line.field("module_type", TypeByte(module_type, &MODULE_TYPES));
            line.field("supported", Flag(supported));
        }
        Report::Module { module_num, report } => {
            line.field("module_num", module_num);
            line.field("module_type", module_name(report.module_type()));
            line.object("message", |o| module_report(&report, o));
        }
        Report::Id { id } | Report::IdSet { id } => line.field("id", id),
        Report::Feature {
            msg_type,
            supported,
            extras,
        } => {
            line.field("msg_type", msg_type);
            line.field("ok", Flag(supported));
            line.array("extras", extras.iter().copied());
        }
        Report::Debug { id, value } => {
            line.field("id", id);
            line.field("value", value);
        }
        Report::Unknown { id, payload } => {
            line.field("id", id);
            line.array("payload", payload.iter().copied());
        }
    }
}

fn sensor_reading(reading: &SensorReading, o: &mut JsonLine) {
    match *reading {
        SensorReading::Hx711 { raw } => o.field("raw", raw),
        SensorReading::Mpu9250 {
            accel,
            gyro,
            mag,
            quat,
        } => {
            o.array("accel", accel);
            o.array("gyro", gyro);
            o.array("mag", mag);
            o.array("quat", quat);
        }
        SensorReading::Vl53l0x { mm } => o.field("mm", mm),
        SensorReading::Veml6040 { r, g, b, w } => {
            o.field("r", r);
            o.field("g", g);
            o.field("b", b);
            o.field("w", w);
        }
        SensorReading::Adxl345 { accel } => o.array("accel", accel),
        SensorReading::Ina226 { volts, amps } => {
            o.field("volts", volts);
            o.field("amps", amps);
        }
        SensorReading::Hmc5883l { field } => o.array("field", field),
        SensorReading::As5600 { angles } => o.array("angles", angles.iter().copied()),
        SensorReading::Mpu6050 { accel, gyro, temp } => {
            o.array("accel", accel);
            o.array("gyro", gyro);
            o.field("temp", temp);
        }
        SensorReading::Bno055 {
            gyro,
            mag,
            accel,
            quat,
            temp,
        } => {
            o.array("gyro", gyro);
            o.array("mag", mag);
            o.array("accel", accel);
            o.array("quat", quat);
            o.field("temp", temp);
        }
    }
}

fn module_report(report: &ModuleReport<&[u8]>, o: &mut JsonLine) {
    match *report {
        ModuleReport::HiwonderPositions(positions) => {
            o.field("subtype", "positions");
            let positions = objects(positions.iter(), |p, pos| {
                p.field("idx", pos.idx);
                p.field("centideg", pos.centideg);
            });
            o.field("positions", RawJson(&positions));
        }
        ModuleReport::HiwonderIdVerify { bus_id, ok } => {
            o.field("subtype", "id_verify");
            o.field("bus_id", bus_id);
            o.field("ok", Flag(ok));
        }
        ModuleReport::HiwonderRange {
            idx,
            min_cdeg,
            max_cdeg,
        } => {
            o.field("subtype", "range");
            o.field("idx", idx);
            o.field("min_cdeg", min_cdeg);
            o.field("max_cdeg", max_cdeg);
        }
        ModuleReport::HiwonderOffset { idx, offset_cdeg } => {
            o.field("subtype", "offset");
            o.field("idx", idx);
            o.field("offset_cdeg", offset_cdeg);
        }
        ModuleReport::HiwonderAdded { bus_id, idx } => {
            o.field("subtype", "added");
            o.field("bus_id", bus_id);
            o.field("idx", idx);
        }
        ModuleReport::Ssd1306Done {
            kind,
            len,
            display_x,
            enabled,
        } => {
            let subtype = match kind {
                Ssd1306Done::Text => "text_done",
                Ssd1306Done::Binary => "binary_done",
            };
            o.field("subtype", subtype);
            o.field("len", len);
            o.field("display_x", display_x);
            o.field("enabled", Flag(enabled));
        }
        ModuleReport::Ssd1306Disabled { request_sub } => {
            o.field("subtype", "disabled");
            o.field("request_sub", request_sub);
        }
    }
}
