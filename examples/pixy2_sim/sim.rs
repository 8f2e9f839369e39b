//! A simulated Pixy2 on an in-memory SPI link, and a host that talks to it.
//!
//! The device runs on its own thread. It decodes requests with the device
//! decoder, dispatches them as the firmware does (spec §4.0: boot, programs,
//! automatic program switches, busy when no new camera frame) and answers in
//! the checksum form, after SPI idle filler and sometimes with the first sync
//! byte doubled (§7.1). The host, on the calling thread, writes requests and
//! polls for answers, pairs each answer with its request through
//! [`Query::answer`], and retries what a host has to retry: a busy device, a
//! program switch, a request or answer lost to line noise.
//!
//! Everything is a pure function of the seeds (integer arithmetic, one
//! request at a time), so the conversation is the same on every run:
//! [`Outcome::capture`] is committed as `tests/data/pixy2_conversation.hex`.

use std::collections::VecDeque;
use std::fmt::Write as _;
use std::sync::mpsc::{self, Receiver, Sender};
use std::thread;

use robowire::pixy2::{
    self, Barcode, Block, BlocksBuf, ChangeProg, DeviceError, Envelope, Error, FeaturesBuf, Form,
    GetBlocks, GetFeatures, GetFps, GetResolution, GetRgb, GetVersion, HostDecoder, Intersection,
    IntersectionLine, PairError, ProgName, ProgSwitch, Query, Request, Resolution, ResponseBuf,
    ReverseVector, Rgb, SetCameraBrightness, SetDefaultTurn, SetLamp, SetLed, SetNextTurn,
    SetServos, Vector, Version, INTERSECTION_SLOTS, MAX_BLOCKS,
};
use robowire::{Encode, Rejected};

/// What the SPI slave clocks out when it has nothing to send (spec §7.1).
pub const FILLER: u8 = 0x01;
/// Bytes the host clocks in per poll.
const POLL: usize = 16;
/// Seeds of the device's timing (filler, doubled sync byte) and of the
/// line noise.
const DEVICE_SEED: u64 = 0x5049_5859_3200_0001;
const NOISE_SEED: u64 = 0x5049_5859_3200_0002;

/// xorshift64: small and seeded.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        let mut x = self.0;
        x ^= x << 13;
        x ^= x >> 7;
        x ^= x << 17;
        self.0 = x;
        x
    }

    fn below(&mut self, n: u64) -> u64 {
        self.next() % n
    }
}

/// A triangle wave: 0 up to `span` and back, one step per unit of `t`.
fn tri(t: u32, span: u32) -> u32 {
    let p = t % (2 * span);
    if p <= span {
        p
    } else {
        2 * span - p
    }
}

// ---------------------------------------------------------------- the link

/// One SPI transaction, host to device.
enum Transfer {
    /// The host clocks out a request; what comes back on MISO is filler.
    Write(Vec<u8>),
    /// The host clocks in this many bytes.
    Read(usize),
}

/// The host's end of the in-memory SPI link. It records every transaction
/// (what the host wrote, what it read) for the capture, and can flip a bit
/// on the wire to simulate line noise.
struct Link {
    to_device: Sender<Transfer>,
    from_device: Receiver<Vec<u8>>,
    transfers: Vec<Vec<u8>>,
    noise: Rng,
    glitch_write: bool,
    glitch_read: bool,
}

impl Link {
    fn write(&mut self, bytes: &[u8]) {
        let mut bytes = bytes.to_vec();
        if std::mem::take(&mut self.glitch_write) {
            // One bit of the last byte (a payload byte for any request that
            // has one) flips on its way.
            let last = bytes.len() - 1;
            bytes[last] ^= 1 << self.noise.below(8);
        }
        self.transfers.push(bytes.clone());
        self.to_device
            .send(Transfer::Write(bytes))
            .expect("the device thread runs until the link closes");
    }

