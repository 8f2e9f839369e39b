//! `units::mm_to_position` against a reference written from the SDK's formula:
//! `max(0, min(255, round(mm / stroke * 255)))` in `f64`, Python's `round`
//! (ties to even).

use proptest::prelude::*;
use robowire::omnitiles::{units::mm_to_position, Motor};

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
