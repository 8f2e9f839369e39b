//! `units::mm_to_position` and `units::adc_to_mm` against references written
//! from the SDK's formulas, in `f64` as Python computes them:
//! `max(0, min(255, round(mm / stroke * 255)))` with Python's `round` (ties
//! to even), and `raw / 4095 * stroke`.

use proptest::prelude::*;
use robowire::omnitiles::units::{adc_to_mm, adc_to_mm_f64, mm_to_position};
use robowire::omnitiles::Motor;

fn sdk(motor: Motor, mm: f64) -> u8 {
    let stroke = match motor {
        Motor::M1 => 150.0,
        Motor::M2 => 100.0,
    };
    (mm / stroke * 255.0).round_ties_even().clamp(0.0, 255.0) as u8
}

#[test]
fn ties_go_to_the_even_byte_as_in_the_sdk() {
    // 25 mm on M1 is 42.5: the SDK sends `a5 33 2a 5d`.
    assert_eq!(mm_to_position(Motor::M1, 25.0), 42);
    for mm in (5..=145).step_by(10) {
        let mm = f64::from(mm);
        assert_eq!(mm_to_position(Motor::M1, mm), sdk(Motor::M1, mm), "M1 {mm}");
    }
    for mm in [30.0, 70.0] {
        assert_eq!(mm_to_position(Motor::M2, mm), sdk(Motor::M2, mm), "M2 {mm}");
    }
    assert_eq!(mm_to_position(Motor::M2, 30.0), 76);
    assert_eq!(mm_to_position(Motor::M2, 70.0), 178);
}

/// The SDK's position in millimetres: `raw / 4095 * stroke`, in `f64`.
fn sdk_mm(motor: Motor, raw: u16) -> f64 {
    let stroke = match motor {
        Motor::M1 => 150.0,
        Motor::M2 => 100.0,
    };
    f64::from(raw) / 4095.0 * stroke
}

#[test]
fn adc_to_mm_is_the_sdk_value_for_every_input() {
    // Every u16 on both motors: 131,072 inputs. The f64 form is the SDK's
    // number bit for bit; the f32 form is that number rounded once to f32.
    // (Computed in f32 it differed by one ulp on 33,163 of them.)
    let mut differ = 0;
    for motor in [Motor::M1, Motor::M2] {
        for raw in 0..=u16::MAX {
            let sdk = sdk_mm(motor, raw);
            assert_eq!(
                adc_to_mm_f64(motor, raw).to_bits(),
                sdk.to_bits(),
                "{motor:?} {raw}"
            );
            if adc_to_mm(motor, raw).to_bits() != (sdk as f32).to_bits() {
                differ += 1;
            }
        }
    }
    assert_eq!(
        differ, 0,
        "inputs whose f32 is not the SDK's value rounded to f32"
    );
    // The spec's example: m1 2000 is 73.26 mm, m2 1000 is 24.42 mm.
    assert_eq!(adc_to_mm(Motor::M1, 2000), 73.260_07);
    assert_eq!(adc_to_mm(Motor::M2, 1000), 24.420_025);
}

#[test]
fn out_of_range_and_nan_clamp() {
    assert_eq!(mm_to_position(Motor::M1, -3.0), 0);
    assert_eq!(mm_to_position(Motor::M1, 1e9), 255);
    assert_eq!(mm_to_position(Motor::M1, f64::INFINITY), 255);
    assert_eq!(mm_to_position(Motor::M1, f64::NEG_INFINITY), 0);
    assert_eq!(mm_to_position(Motor::M1, f32::NAN), 0);
}

proptest! {
    #[test]
    fn matches_the_sdk_for_every_f64(mm in -20.0f64..200.0, m2 in any::<bool>()) {
        let motor = if m2 { Motor::M2 } else { Motor::M1 };
        prop_assert_eq!(mm_to_position(motor, mm), sdk(motor, mm));
    }

    #[test]
    fn matches_the_sdk_for_every_f32(bits in any::<u32>(), m2 in any::<bool>()) {
        let motor = if m2 { Motor::M2 } else { Motor::M1 };
        let mm = f32::from_bits(bits);
        prop_assume!(!mm.is_nan());
        prop_assert_eq!(mm_to_position(motor, mm), sdk(motor, f64::from(mm)));
    }

    #[test]
    fn matches_the_sdk_near_ties(step in 0u32..=255, m2 in any::<bool>(), nudge in -4i64..=4) {
        // Inputs whose quotient lands on or within a few ulps of k + 0.5.
        let motor = if m2 { Motor::M2 } else { Motor::M1 };
        let stroke = if m2 { 100.0 } else { 150.0 };
        let tie = (f64::from(step) + 0.5) * stroke / 255.0;
        let mm = f64::from_bits((tie.to_bits() as i64 + nudge) as u64);
        prop_assert_eq!(mm_to_position(motor, mm), sdk(motor, mm));
        let narrow = mm as f32;
        prop_assert_eq!(mm_to_position(motor, narrow), sdk(motor, f64::from(narrow)));
    }
}
