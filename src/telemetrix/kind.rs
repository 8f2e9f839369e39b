//! The field kinds of the message table's `plain` rows (see
//! [`table`](super::table)): each kind's Rust type, how it is read and
//! checked from a frame, and how it is written. The serde forms of the same
//! kinds are `visit_field!` (in `fields`) and `read_member!` (in `schema`).
//!
//! The macros expand where the codec's helpers are in scope: `ensure`,
//! `counted`, `rgb`, `PIN_COUNT` and the `Reader`/`Writer` methods.

/// The Rust type of a `plain` row's field kind.
macro_rules! field_type {
    (counted_pins $($args:tt)?) => { &'a [u8] };
    (counted $($args:tt)?) => { &'a [u8] };
    (rest) => { &'a [u8] };
    (array($n:literal)) => { [u8; $n] };
    (nonzero_u32) => { u32 };
    (trailing_u16_pair $($args:tt)?) => { Option<(u16, u16)> };
    (trailing_flag) => { Option<bool> };
    (u16) => { u16 };
    (u16_max $($args:tt)?) => { u16 };
    (i16) => { i16 };
    (i8) => { i8 };
    (i32) => { i32 };
    (f32) => { f32 };
    (f32s($n:literal)) => { [f32; $n] };
    (i16s($n:literal)) => { [i16; $n] };
    (flag) => { bool };
    (level) => { bool };
    (rgb) => { Rgb };
    // u8, pin, range
    ($kind:ident $($args:tt)?) => { u8 };
}

/// Read and check one field of a `plain` row.
macro_rules! read_field {
    ($r:ident, $cmd:ident, $f:ident, $key:literal, counted_pins($count:literal, $each:literal $(, $max:literal)?)) => {{
        let pins = counted($r, $count, 0)?;
        ensure(pins.iter().all(|&p| p < PIN_COUNT), $cmd, $each)?;
        pins
    }};
    ($r:ident, $cmd:ident, $f:ident, $key:literal, nonzero_u32) => {{
        let v = $r.u32()?;
        ensure(v >= 1, $cmd, $key)?;
        v
    }};
    ($r:ident, $cmd:ident, $f:ident, $key:literal, trailing_u16_pair $args:tt) => {
        if $r.remaining() > 0 {
            Some(($r.u16()?, $r.u16()?))
        } else {
            None
        }
    };
    ($r:ident, $cmd:ident, $f:ident, $key:literal, counted($count:literal $(, $max:literal)?)) => {
        counted($r, $count, 0)?
    };
    ($r:ident, $cmd:ident, $f:ident, $key:literal, trailing_flag) => {
        if $r.remaining() > 0 {
            Some($r.flag($key)?)
        } else {
            None
        }
    };
    ($r:ident, $cmd:ident, $f:ident, $key:literal, u8) => {
        $r.u8()?
    };
    ($r:ident, $cmd:ident, $f:ident, $key:literal, array($n:literal)) => {
        $r.array::<$n>()?
    };
    ($r:ident, $cmd:ident, $f:ident, $key:literal, rest) => {
        $r.rest()
    };
    ($r:ident, $cmd:ident, $f:ident, $key:literal, u16) => {
        $r.u16()?
    };
    ($r:ident, $cmd:ident, $f:ident, $key:literal, u16_max($max:literal)) => {{
        let v = $r.u16()?;
        ensure(v <= $max, $cmd, $key)?;
        v
    }};
    ($r:ident, $cmd:ident, $f:ident, $key:literal, i16) => {
        $r.i16()?
    };
    ($r:ident, $cmd:ident, $f:ident, $key:literal, type_check $names:tt) => {{
        ensure($r.u8()? == 0, $cmd, "subtype")?;
        $r.u8()?
    }};
    ($r:ident, $cmd:ident, $f:ident, $key:literal, i8) => {
        $r.i8()?
    };
    ($r:ident, $cmd:ident, $f:ident, $key:literal, i32) => {
        $r.i32()?
    };
    ($r:ident, $cmd:ident, $f:ident, $key:literal, f32) => {
        $r.f32()?
    };
    ($r:ident, $cmd:ident, $f:ident, $key:literal, f32s($n:literal)) => {
        $crate::telemetrix::kind::read_field!(@each $r, [0.0; $n], f32)
    };
    ($r:ident, $cmd:ident, $f:ident, $key:literal, i16s($n:literal)) => {
        $crate::telemetrix::kind::read_field!(@each $r, [0; $n], i16)
    };
    // An array, each value read by the reader's method `$read`.
    (@each $r:ident, $values:expr, $read:ident) => {{
        let mut values = $values;
        for value in &mut values {
            *value = $r.$read()?;
        }
        values
    }};
    ($r:ident, $cmd:ident, $f:ident, $key:literal, pin) => {
        $r.pin($key)?
    };
    ($r:ident, $cmd:ident, $f:ident, $key:literal, flag) => {
        $r.flag($key)?
    };
    ($r:ident, $cmd:ident, $f:ident, $key:literal, level) => {
        $r.flag($key)?
    };
    ($r:ident, $cmd:ident, $f:ident, $key:literal, rgb) => {
        rgb($r)?
    };
    ($r:ident, $cmd:ident, $f:ident, $key:literal, range($lo:literal, $hi:literal)) => {{
        let v = $r.u8()?;
        ensure(($lo..=$hi).contains(&v), $cmd, stringify!($f))?;
        v
    }};
}

/// Write one field of a `plain` row.
macro_rules! write_field {
    ($w:ident, $f:ident, counted_pins $args:tt) => {
        write_field!($w, $f, counted)
    };
    ($w:ident, $f:ident, array $args:tt) => {
        $w.bytes(&$f)
    };
    ($w:ident, $f:ident, rest) => {
        $w.bytes($f)
    };
    ($w:ident, $f:ident, nonzero_u32) => {
        $w.u32($f)
    };
    ($w:ident, $f:ident, trailing_u16_pair $args:tt) => {
        if let Some((a, b)) = $f {
            $w.u16(a);
            $w.u16(b);
        }
    };
    ($w:ident, $f:ident, counted $($args:tt)?) => {{
        $w.u8($f.len() as u8);
        $w.bytes($f);
    }};
    ($w:ident, $f:ident, trailing_flag) => {
        if let Some(flag) = $f {
            $w.flag(flag);
        }
    };
    ($w:ident, $f:ident, flag) => {
        $w.flag($f)
    };
    ($w:ident, $f:ident, level) => {
        $w.flag($f)
    };
    ($w:ident, $f:ident, u16) => {
        $w.u16($f)
    };
    ($w:ident, $f:ident, u16_max $args:tt) => {
        $w.u16($f)
    };
    ($w:ident, $f:ident, i16) => {
        $w.i16($f)
    };
    ($w:ident, $f:ident, type_check $names:tt) => {
        $w.bytes(&[0, $f])
    };
    ($w:ident, $f:ident, i8) => {
        $w.i8($f)
    };
    ($w:ident, $f:ident, i32) => {
        $w.i32($f)
    };
    ($w:ident, $f:ident, f32) => {
        $w.f32($f)
    };
    ($w:ident, $f:ident, f32s $args:tt) => {
        $f.iter().for_each(|&v| $w.f32(v))
    };
    ($w:ident, $f:ident, i16s $args:tt) => {
        $f.iter().for_each(|&v| $w.i16(v))
    };
    ($w:ident, $f:ident, rgb) => {
        $w.bytes(&[$f.r, $f.g, $f.b])
    };
    // u8, pin, range
    ($w:ident, $f:ident, $kind:ident $($args:tt)?) => {
        $w.u8($f)
    };
}

/// Parse a row's payload, as an expression: a `plain` row's fields read and
/// checked by their kinds from the reader `$r` (`$id` in errors; its variant
/// of `$enum` named after `plain`, or in brackets by a report row), a
/// `custom` row's `parse` piece with its parameters bound to `$ctx`.
macro_rules! parse_row {
    ($ctx:tt, $r:ident, $id:ident, $enum:ident, $([$($vs:ident)+])? custom {
        variants $vars:tt parse ($($param:ident),*) { $($body:tt)* } $($pieces:tt)*
    }) => {{
        $crate::telemetrix::kind::bind_hook!(($($param),*) = $ctx);
        $($body)*
    }};
    ($ctx:tt, $r:ident, $id:ident, $enum:ident, [$p:ident] plain $body:tt) => {
        $crate::telemetrix::kind::parse_row!($ctx, $r, $id, $enum, plain $p $body)
    };
    ($ctx:tt, $r:ident, $id:ident, $enum:ident, plain $p:ident {
        $($(#[$fm:meta])* $f:ident : $kind:ident $(($($arg:tt)*))? $key:literal),* $(,)?
    }) => {
        $enum::$p { $($f: $crate::telemetrix::kind::read_field!($r, $id, $f, $key, $kind $(($($arg)*))?),)* }
    };
}

/// Write a row's payload: a `plain` row's fields in wire order (its variant
/// of `$enum` is named after `plain`, or in brackets by a report row), a
/// `custom` row's by its `write` arms, with its parameters bound to `$w`
/// and the consumer's other values.
macro_rules! write_row {
    ($value:ident, ($w:ident $(, $ctx:ident)*), $enum:ident, $([$($vs:ident)+])? custom {
        variants $vars:tt parse $pp:tt $pb:tt write ($($param:ident),*) { $($arms:tt)* } $($hooks:tt)*
    }) => {{
        $crate::telemetrix::kind::bind_hook!(($($param),*) = ($w $(, $ctx)*));
        match *$value {
            $($arms)*
            _ => {}
        }
    }};
    ($value:ident, $ws:tt, $enum:ident, [$p:ident] plain $body:tt) => {
        write_row!($value, $ws, $enum, plain $p $body)
    };
    ($value:ident, $ws:tt, $enum:ident, plain $p:ident {}) => {{}};
    ($value:ident, ($w:ident $(, $ctx:ident)*), $enum:ident, plain $p:ident {
        $($(#[$fm:meta])* $f:ident : $kind:ident $(($($arg:tt)*))? $key:literal),* $(,)?
    }) => {
        if let $enum::$p { $($f),* } = *$value {
            $(write_field!($w, $f, $kind $(($($arg)*))?);)*
        }
    };
}

/// The encoder's checks of a row beyond its id's dialects: a `custom` row's
/// `check` piece, or the maxima a `plain` row's field kinds give.
macro_rules! check_row {
    ($value:ident, $dialect:ident, $enum:ident, custom $body:tt) => {
        $crate::telemetrix::kind::piece!(check ($value, $dialect) expr { Ok(()) }, custom $body)
    };
    ($value:ident, $dialect:ident, $enum:ident, plain $p:ident {}) => {
        Ok(())
    };
    ($value:ident, $dialect:ident, $enum:ident, plain $p:ident {
        $($(#[$fm:meta])* $f:ident : $kind:ident $(($($arg:tt)*))? $key:literal),* $(,)?
    }) => {{
        if let $enum::$p { $($f),* } = *$value {
            $($crate::telemetrix::kind::check_field!($f, $kind $(($($arg)*))?);)*
        }
        Ok(())
    }};
}

/// The encoder's check of one field of a `plain` row: the most bytes a
/// byte list may hold, when its kind gives it (`at_most` in scope).
macro_rules! check_field {
    ($f:ident, counted_pins($count:literal, $each:literal, $max:literal)) => {
        at_most($f.len(), $max)?
    };
    ($f:ident, counted($count:literal, $max:literal)) => {
        at_most($f.len(), $max)?
    };
    ($f:ident, $kind:ident $($args:tt)?) => {
        let _ = $f;
    };
}

/// The piece `$name` (`check`, `home`, `quirk`, `fields` or `read`) of a
/// `custom` row or of a section of the module table (`{ variants { … }
/// pieces… }`, or a `data` section's pieces alone), its parameters bound to
/// the values in `$ctx`: an expression (`expr`), or the arms of a `match` on
/// a value (`(match value)`, with a catch-all arm). A `plain` row, or a
/// section without the piece, gives `$default` (a `compile_error!` where
/// the piece is required).
macro_rules! piece {
    ($name:ident $ctx:tt $how:tt $default:block, plain $($row:tt)*) => {
        $default
    };
    ($name:ident $ctx:tt $how:tt $default:block, custom $section:tt) => {
        $crate::telemetrix::kind::piece!($name $ctx $how $default, $section)
    };
    ($name:ident $ctx:tt $how:tt $default:block,
        { variants $vars:tt $($piece:ident $params:tt $body:tt)* }) => {
        $crate::telemetrix::kind::piece!(@find $name $ctx $how $default, $($piece $params $body)*)
    };
    ($name:ident $ctx:tt $how:tt $default:block, { $($piece:ident $params:tt $body:tt)* }) => {
        $crate::telemetrix::kind::piece!(@find $name $ctx $how $default, $($piece $params $body)*)
    };
    (@find check $ctx:tt $how:tt $default:block, check $params:tt $body:tt $($rest:tt)*) => {
        $crate::telemetrix::kind::piece!(@emit $ctx $how $params $body)
    };
    (@find home $ctx:tt $how:tt $default:block, home $params:tt $body:tt $($rest:tt)*) => {
        $crate::telemetrix::kind::piece!(@emit $ctx $how $params $body)
    };
    (@find quirk $ctx:tt $how:tt $default:block, quirk $params:tt $body:tt $($rest:tt)*) => {
        $crate::telemetrix::kind::piece!(@emit $ctx $how $params $body)
    };
    (@find fields $ctx:tt $how:tt $default:block, fields $params:tt $body:tt $($rest:tt)*) => {
        $crate::telemetrix::kind::piece!(@emit $ctx $how $params $body)
    };
    (@find read $ctx:tt $how:tt $default:block, read $params:tt $body:tt $($rest:tt)*) => {
        $crate::telemetrix::kind::piece!(@emit $ctx $how $params $body)
    };
    (@find $name:ident $ctx:tt $how:tt $default:block, $piece:ident $params:tt $body:tt $($rest:tt)*) => {
        $crate::telemetrix::kind::piece!(@find $name $ctx $how $default, $($rest)*)
    };
    (@find $name:ident $ctx:tt $how:tt $default:block,) => {
        $default
    };
    (@emit $ctx:tt expr ($($param:ident),*) { $($body:tt)* }) => {{
        $crate::telemetrix::kind::bind_hook!(($($param),*) = $ctx);
        $($body)*
    }};
    (@emit $ctx:tt (match $value:expr) ($($param:ident),*) { $($body:tt)* }) => {{
        $crate::telemetrix::kind::bind_hook!(($($param),*) = $ctx);
        match $value {
            $($body)*
            _ => {}
        }
    }};
}

/// Bind a `custom` row's hook parameters (the names the row's code uses,
/// in the order the table's docs give) to the consumer's values: the row's
/// own identifiers, so that macro hygiene lets its code see them.
macro_rules! bind_hook {
    (($($param:ident),*) = ($($value:expr),*)) => {
        #[allow(unused_variables)]
        let ($($param,)*) = ($($value,)*);
    };
}

pub(crate) use {
    bind_hook, check_field, check_row, field_type, parse_row, piece, read_field, write_field,
    write_row,
};