    fn read(&mut self, n: usize) -> Vec<u8> {
        self.to_device
            .send(Transfer::Read(n))
            .expect("the device thread runs until the link closes");
        let mut bytes = self
            .from_device
            .recv()
            .expect("the device answers every read");
        if self.glitch_read {
            // Flip a bit of the first payload byte of the frame in this read.
            let start = bytes.windows(2).position(|w| w == [0xaf, 0xc1]);
            if let Some(at) = start.map(|s| s + 6).filter(|&at| at < bytes.len()) {
                bytes[at] ^= 1 << self.noise.below(8);
                self.glitch_read = false;
            }
        }
        self.transfers.push(bytes.clone());
        bytes
    }
}

// ---------------------------------------------------------------- the device

/// The firmware's programs, in the order the device numbers them.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Program {
    Ccc,
    Line,
    Video,
    PanTilt,
}

const PROGRAMS: [(&[u8], Program); 4] = [
    (b"color_connected_components", Program::Ccc),
    (b"line_tracking", Program::Line),
    (b"video", Program::Video),
    (b"pan_tilt_demo", Program::PanTilt),
];

impl Program {
    /// The program a request type > 0x1f belongs to.
    fn owner(packet_type: u8) -> Option<Program> {
        match packet_type {
            0x20..=0x2f => Some(Program::Ccc),
            0x30..=0x3f => Some(Program::Line),
            0x70..=0x7f => Some(Program::Video),
            _ => None,
        }
    }

    fn claims(self, packet_type: u8) -> bool {
        match Program::owner(packet_type) {
            // pan_tilt_demo tracks blocks too.
            Some(Program::Ccc) => matches!(self, Program::Ccc | Program::PanTilt),
            owner => owner == Some(self),
        }
    }
}

/// Requests handled before getVersion stops answering busy.
const BOOT_TICKS: u32 = 1;
/// Requests a program switch takes.
const SWITCH_TICKS: u32 = 3;

/// The camera and its programs: state that answers requests.
struct Camera {
    /// Requests handled so far: the device's clock. A new camera frame
    /// comes every two requests.
    tick: u32,
    program: Program,
    /// A scheduled switch: the program and the tick it completes at.
    switch: Option<(Program, u32)>,
    last_blocks_frame: Option<u32>,
    last_features_frame: Option<u32>,
    /// reverseVector swaps the primary vector's ends.
    reversed: bool,
}

impl Camera {
    fn new() -> Self {
        Camera {
            tick: 0,
            program: Program::Ccc,
            switch: None,
            last_blocks_frame: None,
            last_features_frame: None,
            reversed: false,
        }
    }

    fn frame(&self) -> u32 {
        self.tick / 2
    }

    /// Answer one request, as the firmware dispatches it (spec §4.0).
    fn handle(&mut self, request: Request) -> ResponseBuf {
        use DeviceError::{Busy, General, InvalidRequest, ProgChanging};
        self.tick += 1;
        if let Some((target, done)) = self.switch {
            if self.tick >= done {
                self.program = target;
                self.switch = None;
            }
        }
        let ty = request.packet_type();
        if let Some(owner) = Program::owner(ty) {
            if self.switch.is_some() {
                return ResponseBuf::Error(ProgChanging);
            }
            if !self.program.claims(ty) {
                // Another program's request: switch automatically.
                self.switch = Some((owner, self.tick + SWITCH_TICKS));
                return ResponseBuf::Error(ProgChanging);
            }
        }
        let frame = self.frame();
        match request {
            Request::GetVersion(_) if self.tick <= BOOT_TICKS => ResponseBuf::Error(Busy),
            Request::GetVersion(_) => ResponseBuf::Version(Version {
                hardware: 0x2200,
                firmware_major: 3,
                firmware_minor: 0,
                firmware_build: 20,
                firmware_type: pixy2::FirmwareType::GENERAL,
            }),
            Request::GetResolution(_) if self.switch.is_some() => ResponseBuf::Error(ProgChanging),
            Request::GetResolution(_) => ResponseBuf::Resolution(match self.program {
                Program::Line => Resolution {
                    width: 79,
                    height: 52,
                },
                _ => Resolution {
                    width: 316,
                    height: 208,
                },
            }),
            Request::ChangeProg(ChangeProg(name)) => {
                let wanted = name.name();
                let Some(&(_, target)) = PROGRAMS.iter().find(|(n, _)| n.starts_with(wanted))
                else {
                    return ResponseBuf::Error(InvalidRequest);
                };
                match self.switch {
                    None if self.program == target => ResponseBuf::Result(1),
                    Some((pending, _)) if pending == target => ResponseBuf::Result(0),
                    _ => {
                        self.switch = Some((target, self.tick + SWITCH_TICKS));
                        ResponseBuf::Result(0)
                    }
                }
            }
            Request::GetFps(_) => ResponseBuf::Result(61),
            Request::SetCameraBrightness(_)
            | Request::SetServos(_)
            | Request::SetLed(_)
            | Request::SetLamp(_)
            | Request::SetMode(_)
            | Request::SetVector(_)
            | Request::SetNextTurn(_)
            | Request::SetDefaultTurn(_) => ResponseBuf::Result(0),
            Request::ReverseVector(_) => match scene::primary(frame, self.reversed) {
                Some(_) => {
                    self.reversed = !self.reversed;
                    ResponseBuf::Result(0)
                }
                None => ResponseBuf::Error(General),
            },
            // The camera refuses an empty signature map.
            Request::GetBlocks(GetBlocks { sigmap: 0, .. }) => ResponseBuf::Error(InvalidRequest),
            Request::GetBlocks(q) => {
                if self.last_blocks_frame == Some(frame) {
                    return ResponseBuf::Error(Busy);
                }
                self.last_blocks_frame = Some(frame);
                ResponseBuf::Blocks(scene::blocks(frame, q))
            }
            Request::GetFeatures(q) => {
                if self.last_features_frame == Some(frame) {
                    return ResponseBuf::Error(Busy);
                }
                self.last_features_frame = Some(frame);
                ResponseBuf::Features(scene::features(frame, q, self.reversed))
            }
            Request::GetRgb(GetRgb { x, y, saturate }) => {
                ResponseBuf::Result(scene::rgb(frame, x.min(315), y.min(207), saturate != 0))
            }
        }
    }
}

