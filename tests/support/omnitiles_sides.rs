//! An OmniTiles framing and stream decoder whose side is chosen at run time,
//! for tests that run the same checks over the host's, the device's and both
//! sides' decoders. Every event comes out with a [`Message`].

#![allow(dead_code)] // each test file uses a part

use robowire::omnitiles::{
    Both, BothDecoder, Device, DeviceDecoder, Error, Framing, Host, HostDecoder, Layouts, Message,
};
use robowire::stream::{owned_event, Event, FrameRules, OwnedEvent};
use robowire::{OwnedFrame, Rejected, Stats};

/// An event with the message of either direction.
pub type Ev = Result<OwnedFrame<Message>, Rejected<Error>>;

/// A framing of any side.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum AnyFraming {
    /// Telemetry only.
    Host(Framing<Host>),
    /// Commands only.
    Device(Framing<Device>),
    /// Both.
    Both(Framing<Both>),
}

/// Commands only.
pub fn commands() -> AnyFraming {
    AnyFraming::Device(Framing::new())
}

/// Telemetry in `layouts` only.
pub fn telemetry(layouts: Layouts) -> AnyFraming {
    AnyFraming::Host(Framing::new().with_layouts(layouts))
}

/// Commands and telemetry in `layouts`.
pub fn both(layouts: Layouts) -> AnyFraming {
    AnyFraming::Both(Framing::new().with_layouts(layouts))
}

/// Commands and telemetry in the documented layouts.
pub fn any() -> AnyFraming {
    both(Layouts::DOCUMENTED)
}

impl AnyFraming {
    /// The layouts accepted.
    pub fn layouts(&self) -> Layouts {
        match self {
            AnyFraming::Host(f) => f.layouts(),
            AnyFraming::Device(f) => f.layouts(),
            AnyFraming::Both(f) => f.layouts(),
        }
    }

    /// Whether commands are accepted.
    pub fn accepts_commands(&self) -> bool {
        !matches!(self, AnyFraming::Host(_))
    }
}

/// A stream decoder of any side.
#[derive(Debug, Clone)]
pub enum AnyDecoder {
    /// Telemetry only.
    Host(HostDecoder),
    /// Commands only.
    Device(DeviceDecoder),
    /// Both.
    Both(BothDecoder),
}

/// One engine event, owned, with its message as a [`Message`].
fn widen<F>(event: Event<'_, F::Message<'_>, Error>) -> Ev
where
    F: FrameRules<Error = Error>,
    F::Owned: Into<Message>,
{
    let event: OwnedEvent<F> = owned_event::<F>(event);
    widen_owned(event)
}

/// An owned event with its message as a [`Message`].
fn widen_owned<M: Into<Message>>(event: Result<OwnedFrame<M>, Rejected<Error>>) -> Ev {
    event.map(|f| OwnedFrame {
        offset: f.offset,
        len: f.len,
        message: f.message.into(),
    })
}

macro_rules! each {
    ($self:expr, $d:ident => $body:expr) => {
        match $self {
            AnyDecoder::Host($d) => $body,
            AnyDecoder::Device($d) => $body,
            AnyDecoder::Both($d) => $body,
        }
    };
}

macro_rules! each_event {
    ($self:expr, $d:ident => $body:expr) => {
        match $self {
            AnyDecoder::Host($d) => $body.map(widen::<Framing<Host>>),
            AnyDecoder::Device($d) => $body.map(widen::<Framing<Device>>),
            AnyDecoder::Both($d) => $body.map(widen::<Framing<Both>>),
        }
    };
}

impl AnyDecoder {
    /// A decoder with `framing`.
    pub fn new(framing: AnyFraming) -> Self {
        match framing {
            AnyFraming::Host(f) => AnyDecoder::Host(HostDecoder::new(f)),
            AnyFraming::Device(f) => AnyDecoder::Device(DeviceDecoder::new(f)),
            AnyFraming::Both(f) => AnyDecoder::Both(BothDecoder::new(f)),
        }
    }

    /// Every event `input` completes.
    pub fn feed(&mut self, input: &[u8]) -> std::vec::IntoIter<Ev> {
        let events: Vec<Ev> = each!(self, d => d.feed(input).map(widen_owned).collect());
        events.into_iter()
    }

    /// Every event at the end of the input.
    pub fn flush(&mut self) -> std::vec::IntoIter<Ev> {
        let events: Vec<Ev> = each!(self, d => d.flush().map(widen_owned).collect());
        events.into_iter()
    }

    /// One event from `input`, taking what it reads.
    pub fn decode(&mut self, input: &mut &[u8]) -> Option<Ev> {
        each_event!(self, d => d.decode(input))
    }

    /// One byte in.
    pub fn push(&mut self, byte: u8) -> Option<Ev> {
        each_event!(self, d => d.push(byte))
    }

    /// The next event among the buffered bytes.
    pub fn poll(&mut self) -> Option<Ev> {
        each_event!(self, d => d.poll())
    }

    /// Resolve the buffered candidate at the end of the input.
    pub fn finish(&mut self) -> Option<Ev> {
        each_event!(self, d => d.finish())
    }

    /// The counters.
    pub fn stats(&self) -> Stats {
        each!(self, d => d.stats())
    }

    /// Bytes buffered.
    pub fn buffered(&self) -> usize {
        each!(self, d => d.buffered())
    }
}
