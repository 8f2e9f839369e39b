//! A firmware-shaped robowire example: an OmniTiles tile that decodes its
//! commands in the UART's receive interrupt, with no heap and no `std`.
//!
//! The USART2 interrupt hands each received byte to a command decoder with
//! `push` and collects any further frames with `poll`; the decoder lives in a
//! `static` behind a `critical_section::Mutex<RefCell<…>>`, which is how an
//! interrupt handler and the main loop share state without `static mut`
//! (a hard error to take references to in edition 2024). Bad checksums,
//! unknown ids and line noise are skipped and counted by the decoder; a UART
//! error (overrun, framing) is counted and decoding goes on. The main loop
//! sleeps until a command asks for an answer, then writes a 53-byte telemetry
//! frame through `embedded_io::Write`.
//!
//! The UART is a minimal driver for the STM32F4 USART register block (USART2)
//! and `vectors.rs` is the part of the vector table a peripheral access crate
//! would supply; clock, pin and baud-rate setup are left out. On real hardware
//! use your PAC's `interrupt` and your HAL's UART (HALs implement
//! `embedded_io::{Read, Write}`).
//!
//! ```sh
//! cd examples/firmware && cargo build --release   # target thumbv7em-none-eabihf
//! ```

#![no_std]
#![no_main]

mod vectors;

use core::cell::RefCell;
use core::fmt;
use core::panic::PanicInfo;
use core::ptr::{read_volatile, write_volatile};
use core::sync::atomic::{AtomicBool, AtomicU8, AtomicU16, AtomicU32, Ordering::Relaxed};

use cortex_m::peripheral::NVIC;
use cortex_m_rt::{entry, interrupt};
use critical_section::Mutex;
use embedded_io::Write;
use robowire::omnitiles::{Command, DEVICE_BUFFER, Device, Framing, Layout, Telemetry, units};
use robowire::{Encode, StreamDecoder};

use vectors::interrupt;

/// A firmware-sized command decoder: the 14-byte buffer its framing needs
/// (`DEVICE_BUFFER`) and `u32` counters, 64 bytes of RAM in all.
type CommandDecoder = StreamDecoder<Framing<Device>, DEVICE_BUFFER, u32>;

/// The command decoder, fed by the USART2 interrupt one byte at a time.
/// `const fn` construction: no initialisation code, no `Option`.
static DECODER: Mutex<RefCell<CommandDecoder>> =
    Mutex::new(RefCell::new(StreamDecoder::new(Framing::new())));

// The tile's state, shared with handlers that are not shown (the PWM timer
// reads the duties and targets, the ADC's DMA interrupt writes the positions).
// `#[unsafe(no_mangle)]` keeps them visible to a debugger.

/// Duty levels (0..=50) that the PWM timer applies.
#[unsafe(no_mangle)]
static DUTY: [AtomicU8; 2] = [AtomicU8::new(0), AtomicU8::new(0)];
/// Direction of each actuator: 0 brake, 1 extend, 2 retract.
#[unsafe(no_mangle)]
static DIRECTION: [AtomicU8; 2] = [AtomicU8::new(0), AtomicU8::new(0)];
/// Set-position targets in raw ADC units, or `u16::MAX` for none.
#[unsafe(no_mangle)]
static TARGET: [AtomicU16; 2] = [AtomicU16::new(u16::MAX), AtomicU16::new(u16::MAX)];
/// Positions (raw 0..=4095) kept up to date by the ADC's DMA interrupt.
#[unsafe(no_mangle)]
static POSITION: [AtomicU16; 2] = [AtomicU16::new(0), AtomicU16::new(0)];
/// UART errors seen.
#[unsafe(no_mangle)]
static UART_ERRORS: AtomicU32 = AtomicU32::new(0);
/// Set by the interrupt when a command arrived: the main loop answers it.
static ANSWER: AtomicBool = AtomicBool::new(false);

#[interrupt]
fn USART2() {
    let usart = Usart::usart2();
    let status = usart.status();
    if status & SR_ERRORS != 0 {
        // Reading SR then DR clears the error flags; the byte is lost and the
        // decoder resyncs by itself.
        let _ = usart.read_data();
        UART_ERRORS.fetch_add(1, Relaxed);
        return;
    }
    if status & SR_RXNE == 0 {
        return;
    }
    let byte = usart.read_data();
    critical_section::with(|cs| {
        // Nothing else borrows the decoder inside a critical section;
        // `try_borrow_mut` says so without linking a panic path.
        let Ok(mut decoder) = DECODER.borrow(cs).try_borrow_mut() else {
            return;
        };
        if let Some(Ok(frame)) = decoder.push(byte) {
            on_command(frame.message);
        }
        // A rejection can reveal frames among the bytes already buffered.
        while let Some(event) = decoder.poll() {
            if let Ok(frame) = event {
                on_command(frame.message);
            }
        }
    });
}

fn on_command(command: Command) {
    obey(command);
    ANSWER.store(true, Relaxed);
}