/// What the simulated camera sees, frame by frame.
mod scene {
    use super::*;

    /// A red ball (signature 1) bouncing around the frame, a small static
    /// signature-2 target, and a two-stripe colour code (signature 0o12)
    /// that comes and goes, turning as it does.
    pub fn all_blocks(frame: u32) -> Vec<Block> {
        let mut blocks = vec![
            ball(frame),
            Block {
                signature: 2,
                x: 60,
                y: 170,
                width: 10,
                height: 8,
                angle: 0,
                index: 1,
                age: frame.min(255) as u8,
            },
        ];
        let phase = frame % 8;
        if phase < 5 {
            blocks.push(Block {
                signature: 0o12,
                x: 220,
                y: 150 - 4 * phase as u16,
                width: 40,
                height: 20,
                angle: ((frame * 25) % 360) as i16 - 180,
                // A new track each time it reappears.
                index: (2 + frame / 8) as u8,
                age: phase as u8,
            });
        }
        blocks
    }

    pub fn ball(frame: u32) -> Block {
        Block {
            signature: 1,
            x: (40 + tri(frame * 9, 236)) as u16,
            y: (30 + tri(frame * 5, 148)) as u16,
            width: 24 + (frame % 3) as u16,
            height: 22 + (frame % 2) as u16,
            angle: 0,
            index: 0,
            age: frame.min(255) as u8,
        }
    }

    /// getBlocks: the requested signatures, largest first, at most
    /// `max_blocks` (and 18).
    pub fn blocks(frame: u32, q: GetBlocks) -> BlocksBuf {
        let mut blocks: Vec<Block> = all_blocks(frame)
            .into_iter()
            .filter(|b| q.wants(b.signature))
            .collect();
        blocks.sort_by_key(|b| std::cmp::Reverse(u32::from(b.width) * u32::from(b.height)));
        blocks.truncate(usize::from(q.max_blocks).min(MAX_BLOCKS));
        BlocksBuf::from_blocks(&blocks).expect("at most 18 blocks")
    }

    /// The line is lost from view on one frame of every five.
    const LOST_EVERY: u32 = 5;

