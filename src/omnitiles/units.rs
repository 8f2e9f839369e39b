//! Conversions between wire bytes and physical meaning (spec §3 and §5).
//!
//! ```
//! use robowire::omnitiles::{units, Motor};
//! assert_eq!(units::speed_to_duty(255), 50);
//! assert_eq!(units::mm_to_position(Motor::M1, 75.0), 128);
//! assert!((units::position_to_mm(Motor::M1, 128) - 75.29).abs() < 0.01);
//! assert_eq!(units::position_target_mm(Motor::M2, 0), 25.0);
//! assert_eq!(units::duty_to_velocity(-1.0), -127);
//! ```

use super::command::Motor;

/// The PWM's maximum duty level (20 kHz from a 1 MHz timer, ARR = 49).
pub const MAX_DUTY: u8 = 50;

/// Full-scale raw reading of a position or ADC channel (12-bit).
pub const ADC_FULL_SCALE: u16 = 4095;

impl Motor {
    /// The actuator's stroke in millimetres (M1 150, M2 100).
    pub const fn stroke_mm(self) -> f32 {
        match self {
            Motor::M1 => 150.0,
            Motor::M2 => 100.0,
        }
    }

    /// The firmware's clamp on set-position targets, in millimetres
    /// (M1 20–115, M2 25–85).
    pub const fn target_range_mm(self) -> (f32, f32) {
        match self {
            Motor::M1 => (20.0, 115.0),
            Motor::M2 => (25.0, 85.0),
        }
    }
}

/// Round half away from zero, without `std`.
fn round(x: f32) -> f32 {
    let r = if x >= 0.0 { x + 0.5 } else { x - 0.5 };
    (r as i32) as f32
}

/// The duty level (0..=50) the firmware drives for a speed byte:
/// `floor(v / 255 · 50)`. Speeds 1..=5 give 0 (coast); speed 0 brakes.
pub const fn speed_to_duty(speed: u8) -> u8 {
    (speed as u16 * MAX_DUTY as u16 / 255) as u8
}

/// The speed byte for a commanded duty fraction 0.0..=1.0 (`round(d · 255)`,
/// clamped). NaN gives 0.
pub fn duty_to_speed(duty: f32) -> u8 {
    round(duty.clamp(0.0, 1.0) * 255.0) as u8
}

/// The target a set-position byte asks for, in millimetres, before the
/// firmware's clamp: `stroke · v / 255`.
pub fn position_to_mm(motor: Motor, position: u8) -> f32 {
    motor.stroke_mm() * f32::from(position) / 255.0
}

/// The target the firmware actually moves to: [`position_to_mm`] clamped to
/// [`Motor::target_range_mm`].
pub fn position_target_mm(motor: Motor, position: u8) -> f32 {
    let (lo, hi) = motor.target_range_mm();
    position_to_mm(motor, position).clamp(lo, hi)
}

/// The set-position byte for a target in millimetres, exactly as the SDK
/// encodes it: `round(mm / stroke · 255)` computed in `f64` with
/// round-half-to-even (Python's `round`), then clamped to 0..=255. NaN gives
/// 0 (the SDK raises). Takes `f32` or `f64`; an `f32` is widened exactly.
///
/// ```
/// use robowire::omnitiles::{units::mm_to_position, Motor};
/// // 25 / 150 · 255 = 42.5: ties go to the even byte, as in the SDK.
/// assert_eq!(mm_to_position(Motor::M1, 25.0), 42);
/// assert_eq!(mm_to_position(Motor::M2, 30.0_f32), 76);
/// ```
pub fn mm_to_position(motor: Motor, mm: impl Into<f64>) -> u8 {
    let x = mm.into() / f64::from(motor.stroke_mm()) * 255.0;
    // NaN fails both comparisons and ends at 0.
    let x = if x >= 255.0 {
        255.0
    } else if x > 0.0 {
        x
    } else {
        0.0
    };
    round_half_even(x) as u8
}

/// Round a value in 0.0..=255.0 to the nearest whole number, ties to even,
/// without `std`. Exact: the integer part and the fraction of such an `f64`
/// are both representable.
fn round_half_even(x: f64) -> f64 {
    let whole = f64::from(x as u32);
    let fraction = x - whole;
    if fraction > 0.5 || (fraction == 0.5 && (x as u32) % 2 == 1) {
        whole + 1.0
    } else {
        whole
    }
}

/// A base velocity byte as normalised duty: `v / 127` (so −128 → −1.008).
pub fn velocity_to_duty(v: i8) -> f32 {
    f32::from(v) / 127.0
}

/// The base velocity byte for a normalised duty: `round(d · 127)`, clamped to
/// −128..=127. NaN gives 0.
pub fn duty_to_velocity(duty: f32) -> i8 {
    round((duty * 127.0).clamp(-128.0, 127.0)) as i8
}

/// A raw position or ADC reading (0..=4095) in millimetres along the stroke,
/// as the SDK computes it (`raw / 4095 · stroke`, see [`adc_to_mm_f64`])
/// and rounded once to `f32`. The tile's firmware sends the raw reading and
/// converts nothing, so the SDK's number is the reference.
///
/// It stays in `f32`, for firmware without a double-precision FPU: `raw ·
/// stroke` is an integer below 2²⁴, so exact in `f32`, and one IEEE division
/// rounds the exact quotient once. That is the SDK's number: its `f64`
/// result is within a few `f64` ulps of the quotient, and a quotient `n /
/// 4095` is never that close to a midpoint between two `f32`s. Dividing
/// first, as 0.2.0 did, rounded twice and was one ulp off for a quarter of
/// all inputs. A test compares every input with [`adc_to_mm_f64`].
///
/// ```
/// use robowire::omnitiles::{units::adc_to_mm, Motor};
/// assert_eq!(adc_to_mm(Motor::M1, 2000), (2000.0_f64 / 4095.0 * 150.0) as f32);
/// ```
pub fn adc_to_mm(motor: Motor, raw: u16) -> f32 {
    f32::from(raw) * motor.stroke_mm() / f32::from(ADC_FULL_SCALE)
}

/// A raw position or ADC reading in millimetres exactly as the SDK computes
/// it: `raw / 4095 * stroke` in `f64` (Python's float), bit for bit. On a
/// target without a double-precision FPU this links the soft-float `f64`
/// division; [`adc_to_mm`] is the same number as an `f32` without it.
pub fn adc_to_mm_f64(motor: Motor, raw: u16) -> f64 {
    f64::from(raw) / f64::from(ADC_FULL_SCALE) * f64::from(motor.stroke_mm())
}