#[entry]
fn main() -> ! {
    let usart = Usart::usart2();
    usart.listen_rx();
    // SAFETY: the handler and everything it touches are ready; unmasking an
    // interrupt cannot break a critical section in progress here.
    unsafe { NVIC::unmask(interrupt::USART2) };
    let mut uart_tx = usart.tx();

    loop {
        if ANSWER.swap(false, Relaxed) {
            // Answer with the current state. Encoding a well-formed telemetry
            // value cannot fail; a write fails only on a UART error.
            let mut frame = [0u8; Telemetry::MAX_LEN];
            if let Ok(n) = telemetry().encode(&mut frame) {
                let _ = uart_tx.write_all(&frame[..n]);
            }
        }
        // Sleep until the next interrupt. Checking with interrupts masked
        // closes the gap between the check and `wfi`: a pending interrupt
        // still wakes the core, and runs once the critical section ends.
        critical_section::with(|_| {
            if !ANSWER.load(Relaxed) {
                cortex_m::asm::wfi();
            }
        });
    }
}

/// Link-quality counters, for a debugger or a status command.
#[allow(dead_code)]
fn link_stats() -> robowire::Stats<u32> {
    critical_section::with(|cs| DECODER.borrow(cs).try_borrow().map(|d| d.stats()))
        .unwrap_or_default()
}

fn obey(command: Command) {
    let (motor, direction, duty, target) = match command {
        Command::Extend { motor, speed } => (motor, 1, units::speed_to_duty(speed), None),
        Command::Retract { motor, speed } => (motor, 2, units::speed_to_duty(speed), None),
        Command::Brake { motor } => (motor, 0, 0, None),
        Command::SetPosition { motor, position } => {
            let mm = units::position_target_mm(motor, position);
            let raw = mm / motor.stroke_mm() * f32::from(units::ADC_FULL_SCALE);
            (motor, 0, 0, Some(raw as u16))
        }
        // Ping needs no answer beyond telemetry; this tile has no base.
        _ => return,
    };
    let i = motor as usize;
    TARGET[i].store(target.unwrap_or(u16::MAX), Relaxed);
    DIRECTION[i].store(direction, Relaxed);
    DUTY[i].store(duty, Relaxed);
}

fn telemetry() -> Telemetry {
    let m1 = POSITION[0].load(Relaxed);
    let m2 = POSITION[1].load(Relaxed);
    Telemetry {
        m1_pos: Some(m1),
        m2_pos: Some(m2),
        m1_adcs: Some([m1; 4]),
        m2_adcs: Some([m2; 2]),
        ..Telemetry::empty(Layout::Ble53)
    }
}

/// The STM32F4 USART2 register block (clock, pins and baud rate set up elsewhere).
struct Usart {
    base: usize,
}

/// Status register bits.
const SR_PE: u32 = 1 << 0;
const SR_FE: u32 = 1 << 1;
const SR_NF: u32 = 1 << 2;
const SR_ORE: u32 = 1 << 3;
const SR_RXNE: u32 = 1 << 5;
const SR_TC: u32 = 1 << 6;
const SR_TXE: u32 = 1 << 7;
const SR_ERRORS: u32 = SR_PE | SR_FE | SR_NF | SR_ORE;
/// Control register 1: receive-not-empty interrupt enable.
const CR1_RXNEIE: u32 = 1 << 5;

impl Usart {
    const fn usart2() -> Self {
        Usart { base: 0x4000_4400 }
    }

    fn status(&self) -> u32 {
        // SAFETY: the USART's status register; reading it has no side effect.
        unsafe { read_volatile(self.base as *const u32) }
    }

    fn read_data(&self) -> u8 {
        // SAFETY: the data register; reading it takes the received byte.
        unsafe { read_volatile((self.base + 4) as *const u32) as u8 }
    }

    /// Enable the receive interrupt (RXNEIE; it also fires on an overrun).
    fn listen_rx(&self) {
        let cr1 = (self.base + 0x0c) as *mut u32;
        // SAFETY: control register 1; setting RXNEIE only enables the interrupt.
        unsafe { write_volatile(cr1, read_volatile(cr1) | CR1_RXNEIE) }
    }

    fn write_data(&self, byte: u8) {
        // SAFETY: the data register; writing it sends the byte.
        unsafe { write_volatile((self.base + 4) as *mut u32, u32::from(byte)) }
    }

    /// The transmit half.
    const fn tx(self) -> UsartTx {
        UsartTx(self)
    }
}

/// The transmit half, polled.
struct UsartTx(Usart);

/// A transmit error (this polled driver has none, but the trait wants a type).
#[derive(Debug, Clone, Copy)]
enum UsartError {}

impl fmt::Display for UsartError {
    fn fmt(&self, _: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {}
    }
}

impl core::error::Error for UsartError {}

impl embedded_io::Error for UsartError {
    fn kind(&self) -> embedded_io::ErrorKind {
        match *self {}
    }
}

impl embedded_io::ErrorType for UsartTx {
    type Error = UsartError;
}

impl embedded_io::Write for UsartTx {
    fn write(&mut self, buf: &[u8]) -> Result<usize, UsartError> {
        for &byte in buf {
            while self.0.status() & SR_TXE == 0 {}
            self.0.write_data(byte);
        }
        Ok(buf.len())
    }

    fn flush(&mut self) -> Result<(), UsartError> {
        while self.0.status() & SR_TC == 0 {}
        Ok(())
    }
}

#[panic_handler]
fn panic(_: &PanicInfo) -> ! {
    loop {
        core::hint::spin_loop();
    }
}