    /// The line under the robot: tail at the bottom edge, head at the top,
    /// both drifting; `None` while it is out of view.
    pub fn primary(frame: u32, reversed: bool) -> Option<Vector> {
        if frame % LOST_EVERY == LOST_EVERY - 1 {
            return None;
        }
        let tail = (35 + tri(frame, 8)) as u8;
        let head = (35 + tri(frame * 2, 10)) as u8;
        let (x0, y0, x1, y1) = if reversed {
            (head, 0, tail, 51)
        } else {
            (tail, 51, head, 0)
        };
        Some(Vector {
            x0,
            y0,
            x1,
            y1,
            index: 3,
            flags: 0,
        })
    }

    /// An intersection, valid on three frames of every six.
    fn intersection(frame: u32) -> Option<Intersection> {
        if !matches!(frame % 6, 4 | 5 | 0) {
            return None;
        }
        let mut slots = [IntersectionLine::default(); INTERSECTION_SLOTS];
        // Ascending by angle, as the device sorts them.
        for (slot, (index, angle)) in slots.iter_mut().zip([(4, -90), (3, 0), (5, 90)]) {
            *slot = IntersectionLine {
                index,
                reserved: 0,
                angle,
            };
        }
        Some(Intersection {
            x: 40,
            y: 20,
            n: 3,
            reserved: 0,
            slots,
        })
    }

    /// Barcode 5 beside the line, visible except on one frame of every six.
    fn barcode(frame: u32) -> Option<Barcode> {
        (frame % 6 != 0).then_some(Barcode {
            x: 20,
            y: 30,
            flags: 0,
            code: 5,
        })
    }

    /// getFeatures (spec §4.4). Main mode: the primary vector (flag 0x04
    /// when the frame has an intersection), an intersection only on its first
    /// valid frame, a barcode only when newly validated. All mode: every
    /// tracked feature with its tracker state.
    pub fn features(frame: u32, q: GetFeatures, reversed: bool) -> FeaturesBuf {
        let mut vectors = Vec::new();
        let mut intersections = Vec::new();
        let mut barcodes = Vec::new();
        let crossing = intersection(frame);
        let main = q.scope == GetFeatures::MAIN;
        if let Some(mut v) = primary(frame, reversed) {
            if main && crossing.is_some() {
                v.flags = Vector::INTERSECTION_PRESENT;
            }
            vectors.push(v);
        }
        if !main {
            // A branch the tracker is still validating (state 2, leading).
            vectors.push(Vector {
                x0: 40,
                y0: 20,
                x1: 70,
                y1: 12,
                index: 5,
                flags: 2,
            });
        }
        if let Some(i) = crossing {
            if !main || intersection(frame.wrapping_sub(1)).is_none() {
                intersections.push(i);
            }
        }
        if let Some(b) = barcode(frame) {
            if !main || barcode(frame.wrapping_sub(1)).is_none() {
                barcodes.push(b);
            }
        }
        let wanted = |bit: u8| q.features & bit != 0;
        FeaturesBuf::from_parts(
            if wanted(GetFeatures::VECTORS) {
                &vectors
            } else {
                &[]
            },
            if wanted(GetFeatures::INTERSECTIONS) {
                &intersections
            } else {
                &[]
            },
            if wanted(GetFeatures::BARCODES) {
                &barcodes
            } else {
                &[]
            },
        )
        .expect("a few features fit in 255 bytes")
    }

    /// getRGB: the ball's red, the signature-2 target's green, a grey floor
    /// elsewhere; saturate scales the brightest channel to 255.
    pub fn rgb(frame: u32, x: u16, y: u16, saturate: bool) -> i32 {
        let on = |b: &Block| x.abs_diff(b.x) <= b.width / 2 && y.abs_diff(b.y) <= b.height / 2;
        let blocks = all_blocks(frame);
        let (r, g, bl) = match blocks.iter().find(|b| b.signature <= 2 && on(b)) {
            Some(b) if b.signature == 1 => (180, 40, 30),
            Some(_) => (30, 140, 60),
            None => (96, 96, 88),
        };
        let (r, g, bl) = if saturate {
            let max = u32::from(r.max(g).max(bl));
            let scale = |c: u8| (u32::from(c) * 255 / max) as u8;
            (scale(r), scale(g), scale(bl))
        } else {
            (r, g, bl)
        };
        Rgb { r, g, b: bl }.to_result()
    }
}

