//! The OmniTiles stream decoder on arbitrary bytes: the same events and
//! counters whether the input is fed whole, in chunk sizes taken from the
//! input, byte at a time through `push`/`poll`, or through `feed`/`flush`;
//! consumption and counters are checked on every call. A host framing's
//! view decoder (telemetry read in place) gives the same events and counters
//! as its owned decoder.
#![no_main]

use libfuzzer_sys::fuzz_target;
use robowire::omnitiles::{BOTH_BUFFER, HOST_BUFFER};
use robowire::StreamDecoder;
use robowire_fuzz::{
    check_stream, omnitiles_framing, split_input, with_omnitiles_framing, OmniTilesFraming,
};

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
    if let OmniTilesFraming::Host(framing) = omnitiles_framing(selector) {
        let owned = check_stream(
            || StreamDecoder::<_, HOST_BUFFER>::new(framing),
            stream,
            sizes,
        );
        let views = check_stream(
            || StreamDecoder::<_, HOST_BUFFER>::new(framing.views()),
            stream,
            sizes,
        );
        assert_eq!(views, owned);
    }
});
