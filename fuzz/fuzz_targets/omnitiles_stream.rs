//! The OmniTiles stream decoder on arbitrary bytes: the same events and
//! counters whether the input is fed whole, in chunk sizes taken from the
//! input, byte at a time through `push`/`poll`, or through `feed`/`flush`;
//! consumption and counters are checked on every call.
#![no_main]

use libfuzzer_sys::fuzz_target;
use robowire::omnitiles::BOTH_BUFFER;
use robowire::StreamDecoder;
use robowire_fuzz::{check_stream, omnitiles_framing, split_input, with_omnitiles_framing};

fuzz_target!(|data: &[u8]| {
    let Some((selector, sizes, stream)) = split_input(data) else {
        return;
    };
    with_omnitiles_framing!(omnitiles_framing(selector), |framing| {
        check_stream(
            || StreamDecoder::<_, BOTH_BUFFER>::new(framing),
            stream,
            sizes,
        );
    });
});