/// The simulated camera behind a decoder: bytes a host wrote in, the
/// frames it answers out. The SPI device thread and `--pty` both use it.
pub struct Responder {
    decoder: pixy2::DeviceDecoder,
    camera: Camera,
    /// What it answered and dropped.
    pub stats: DeviceStats,
}

impl Default for Responder {
    fn default() -> Self {
        Responder::new()
    }
}

impl Responder {
    /// A camera that has just booted.
    pub fn new() -> Self {
        Responder {
            decoder: pixy2::device_decoder(),
            camera: Camera::new(),
            stats: DeviceStats::default(),
        }
    }

    /// Take `bytes` from the host; call `answer` with each response frame
    /// (the checksum form), in order.
    pub fn feed(&mut self, bytes: &[u8], answer: &mut dyn FnMut(&[u8])) {
        let mut out = [0u8; pixy2::MAX_FRAME_LEN];
        let mut input = bytes;
        while let Some(event) = self.decoder.decode(&mut input) {
            let event = event.map(|frame| frame.message.body);
            let response = match event {
                Ok(request) => self.camera.handle(request),
                // What the device answers to requests it cannot take.
                Err(Rejected {
                    error: Error::BadLength { .. } | Error::Malformed { .. },
                    ..
                }) => ResponseBuf::Error(DeviceError::InvalidRequest),
                Err(Rejected {
                    error: Error::UnknownType { .. },
                    ..
                }) => ResponseBuf::Error(DeviceError::TypeUnsupported),
                // A bad checksum, more than 64 bytes, noise: no answer.
                Err(_) => {
                    self.stats.dropped += 1;
                    continue;
                }
            };
            self.stats.answered += 1;
            let n = response.encode(&mut out).expect("responses fit");
            answer(&out[..n]);
        }
    }
}

/// The device thread: decode what the host writes, queue the answers, and
/// clock them out (after filler) when the host reads.
fn device(transfers: Receiver<Transfer>, miso: Sender<Vec<u8>>) -> DeviceStats {
    let mut responder = Responder::new();
    let mut rng = Rng(DEVICE_SEED);
    let mut queue = VecDeque::new();
    for transfer in transfers {
        match transfer {
            Transfer::Write(bytes) => responder.feed(&bytes, &mut |frame| {
                // SPI latency: some filler first; and the FIFO workaround
                // sometimes clocks the first byte out twice.
                queue.extend(std::iter::repeat(FILLER).take(rng.below(3) as usize));
                if rng.below(4) == 0 {
                    queue.push_back(0xaf);
                }
                queue.extend(frame);
            }),
            Transfer::Read(n) => {
                let mut bytes: Vec<u8> = queue.drain(..n.min(queue.len())).collect();
                bytes.resize(n, FILLER);
                if miso.send(bytes).is_err() {
                    break;
                }
            }
        }
    }
    responder.stats
}

/// What the device counted.
#[derive(Debug, Default, Clone, Copy, PartialEq, Eq)]
pub struct DeviceStats {
    /// Requests (good or bad) it answered.
    pub answered: u32,
    /// Requests it dropped without an answer.
    pub dropped: u32,
}

// ---------------------------------------------------------------- the host

/// Why the host got no typed answer.
#[derive(Debug)]
enum AskError {
    /// The device refused, or the response does not answer the request.
    Pair(PairError),
    /// Nothing but filler came back.
    NoResponse,
}

/// What the host learned, for the example's output and for tests.
#[derive(Debug, Default)]
pub struct Learned {
    /// getVersion's answer.
    pub version: Option<Version>,
    /// Every getResolution answer, in order.
    pub resolutions: Vec<Resolution>,
    /// getFPS's answer.
    pub fps: Option<u32>,
    /// The ball (signature 1) at each getBlocks answer that had it.
    pub ball: Vec<(u16, u16)>,
    /// Blocks per getBlocks answer.
    pub blocks_per_frame: Vec<usize>,
    /// Every vector seen.
    pub vectors: Vec<Vector>,
    /// Angles of the lines of every intersection seen.
    pub intersections: Vec<Vec<i16>>,
    /// Barcodes seen.
    pub barcodes: Vec<u8>,
    /// reverseVector attempts: whether each found a primary vector.
    pub reversals: Vec<bool>,
    /// getRGB's answer.
    pub rgb: Option<Rgb>,
    /// Device errors answered to requests that do not exist or are malformed.
    pub refused: Vec<DeviceError>,
    /// Retries: busy (no new frame), program switching, no response.
    pub busy: u32,
    /// Retries after ERROR −6.
    pub prog_changing: u32,
    /// Retries after nothing came back.
    pub no_response: u32,
    /// Checksum failures the host decoder saw.
    pub checksum_failures: u64,
}

