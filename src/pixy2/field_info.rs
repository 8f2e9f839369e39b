//! What each Pixy2 field means (spec §3 and §4): units, names and which
//! frames carry it, declared once for the tool's schemas, CSV and plots and
//! for the Python items.

use super::envelope::Message;
use super::error::DeviceError;
use super::quirk::Quirk;
use crate::units::{FieldInfo, FieldTable, Unit};

const fn px(doc: &'static str) -> FieldInfo {
    FieldInfo::new(doc).unit(Unit::Pixel)
}

const fn cell(doc: &'static str) -> FieldInfo {
    FieldInfo::new(doc).unit(Unit::GridCell)
}

const fn degrees(doc: &'static str) -> FieldInfo {
    FieldInfo::new(doc).unit(Unit::Degree)
}

/// Every Pixy2 field: requests (host → device) and responses (device →
/// host). Features are under `sections.*.vectors.*` and so on.
///
/// ```
/// use robowire::pixy2::FIELD_INFO;
/// use robowire::units::Unit;
/// assert_eq!(FIELD_INFO.get("blocks", "blocks.3.x").unwrap().unit, Some(Unit::Pixel));
/// assert_eq!(
///     FIELD_INFO.get("features", "sections.0.vectors.1.x0").unwrap().unit,
///     Some(Unit::GridCell),
/// );
/// ```
pub static FIELD_INFO: FieldTable = FieldTable {
    protocol: "pixy2",
    entries: &[
        (
            "*",
            "type",
            FieldInfo::new("The message type.").names(&Message::NAMES),
        ),
        (
            "*",
            "checksum",
            FieldInfo::new("Whether the frame carried a checksum (af c1 / ae c1 sync)."),
        ),
        (
            "*",
            "quirk",
            FieldInfo::new("What the device refuses about this request.")
                .names(&Quirk::NAMES)
                .optional(),
        ),
        (
            "change_prog",
            "name",
            FieldInfo::new("The program's name (\"color_connected_components\", \"line\", …)."),
        ),
        (
            "get_resolution",
            "reserved",
            FieldInfo::new("The reserved byte, shown when not 0.").optional(),
        ),
        (
            "set_camera_brightness",
            "brightness",
            FieldInfo::new("Camera brightness."),
        ),
        (
            "set_servos",
            "pan",
            FieldInfo::new("Pan servo position, 0..1000 (more is ignored)."),
        ),
        (
            "set_servos",
            "tilt",
            FieldInfo::new("Tilt servo position, 0..1000 (more is ignored)."),
        ),
        ("set_led", "r", FieldInfo::new("LED red.")),
        ("set_led", "g", FieldInfo::new("LED green.")),
        ("set_led", "b", FieldInfo::new("LED blue.")),
        (
            "set_lamp",
            "upper",
            FieldInfo::new("Upper lamps on (not 0)."),
        ),
        (
            "set_lamp",
            "lower",
            FieldInfo::new("Lower lamp on (not 0)."),
        ),
        (
            "get_blocks",
            "sigmap",
            FieldInfo::new("Signatures asked for, one bit each (255: all)."),
        ),
        (
            "get_blocks",
            "max_blocks",
            FieldInfo::new("The most blocks to return."),
        ),
        (
            "get_features",
            "scope",
            FieldInfo::new("0: the main features, 1: all."),
        ),
        (
            "get_features",
            "features",
            FieldInfo::new("Feature types asked for: 1 vectors, 2 intersections, 4 barcodes."),
        ),
        (
            "set_mode",
            "mode",
            FieldInfo::new("Line-tracking mode flags."),
        ),
        (
            "set_vector",
            "index",
            FieldInfo::new("The vector to track, by index."),
        ),
        (
            "set_next_turn",
            "angle",
            degrees("Turn at the next intersection (0 up, +90 left)."),
        ),
        (
            "set_default_turn",
            "angle",
            degrees("Turn when no next turn is set (0 up, +90 left)."),
        ),
        ("get_rgb", "x", px("Pixel column.")),
        ("get_rgb", "y", px("Pixel row.")),
        (
            "get_rgb",
            "saturate",
            FieldInfo::new("Scale the colour to saturation (not 0)."),
        ),
        (
            "result",
            "value",
            FieldInfo::new("The request's result (getFPS: frames/s; getRGB: 0x00RRGGBB)."),
        ),
        (
            "error",
            "code",
            FieldInfo::new("The device's error, by name (its number if unknown).")
                .names_or_number(&DeviceError::NAMES),
        ),
        ("resolution", "width", px("Frame width.")),
        ("resolution", "height", px("Frame height.")),
        ("version", "hardware", FieldInfo::new("Hardware version.")),
        (
            "version",
            "firmware_major",
            FieldInfo::new("Firmware major version."),
        ),
        (
            "version",
            "firmware_minor",
            FieldInfo::new("Firmware minor version."),
        ),
        (
            "version",
            "firmware_build",
            FieldInfo::new("Firmware build number."),
        ),
        (
            "version",
            "firmware_type",
            FieldInfo::new("Firmware type (\"general\")."),
        ),
        (
            "blocks",
            "blocks",
            FieldInfo::new("The blocks detected, largest first.").rows(),
        ),
        (
            "blocks",
            "blocks.*.signature",
            FieldInfo::new("Signature 1..7, or a color code's signatures as octal digits."),
        ),
        ("blocks", "blocks.*.x", px("Centre column.")),
        ("blocks", "blocks.*.y", px("Centre row.")),
        ("blocks", "blocks.*.width", px("Width.")),
        ("blocks", "blocks.*.height", px("Height.")),
        (
            "blocks",
            "blocks.*.angle",
            degrees("Color code angle, −180..180 (0 for plain signatures)."),
        ),
        (
            "blocks",
            "blocks.*.index",
            FieldInfo::new("Tracking index: the same object keeps it from frame to frame."),
        ),
        (
            "blocks",
            "blocks.*.age",
            FieldInfo::new("Frames tracked (saturates at 255).").unit(Unit::Frame),
        ),
        (
            "features",
            "sections",
            FieldInfo::new("The feature sections in wire order."),
        ),
        (
            "features",
            "sections.*.vectors",
            FieldInfo::new("Line vectors.").optional().rows(),
        ),
        ("features", "sections.*.vectors.*.x0", cell("Tail column.")),
        ("features", "sections.*.vectors.*.y0", cell("Tail row.")),
        ("features", "sections.*.vectors.*.x1", cell("Head column.")),
        ("features", "sections.*.vectors.*.y1", cell("Head row.")),
        (
            "features",
            "sections.*.vectors.*.index",
            FieldInfo::new("Tracking index."),
        ),
        (
            "features",
            "sections.*.vectors.*.flags",
            FieldInfo::new("Vector flags (2: intersection present)."),
        ),
        (
            "features",
            "sections.*.intersections",
            FieldInfo::new("Intersections.").optional().rows(),
        ),
        ("features", "sections.*.intersections.*.x", cell("Column.")),
        ("features", "sections.*.intersections.*.y", cell("Row.")),
        (
            "features",
            "sections.*.intersections.*.reserved",
            FieldInfo::new("The reserved byte, shown when not 0.").optional(),
        ),
        (
            "features",
            "sections.*.intersections.*.lines",
            FieldInfo::new("The lines leaving the intersection, by angle."),
        ),
        (
            "features",
            "sections.*.intersections.*.lines.*.index",
            FieldInfo::new("The line's vector index."),
        ),
        (
            "features",
            "sections.*.intersections.*.lines.*.angle",
            degrees("Direction outward (0 up, +90 left)."),
        ),
        (
            "features",
            "sections.*.intersections.*.lines.*.reserved",
            FieldInfo::new("The reserved byte, shown when not 0.").optional(),
        ),
        (
            "features",
            "sections.*.intersections.*.unused_slots",
            FieldInfo::new("Line slots after the valid ones, shown when one is not zero.")
                .optional(),
        ),
        (
            "features",
            "sections.*.barcodes",
            FieldInfo::new("Barcodes.").optional().rows(),
        ),
        ("features", "sections.*.barcodes.*.x", cell("Column.")),
        ("features", "sections.*.barcodes.*.y", cell("Row.")),
        (
            "features",
            "sections.*.barcodes.*.flags",
            FieldInfo::new("Barcode flags."),
        ),
        (
            "features",
            "sections.*.barcodes.*.code",
            FieldInfo::new("The barcode's value, 0..15."),
        ),
        (
            "features",
            "sections.*.ftype",
            FieldInfo::new("A feature type this codec does not know.").optional(),
        ),
        (
            "features",
            "sections.*.data",
            FieldInfo::new("That section's bytes.").optional(),
        ),
    ],
};
