//! The OmniTiles stream decoder on arbitrary bytes: the same events and
//! counters whether the input is fed whole, in chunk sizes taken from the
//! input, byte at a time through `push`/`poll`, or through `feed`/`flush`;
//! consumption and counters are checked on every call.
#![no_main]

use libfuzzer_sys::fuzz_target;
use robowire::omnitiles::Decoder;
use robowire_fuzz::{check_stream, omnitiles_framing, split_input};

fuzz_target!(|data: &[u8]| {
    let Some((selector, sizes, stream)) = split_input(data) else {
        return;
    };
    let framing = omnitiles_framing(selector);
    check_stream(|| Decoder::new(framing), stream, sizes);
});