/// The host's side of the conversation.
struct Host<'r> {
    link: Link,
    decoder: HostDecoder,
    learned: Learned,
    report: &'r mut dyn FnMut(&str),
}

impl Host<'_> {
    fn say(&mut self, text: &str) {
        (self.report)(text);
    }

    /// Write a request and poll until a response decodes; hand it to
    /// `answer`. No response: two polls of nothing but filler.
    fn exchange<T>(
        &mut self,
        request: &[u8],
        answer: impl FnOnce(pixy2::Response<'_>) -> T,
    ) -> Option<T> {
        self.link.write(request);
        let mut idle = 0;
        while idle < 2 {
            let bytes = self.link.read(POLL);
            if bytes.iter().all(|&b| b == FILLER) && self.decoder.buffered() == 0 {
                idle += 1;
                continue;
            }
            let mut input = &bytes[..];
            while let Some(event) = self.decoder.decode(&mut input) {
                match event {
                    // The device speaks only when asked: this is the answer.
                    Ok(frame) => return Some(answer(frame.message.body)),
                    Err(rejected) => (self.report)(&format!("  line noise: {rejected}")),
                }
            }
        }
        None
    }

    /// Ask `query` in `form`, retrying what a host retries: busy, a program
    /// switch, no response. `f` turns the typed answer into what to keep.
    fn ask<Q: Query, T>(
        &mut self,
        query: Q,
        form: Form,
        f: impl Fn(Q::Answer<'_>) -> T,
    ) -> Result<T, AskError> {
        let mut bytes = [0u8; 72];
        let n = Envelope::new(form, query.request())
            .encode(&mut bytes)
            .expect("requests fit in 72 bytes");
        let name = spec_name(&query.request());
        for _ in 0..12 {
            let result = self.exchange(&bytes[..n], |r| query.answer(r).map(&f));
            match result {
                Some(Ok(value)) => return Ok(value),
                Some(Err(PairError::Device(DeviceError::Busy))) => {
                    self.learned.busy += 1;
                    self.say(&format!("  {name}: busy, asking again"));
                }
                Some(Err(PairError::Device(DeviceError::ProgChanging))) => {
                    self.learned.prog_changing += 1;
                    self.say(&format!("  {name}: program changing, asking again"));
                }
                Some(Err(e)) => return Err(AskError::Pair(e)),
                None => {
                    self.learned.no_response += 1;
                    self.say(&format!("  {name}: no response, sending it again"));
                }
            }
        }
        Err(AskError::NoResponse)
    }
}

/// A request's name in the spec.
fn spec_name(request: &Request) -> &'static str {
    match request {
        Request::ChangeProg(_) => "changeProg",
        Request::GetResolution(_) => "getResolution",
        Request::GetVersion(_) => "getVersion",
        Request::SetCameraBrightness(_) => "setCameraBrightness",
        Request::SetServos(_) => "setServos",
        Request::SetLed(_) => "setLED",
        Request::SetLamp(_) => "setLamp",
        Request::GetFps(_) => "getFPS",
        Request::GetBlocks(_) => "getBlocks",
        Request::GetFeatures(_) => "getFeatures",
        Request::SetMode(_) => "setMode",
        Request::SetVector(_) => "setVector",
        Request::SetNextTurn(_) => "setNextTurn",
        Request::SetDefaultTurn(_) => "setDefaultTurn",
        Request::ReverseVector(_) => "reverseVector",
        Request::GetRgb(_) => "getRGB",
    }
}

impl Host<'_> {
    /// Send bytes that are no valid request and report the device's answer.
    fn refused(&mut self, what: &str, request: &[u8]) {
        let answer = self.exchange(request, |r| r.to_owned());
        match answer {
            Some(ResponseBuf::Error(e)) => {
                self.learned.refused.push(e);
                self.say(&format!("{what}: {e}"));
            }
            other => self.say(&format!("{what}: unexpected answer {other:?}")),
        }
    }
}

