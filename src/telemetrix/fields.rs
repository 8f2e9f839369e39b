//! The fields of every message, in the order and with the names of the
//! JSON-lines schema, written once: `Display` walks them as `name k=v …`,
//! and (with `serde`) `Serialize` as a map.

use core::fmt;

use super::buf::{CommandBuf, Message, MessageBuf, ReportBuf};
use super::command::{Command, ModifyReporting, PinMode, PwmPin, Rgb};
use super::kind::{bind_hook, piece};
use super::list::List;
use super::module::{
    HiwonderCommand, ModuleCommand, ModuleInit, ModuleNew, ModuleReport, ModuleType,
    Pca9685Channel, Pca9685Command, RelayCommand, ServoMove, ServoPosition, ServoPositions,
    Ssd1306Command, Ssd1306Done,
};
use super::quirk::Quirk;
use super::report::{Report, Sonar, SONAR_NO_ECHO, SONAR_OUT_OF_RANGE, SONAR_STALE};
use super::sensor::{SensorNew, SensorReading, SensorType};
use super::table::sensor_readings;

/// One field value.
#[derive(Clone, Copy)]
pub(crate) enum V<'a> {
    /// An unsigned integer and its width on the wire.
    U(
        u64,
        #[cfg_attr(not(feature = "serde"), allow(dead_code))] Width,
    ),
    /// A signed integer and its width on the wire.
    I(
        i64,
        #[cfg_attr(not(feature = "serde"), allow(dead_code))] Width,
    ),
    Bool(bool),
    Str(&'a str),
    F32(f32),
    /// An array of numbers.
    Bytes(&'a [u8]),
    U16s(&'a [u16]),
    I16s(&'a [i16]),
    F32s(&'a [f32]),
    /// Bytes as a string, one character per byte (ISO 8859-1).
    Latin1(&'a [u8]),
    Obj(&'a dyn Visit),
    Objs(&'a dyn VisitSeq),
}

/// An integer's width on the wire: `serde` sees the Rust type it has
/// (`u8`, `i16`, …), so a schema can give the wire's range.
#[derive(Clone, Copy)]
pub(crate) enum Width {
    W8,
    W16,
    W32,
}

/// An integer type a field may have.
pub(crate) trait Wide: Copy {
    /// Its width.
    const WIDTH: Width;
}

macro_rules! wide {
    ($($ty:ty => $width:ident),*) => {$(
        impl Wide for $ty {
            const WIDTH: Width = Width::$width;
        }
    )*};
}

wide!(u8 => W8, u16 => W16, u32 => W32, i8 => W8, i16 => W16, i32 => W32);

/// Something with named fields.
pub(crate) trait Visit {
    fn visit(&self, w: &mut W<'_>);
}

/// A sequence of things with named fields.
pub(crate) trait VisitSeq {
    fn visit_each(&self, f: &mut dyn FnMut(&dyn Visit));
}

/// The receiver of fields.
pub(crate) struct W<'f>(pub(crate) &'f mut dyn FnMut(&'static str, V<'_>));

impl W<'_> {
    fn v(&mut self, key: &'static str, value: V<'_>) {
        (self.0)(key, value);
    }
    fn u<T: Into<u64> + Wide>(&mut self, key: &'static str, value: T) {
        self.v(key, V::U(value.into(), T::WIDTH));
    }
    fn i<T: Into<i64> + Wide>(&mut self, key: &'static str, value: T) {
        self.v(key, V::I(value.into(), T::WIDTH));
    }
    fn flag(&mut self, key: &'static str, value: bool) {
        self.v(key, V::Bool(value));
    }
    /// A level: 0 or 1.
    fn level(&mut self, key: &'static str, value: bool) {
        self.u(key, u8::from(value));
    }
    fn s(&mut self, key: &'static str, value: &str) {
        self.v(key, V::Str(value));
    }
    fn bytes(&mut self, key: &'static str, value: &[u8]) {
        self.v(key, V::Bytes(value));
    }
    fn obj(&mut self, key: &'static str, value: &dyn Visit) {
        self.v(key, V::Obj(value));
    }
    fn objs(&mut self, key: &'static str, value: &dyn VisitSeq) {
        self.v(key, V::Objs(value));
    }
    /// A type byte: its name where it names a known type, its number
    /// otherwise.
    fn type_byte(&mut self, key: &'static str, value: u8, names: &[&str]) {
        match names.get(usize::from(value)) {
            Some(name) => self.s(key, name),
            None => self.u(key, value),
        }
    }
}

/// Fields written by a closure.
pub(crate) struct FnVisit<F: Fn(&mut W<'_>)>(pub(crate) F);

impl<F: Fn(&mut W<'_>)> Visit for FnVisit<F> {
    fn visit(&self, w: &mut W<'_>) {
        (self.0)(w);
    }
}

impl<T: Visit, const N: usize> VisitSeq for List<T, N> {
    fn visit_each(&self, f: &mut dyn FnMut(&dyn Visit)) {
        for item in self {
            f(item);
        }
    }
}

impl Visit for PwmPin {
    fn visit(&self, w: &mut W<'_>) {
        w.u("pin", self.pin);
        w.u("value", self.value);
    }
}

impl Visit for ServoMove {
    fn visit(&self, w: &mut W<'_>) {
        w.u("idx", self.idx);
        w.u("centideg", self.centideg);
        w.u("time_ms", self.time_ms);
    }
}

impl Visit for Pca9685Channel {
    fn visit(&self, w: &mut W<'_>) {
        w.u("channel", self.channel);
        w.u("on", self.on);
        w.u("off", self.off);
    }
}

impl Visit for ServoPosition {
    fn visit(&self, w: &mut W<'_>) {
        w.u("idx", self.idx);
        w.u("centideg", self.centideg);
    }
}

impl VisitSeq for ServoPositions<'_> {
    fn visit_each(&self, f: &mut dyn FnMut(&dyn Visit)) {
        for position in self.iter() {
            f(&position);
        }
    }
}

fn rgb(w: &mut W<'_>, rgb: Rgb) {
    w.u("r", rgb.r);
    w.u("g", rgb.g);
    w.u("b", rgb.b);
}

/// A command with what a capture told about it: the other reading's type
/// and the type of the module a MODULE_DATA goes to.
pub(crate) struct CommandView<'c, 'a> {
    pub(crate) command: &'c Command<'a>,
    pub(crate) also: Option<&'static str>,
    pub(crate) module_type: Option<ModuleType>,
}

/// A report with the other reading's type.
pub(crate) struct ReportView<'r, 'a> {
    pub(crate) report: &'r Report<'a>,
    pub(crate) also: Option<&'static str>,
}

impl Visit for Command<'_> {
    fn visit(&self, w: &mut W<'_>) {
        CommandView {
            command: self,
            also: None,
            module_type: None,
        }
        .visit(w);
    }
}

impl Visit for Report<'_> {
    fn visit(&self, w: &mut W<'_>) {
        ReportView {
            report: self,
            also: None,
        }
        .visit(w);
    }
}

impl Visit for Message<'_> {
    fn visit(&self, w: &mut W<'_>) {
        match self {
            Message::Command(c) => c.visit(w),
            Message::Report(r) => r.visit(w),
        }
    }
}

/// A frame's fields (written by `fields`), then `quirk` when the frame has
/// one. Where the message does not hold all of a quirky frame's bytes, the
/// line gives them as they are on the wire, so that it encodes back to the
/// frame: a level byte above 1 as `value`, an encoder type 3 as `kind`, the
/// bytes after PWM_WRITE's last whole triple as `trailing`.
fn with_quirk(w: &mut W<'_>, frame: &[u8], quirk: Option<Quirk>, fields: &dyn Fn(&mut W<'_>)) {
    // The field a quirk replaces by its wire byte, and that byte.
    let replaced = match (quirk, frame) {
        (Some(Quirk::LevelNotBinary), &[_, _, _, level]) => Some(("value", level)),
        (Some(Quirk::EncoderTypeNot1Or2), &[_, _, kind, ..]) => Some(("kind", kind)),
        _ => None,
    };
    match replaced {
        Some((key, byte)) => fields(&mut W(&mut |k, v| {
            (w.0)(
                k,
                if k == key {
                    V::U(byte.into(), Width::W8)
                } else {
                    v
                },
            );
        })),
        None => fields(w),
    }
    if quirk == Some(Quirk::PwmTrailingBytes) {
        let payload = frame.get(2..).unwrap_or(&[]);
        w.bytes("trailing", &payload[payload.len() / 3 * 3..]);
    }
    if let Some(q) = quirk {
        w.s("quirk", q.name());
    }
}

impl Visit for CommandBuf {
    fn visit(&self, w: &mut W<'_>) {
        with_quirk(w, self.frame(), self.quirk(), &|w| self.message().visit(w));
    }
}

impl Visit for ReportBuf {
    fn visit(&self, w: &mut W<'_>) {
        with_quirk(w, self.frame(), self.quirk(), &|w| self.message().visit(w));
    }
}

impl Visit for MessageBuf {
    fn visit(&self, w: &mut W<'_>) {
        let also = self.also().map(|m| match m {
            Message::Command(c) => c.name(),
            Message::Report(r) => r.name(),
        });
        with_quirk(w, self.frame(), self.quirk(), &|w| match self.message() {
            Message::Command(command) => CommandView {
                command: &command,
                also,
                module_type: self.module_type(),
            }
            .visit(w),
            Message::Report(report) => ReportView {
                report: &report,
                also,
            }
            .visit(w),
        });
    }
}

/// A command's payload fields, from the command table: the `plain` rows'
/// fields by their kind, the `custom` rows' by their `fields` pieces.
macro_rules! command_fields {
    ($($(#[$vm:meta])* $n:literal $id:ident $name:literal [$($v:ident),+] in [$($d:ident),+] len $lens:tt
        $codec:ident $($p:ident)? { $($body:tt)* };)*) => {
        impl CommandView<'_, '_> {
            fn payload(&self, w: &mut W<'_>) {
                match *self.command {
                    $($(Command::$v { .. })|+ => {
                        visit_row!(self, w, Command (self.command), $codec $($p)? { $($body)* })
                    })*
                }
            }
        }
    };
}

/// Visit a row's payload: `$value` is the `$enum` (a `plain` row's variant
/// is named after `plain`, or in brackets by a report row); a `custom` row's
/// `fields` arms see `$view` and `$w` by the names the row gives them.
macro_rules! visit_row {
    ($view:ident, $w:ident, $enum:ident ($value:expr), $([$($vs:ident)+])? custom {
        variants $vars:tt parse $pp:tt $pb:tt write $wp:tt $wb:tt
        fields ($($param:ident),*) { $($arms:tt)* } $($hooks:tt)*
    }) => {{
        bind_hook!(($($param),*) = ($view, $w));
        match *$value {
            $($arms)*
            _ => {}
        }
    }};
    ($view:ident, $w:ident, $enum:ident ($value:expr), [$p:ident] plain $body:tt) => {
        visit_row!($view, $w, $enum ($value), plain $p $body)
    };
    ($view:ident, $w:ident, $enum:ident ($value:expr), plain $p:ident {}) => {{}};
    ($view:ident, $w:ident, $enum:ident ($value:expr),
        plain $p:ident { $($(#[$fm:meta])* $f:ident : $kind:ident $(($($arg:tt)*))? $key:literal),* $(,)? }) => {
        if let $enum::$p { $($f),* } = *$value {
            $(visit_field!($w, $f, $key, $kind $(($($arg)*))?);)*
        }
    };
}

/// Visit one field of a `plain` row.
macro_rules! visit_field {
    ($w:ident, $f:ident, $key:literal, counted_pins $args:tt) => {
        $w.bytes($key, $f)
    };
    ($w:ident, $f:ident, $key:literal, trailing_u16_pair($a:literal, $b:literal)) => {
        if let Some((a, b)) = $f {
            $w.u($a, a);
            $w.u($b, b);
        }
    };
    ($w:ident, $f:ident, $key:literal, counted $args:tt) => {
        $w.bytes($key, $f)
    };
    ($w:ident, $f:ident, $key:literal, rest) => {
        $w.bytes($key, $f)
    };
    ($w:ident, $f:ident, $key:literal, array $args:tt) => {
        $w.bytes($key, &$f)
    };
    ($w:ident, $f:ident, $key:literal, trailing_flag) => {
        if let Some(flag) = $f {
            $w.flag($key, flag);
        }
    };
    ($w:ident, $f:ident, $key:literal, flag) => {
        $w.flag($key, $f)
    };
    ($w:ident, $f:ident, $key:literal, level) => {
        $w.level($key, $f)
    };
    ($w:ident, $f:ident, $key:literal, rgb) => {
        rgb($w, $f)
    };
    ($w:ident, $f:ident, $key:literal, i16) => {
        $w.i($key, $f)
    };
    ($w:ident, $f:ident, $key:literal, type_check($($names:tt)*)) => {
        $w.type_byte($key, $f, $($names)*)
    };
    ($w:ident, $f:ident, $key:literal, i8) => {
        $w.i($key, $f)
    };
    ($w:ident, $f:ident, $key:literal, i32) => {
        $w.i($key, $f)
    };
    ($w:ident, $f:ident, $key:literal, f32) => {
        $w.v($key, V::F32($f))
    };
    ($w:ident, $f:ident, $key:literal, f32s $args:tt) => {
        $w.v($key, V::F32s(&$f))
    };
    ($w:ident, $f:ident, $key:literal, i16s $args:tt) => {
        $w.v($key, V::I16s(&$f))
    };
    // u8, u16, u16_max, pin, range
    ($w:ident, $f:ident, $key:literal, $kind:ident $($args:tt)?) => {
        $w.u($key, $f)
    };
}

super::table::command_table!(command_fields);

/// A report's payload fields, from the report table: the `plain` rows'
/// fields by their kind, the `custom` rows' by their `fields` pieces.
macro_rules! report_fields {
    ($($(#[$m:meta])* $n:literal $id:ident in [$($d:ident),+] len $rlen:tt
        { $($name:literal [$($v:ident),+]),+ } $codec:ident { $($body:tt)* };)*) => {
        impl ReportView<'_, '_> {
            fn payload(&self, w: &mut W<'_>) {
                match *self.report {
                    $($($(Report::$v { .. })|+)|+ => {
                        visit_row!(self, w, Report (self.report), [$($($v)+)+] $codec { $($body)* })
                    })*
                    Report::Unknown { id, payload } => {
                        w.u("id", id);
                        w.bytes("payload", payload);
                    }
                }
            }
        }
    };
}

super::table::report_table!(report_fields);

impl Visit for CommandView<'_, '_> {
    fn visit(&self, w: &mut W<'_>) {
        w.s("type", self.command.name());
        if let Some(also) = self.also {
            w.s("also", also);
        }
        self.payload(w);
    }
}

impl Visit for SensorNew {
    fn visit(&self, w: &mut W<'_>) {
        match *self {
            SensorNew::Check { sensor_type } => {
                w.s("subtype", "check");
                w.type_byte("sensor_type", sensor_type, SensorType::NAMES);
            }
            SensorNew::Add {
                sensor_num,
                sensor_type,
                ref settings,
            } => {
                w.s("subtype", "add");
                w.u("sensor_num", sensor_num);
                w.s("sensor_type", sensor_type.name());
                w.bytes("settings", settings);
            }
            SensorNew::AddMirte12 {
                sensor_num,
                sensor_type,
                ref settings,
            } => {
                w.s("subtype", "add");
                w.u("sensor_num", sensor_num);
                w.s("sensor_type", sensor_type.name());
                w.bytes("settings", settings);
            }
        }
    }
}

impl Visit for ModuleNew<'_> {
    fn visit(&self, w: &mut W<'_>) {
        match *self {
            ModuleNew::Check { module_type } => {
                w.s("subtype", "check");
                w.type_byte("module_type", module_type, ModuleType::NAMES);
            }
            ModuleNew::Add { module_num, init } => {
                w.s("subtype", "add");
                w.u("module_num", module_num);
                w.s("module_type", init.module_type().name());
                w.obj("init", &init);
            }
        }
    }
}

/// The JSON fields of a module's init and reports, from the module table.
macro_rules! module_fields {
    ($($(#[$tm:meta])* $n:literal $t:ident $name:literal
        init $init:tt data $data:ident $dsec:tt
        $(reports [$($rv:ident),+ $(,)?] $reports:tt)?;)*) => {
        impl Visit for ModuleInit<'_> {
            fn visit(&self, o: &mut W<'_>) {
                match *self {
                    $(ModuleInit::$t { .. } => {
                        piece!(fields (self, o) (match *self) { compile_error!("an init without fields") }, $init)
                    })*
                }
            }
        }

        impl Visit for ModuleReport<'_> {
            fn visit(&self, o: &mut W<'_>) {
                match *self {
                    $($($(ModuleReport::$rv { .. })|+ => {
                        piece!(fields (self, o) (match *self) { compile_error!("reports without fields") }, $reports)
                    })?)*
                }
            }
        }

        /// MODULE_DATA parsed as the data of one module type.
        enum ModuleData {
            $($t($data),)*
        }

        impl ModuleData {
            fn parse(module_type: ModuleType, data: &[u8]) -> Option<Self> {
                match module_type {
                    $(ModuleType::$t => $data::parse(data).ok().map(Self::$t),)*
                }
            }
        }

        impl Visit for ModuleData {
            fn visit(&self, o: &mut W<'_>) {
                match self {
                    $(ModuleData::$t(m) => data_fields!(o, m, $dsec),)*
                }
            }
        }
    };
}

/// A module's MODULE_DATA fields: its data table's, or the row's `fields`.
macro_rules! data_fields {
    ($o:ident, $m:ident, table) => {
        $m.visit($o)
    };
    ($o:ident, $m:ident, $section:tt) => {
        piece!(fields ($o, $m) expr { compile_error!("data without fields") }, $section)
    };
}

super::table::module_table!(module_fields);

/// A module data table's JSON fields: `subtype` names the row, then the
/// `plain` rows' fields by their kind, the `custom` rows' by their `fields`
/// pieces.
macro_rules! module_data_fields {
    ($(#[$em:meta])* $enum:ident; $($(#[$vm:meta])* $n:literal $name:literal [$($v:ident),+]
        $codec:ident $($p:ident)? { $($body:tt)* };)*) => {
        impl Visit for $enum {
            fn visit(&self, o: &mut W<'_>) {
                match *self {
                    $($($enum::$v { .. })|+ => {
                        o.s("subtype", $name);
                        visit_row!(self, o, $enum (self), $codec $($p)? { $($body)* })
                    })*
                }
            }
        }
    };
}

super::table::hiwonder_table!(module_data_fields);
super::table::ssd1306_table!(module_data_fields);

/// A mirte 1.3 sonar distance: centimetres, or the name of a sentinel.
fn sonar_cm(w: &mut W<'_>, cm: u16) {
    match cm {
        SONAR_NO_ECHO => w.s("cm", "no_echo"),
        SONAR_OUT_OF_RANGE => w.s("cm", "out_of_range"),
        SONAR_STALE => w.s("cm", "stale"),
        cm => w.u("cm", cm),
    }
}

impl Visit for ReportView<'_, '_> {
    fn visit(&self, w: &mut W<'_>) {
        w.s("type", self.report.name());
        if let Some(also) = self.also {
            w.s("also", also);
        }
        self.payload(w);
    }
}

/// A sensor reading's fields, from the sensor table.
macro_rules! sensor_reading_fields {
    ($($(#[$rm:meta])* $n:literal $t:ident $codec:ident { $($body:tt)* };)*) => {
        impl Visit for SensorReading {
            fn visit(&self, o: &mut W<'_>) {
                match *self {
                    $(SensorReading::$t { .. } => {
                        visit_row!(self, o, SensorReading (self), [$t] $codec { $($body)* })
                    })*
                }
            }
        }
    };
}

super::table::sensor_table!(sensor_readings, sensor_reading_fields);

// ---------------------------------------------------------------- Display

/// Write `value` for `Display`.
fn write_value(f: &mut fmt::Formatter<'_>, value: V<'_>) -> fmt::Result {
    fn list<T: fmt::Display>(f: &mut fmt::Formatter<'_>, items: &[T]) -> fmt::Result {
        f.write_str("[")?;
        for (i, item) in items.iter().enumerate() {
            if i > 0 {
                f.write_str(",")?;
            }
            write!(f, "{item}")?;
        }
        f.write_str("]")
    }
    match value {
        V::U(v, _) => write!(f, "{v}"),
        V::I(v, _) => write!(f, "{v}"),
        V::Bool(v) => write!(f, "{v}"),
        V::Str(v) => f.write_str(v),
        V::F32(v) => write!(f, "{v}"),
        V::Bytes(v) => list(f, v),
        V::U16s(v) => list(f, v),
        V::I16s(v) => list(f, v),
        V::F32s(v) => list(f, v),
        V::Latin1(v) => {
            f.write_str("\"")?;
            for &b in v {
                write!(f, "{}", char::from(b).escape_debug())?;
            }
            f.write_str("\"")
        }
        V::Obj(o) => {
            f.write_str("{")?;
            write_fields(f, o, false)?;
            f.write_str("}")
        }
        V::Objs(seq) => {
            f.write_str("[")?;
            let mut result = Ok(());
            let mut first = true;
            seq.visit_each(&mut |o| {
                if result.is_ok() {
                    if !first {
                        result = f.write_str(",");
                    }
                    first = false;
                    result = result
                        .and_then(|()| f.write_str("{"))
                        .and_then(|()| write_fields(f, o, false))
                        .and_then(|()| f.write_str("}"));
                }
            });
            result?;
            f.write_str("]")
        }
    }
}

/// Write the fields of `o` as `k=v`, space-separated; a leading `type` as its
/// bare value when `top`.
fn write_fields(f: &mut fmt::Formatter<'_>, o: &dyn Visit, top: bool) -> fmt::Result {
    let mut result = Ok(());
    let mut first = true;
    o.visit(&mut W(&mut |key, value| {
        if result.is_err() {
            return;
        }
        if !first {
            result = f.write_str(" ");
        }
        let bare = first && top && key == "type";
        first = false;
        if !bare {
            result = result.and_then(|()| write!(f, "{key}="));
        }
        result = result.and_then(|()| write_value(f, value));
    }));
    result
}

macro_rules! display_fields {
    ($($ty:ty),*) => {$(
        /// One line: the message's `type`, then its fields as `name=value`
        /// (the JSON-lines schema's words).
        impl fmt::Display for $ty {
            fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                write_fields(f, self, true)
            }
        }
    )*};
}

display_fields!(
    Command<'_>,
    Report<'_>,
    Message<'_>,
    CommandBuf,
    ReportBuf,
    MessageBuf
);