/// Everything a run produced.
pub struct Outcome {
    /// The conversation as hex text, one SPI transaction per line (what the
    /// host wrote, what it read), for `robowire decode pixy2 --hex`.
    pub capture: String,
    /// What the host learned.
    pub learned: Learned,
    /// What the device counted.
    pub device: DeviceStats,
}

/// Run the whole conversation. Every line the host has to say goes to
/// `report` as it happens.
pub fn run(report: &mut dyn FnMut(&str)) -> Result<Outcome, String> {
    let (to_device, transfers) = mpsc::channel();
    let (miso, from_device) = mpsc::channel();
    let device = thread::spawn(move || device(transfers, miso));
    let mut host = Host {
        link: Link {
            to_device,
            from_device,
            transfers: Vec::new(),
            noise: Rng(NOISE_SEED),
            glitch_write: false,
            glitch_read: false,
        },
        // A serial host: the device always answers with a checksum.
        decoder: HostDecoder::new(pixy2::Framing::new().checksum_only()),
        learned: Learned::default(),
        report,
    };
    let result = conversation(&mut host);
    let Host {
        link,
        decoder,
        mut learned,
        ..
    } = host;
    learned.checksum_failures = decoder.stats().checksum_failures;
    let Link {
        transfers,
        to_device,
        ..
    } = link;
    // Closing the link ends the device thread.
    drop(to_device);
    let device = device
        .join()
        .map_err(|_| "the device thread panicked".to_owned())?;
    result.map_err(|e| match e {
        AskError::Pair(e) => format!("the host gave up: {e}"),
        AskError::NoResponse => "the host gave up: no response".to_owned(),
    })?;
    let mut capture = String::new();
    for transfer in &transfers {
        let line: Vec<String> = transfer.iter().map(|b| format!("{b:02x}")).collect();
        let _ = writeln!(capture, "{}", line.join(" "));
    }
    Ok(Outcome {
        capture,
        learned,
        device,
    })
}

/// The host's script: a few minutes of a robot's life, compressed.
fn conversation(host: &mut Host<'_>) -> Result<(), AskError> {
    use Form::{Checksum, NoChecksum};

    // Ping with getVersion until the device has booted.
    let v = host.ask(GetVersion, NoChecksum, |v| v)?;
    host.learned.version = Some(v);
    host.say(&format!(
        "version: hardware {:#06x}, firmware {}.{}.{} {}",
        v.hardware,
        v.firmware_major,
        v.firmware_minor,
        v.firmware_build,
        v.firmware_type.as_str().unwrap_or("?")
    ));
    let r = host.ask(GetResolution::default(), NoChecksum, |r| r)?;
    host.learned.resolutions.push(r);
    host.say(&format!("resolution: {} x {}", r.width, r.height));
    let fps = host.ask(GetFps, NoChecksum, |fps| fps)?;
    host.learned.fps = Some(fps);
    host.say(&format!("frames per second: {fps}"));

    // Actuators, with checksums: a flipped bit must not move a servo.
    host.ask(SetLamp::new(true, false), Checksum, |()| ())?;
    host.ask(SetLed { r: 0, g: 0, b: 255 }, Checksum, |()| ())?;
    host.ask(SetCameraBrightness(80), Checksum, |()| ())?;
    host.link.glitch_write = true;
    host.ask(
        SetServos {
            pan: 500,
            tilt: 650,
        },
        Checksum,
        |()| (),
    )?;
    host.say("lamp, LED, brightness and servos set");

    // Track the ball.
    for _ in 0..6 {
        let query = GetBlocks {
            sigmap: GetBlocks::ALL,
            max_blocks: 3,
        };
        let blocks: Vec<Block> = host.ask(query, NoChecksum, |b| b.iter().collect())?;
        let text: Vec<String> = blocks
            .iter()
            .map(|b| {
                let what = if b.is_color_code() {
                    format!("colour code {:#o} angle {}", b.signature, b.angle)
                } else {
                    format!("sig {}", b.signature)
                };
                format!(
                    "{what} at ({}, {}) {}x{} #{} age {}",
                    b.x, b.y, b.width, b.height, b.index, b.age
                )
            })
            .collect();
        host.learned.blocks_per_frame.push(blocks.len());
        if let Some(ball) = blocks.iter().find(|b| b.signature == 1) {
            host.learned.ball.push((ball.x, ball.y));
        }
        host.say(&format!("blocks: {}", text.join("; ")));
    }

    // An answer lost to line noise: the checksum catches it.
    host.link.glitch_read = true;
    let fps = host.ask(GetFps, NoChecksum, |fps| fps)?;
    host.say(&format!("frames per second, again: {fps}"));

    // Requests the device refuses.
    host.refused(
        "setServos with 3 bytes",
        &[0xae, 0xc1, 0x12, 0x03, 0xf4, 0x01, 0xf4],
    );

    // Switch to line tracking.
    // The device matches a prefix of the program name.
    let line = ChangeProg(ProgName::new("line").expect("4 bytes, no NUL"));
    loop {
        match host.ask(line, NoChecksum, |s| s)? {
            ProgSwitch::Running => break,
            ProgSwitch::Pending => host.say("  changeProg line: pending"),
        }
    }
    host.say("program: line_tracking");
    let r = host.ask(GetResolution::default(), NoChecksum, |r| r)?;
    host.learned.resolutions.push(r);
    host.say(&format!("resolution: {} x {}", r.width, r.height));
    host.refused("type 0x32", &[0xae, 0xc1, 0x32, 0x02, 0x00, 0x07]);
    host.ask(SetDefaultTurn(-90), NoChecksum, |()| ())?;

    // Follow the line.
    for i in 0..6 {
        if i == 1 {
            host.ask(SetNextTurn(90), NoChecksum, |()| ())?;
            host.say("next turn: left (90)");
        }
        if i == 1 || i == 4 {
            match host.ask(ReverseVector, NoChecksum, |()| ()) {
                Ok(()) => {
                    host.learned.reversals.push(true);
                    host.say("primary vector reversed");
                }
                // ERROR -1: the line is out of view on this frame.
                Err(AskError::Pair(PairError::Device(DeviceError::General))) => {
                    host.learned.reversals.push(false);
                    host.say("reverseVector: no primary vector to reverse");
                }
                Err(e) => return Err(e),
            }
        }
        let scope = if i == 3 {
            GetFeatures::ALL
        } else {
            GetFeatures::MAIN
        };
        let query = GetFeatures {
            scope,
            features: GetFeatures::ALL_FEATURES,
        };
        let (vectors, intersections, barcodes) = host.ask(query, NoChecksum, |f| {
            (
                f.vectors().collect::<Vec<_>>(),
                f.intersections().collect::<Vec<_>>(),
                f.barcodes().collect::<Vec<_>>(),
            )
        })?;
        let mut text = Vec::new();
        for v in &vectors {
            text.push(format!(
                "vector ({}, {}) -> ({}, {}) #{} flags {:#04x}",
                v.x0, v.y0, v.x1, v.y1, v.index, v.flags
            ));
        }
        for x in &intersections {
            let angles: Vec<i16> = x.lines().iter().map(|l| l.angle).collect();
            text.push(format!("intersection ({}, {}) lines {angles:?}", x.x, x.y));
            host.learned.intersections.push(angles);
        }
        for b in &barcodes {
            text.push(format!("barcode {} at ({}, {})", b.code, b.x, b.y));
            host.learned.barcodes.push(b.code);
        }
        let mode = if scope == GetFeatures::MAIN {
            "main"
        } else {
            "all"
        };
        host.say(&format!("features ({mode}): {}", text.join("; ")));
        host.learned.vectors.extend(vectors);
    }

    // getRGB belongs to the video program: the device switches by itself.
    let rgb = host.ask(GetRgb::new(60, 170, true), NoChecksum, |c| c)?;
    host.learned.rgb = Some(rgb);
    host.say(&format!(
        "colour of the signature-2 target at (60, 170), saturated: #{:02x}{:02x}{:02x}",
        rgb.r, rgb.g, rgb.b
    ));
    Ok(())
}
