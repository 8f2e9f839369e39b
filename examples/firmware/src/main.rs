//! A firmware-shaped robowire example: an OmniTiles tile's command loop over
//! a UART, with no heap and no `std`.
//!
//! `robowire::io::embedded_io::PacketReader` decodes commands from any
//! `embedded_io::Read` (the UART's receive half) into a 16-byte buffer on the
//! stack; `PacketWriter` answers each command with a 53-byte telemetry frame
//! on any `embedded_io::Write`. Bad checksums, unknown ids and line noise are
//! skipped and counted by the decoder; a UART error (overrun, framing) is
//! reported and the loop goes on.
//!
//! The UART here is a minimal polled driver for the STM32F4 USART register
//! block (USART2); clock, pin and baud-rate setup are left out. On real
//! hardware use your HAL's UART: HALs implement `embedded_io::{Read, Write}`.
//!
//! ```sh
//! cd examples/firmware && cargo build --release   # target thumbv7em-none-eabihf
//! ```

#![no_std]
#![no_main]

use core::fmt;
use core::panic::PanicInfo;
use core::ptr::{read_volatile, write_volatile};
use core::sync::atomic::{AtomicU16, AtomicU32, AtomicU8, Ordering::Relaxed};

use cortex_m_rt::entry;
use robowire::io::embedded_io::{PacketReader, PacketWriter};
use robowire::omnitiles::{device_decoder, units, Command, Layout, Telemetry};

// The tile's state, shared with interrupt handlers that are not shown (the
// PWM timer reads the duties and targets, the ADC's DMA interrupt writes the
// positions). `#[no_mangle]` keeps them visible to those handlers and to a
// debugger.

/// Duty levels (0..=50) that the PWM timer applies.
#[no_mangle]
static DUTY: [AtomicU8; 2] = [AtomicU8::new(0), AtomicU8::new(0)];
/// Direction of each actuator: 0 brake, 1 extend, 2 retract.
#[no_mangle]
static DIRECTION: [AtomicU8; 2] = [AtomicU8::new(0), AtomicU8::new(0)];
/// Set-position targets in raw ADC units, or `u16::MAX` for none.
#[no_mangle]
static TARGET: [AtomicU16; 2] = [AtomicU16::new(u16::MAX), AtomicU16::new(u16::MAX)];
/// Positions (raw 0..=4095) kept up to date by the ADC's DMA interrupt.
#[no_mangle]
static POSITION: [AtomicU16; 2] = [AtomicU16::new(0), AtomicU16::new(0)];
/// UART errors seen.
#[no_mangle]
static UART_ERRORS: AtomicU32 = AtomicU32::new(0);

#[entry]
fn main() -> ! {
    let (uart_rx, uart_tx) = Usart::usart2().split();
    let mut rx_buf = [0u8; 16];
    let mut rx = PacketReader::new(uart_rx, device_decoder(), &mut rx_buf[..]);
    let mut tx = PacketWriter::<_, { Telemetry::MAX_LEN }>::new(uart_tx);

    loop {
        match rx.read_message() {
            Ok(Some(frame)) => {
                obey(frame.message);
                // Answer every command with the current state. A write can
                // only fail on a UART error: nothing to do but go on.
                let _ = tx.send(&telemetry());
            }
            // A UART has no end of input.
            Ok(None) => {}
            // Overrun or framing error: the decoder resyncs by itself.
            Err(_) => {
                UART_ERRORS.fetch_add(1, Relaxed);
            }
        }
    }
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

/// A polled USART in the STM32F4 register layout.
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

impl Usart {
    fn usart2() -> Self {
        Usart { base: 0x4000_4400 }
    }

    fn split(self) -> (UsartRx, UsartTx) {
        (UsartRx { base: self.base }, UsartTx { base: self.base })
    }
}

fn sr(base: usize) -> u32 {
    // SAFETY: the USART's status register; reading it has no side effect.
    unsafe { read_volatile(base as *const u32) }
}

fn read_dr(base: usize) -> u8 {
    // SAFETY: the data register; reading it takes the received byte.
    unsafe { read_volatile((base + 4) as *const u32) as u8 }
}

fn write_dr(base: usize, byte: u8) {
    // SAFETY: the data register; writing it sends the byte.
    unsafe { write_volatile((base + 4) as *mut u32, u32::from(byte)) }
}

/// The receive half.
struct UsartRx {
    base: usize,
}

/// The transmit half.
struct UsartTx {
    base: usize,
}

/// A receive error flagged by the USART.
#[derive(Debug, Clone, Copy)]
struct UsartError {
    status: u32,
}

impl fmt::Display for UsartError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "USART error, status {:#x}", self.status)
    }
}

impl core::error::Error for UsartError {}

impl embedded_io::Error for UsartError {
    fn kind(&self) -> embedded_io::ErrorKind {
        embedded_io::ErrorKind::Other
    }
}

impl embedded_io::ErrorType for UsartRx {
    type Error = UsartError;
}

impl embedded_io::ErrorType for UsartTx {
    type Error = UsartError;
}

impl embedded_io::Read for UsartRx {
    /// Block until a byte arrives, then take every byte that is ready.
    fn read(&mut self, buf: &mut [u8]) -> Result<usize, UsartError> {
        let mut n = 0;
        while n < buf.len() {
            let status = sr(self.base);
            if status & SR_ERRORS != 0 {
                if n > 0 {
                    break; // report it on the next read
                }
                // Reading SR then DR clears the error flags.
                let _ = read_dr(self.base);
                return Err(UsartError { status });
            }
            if status & SR_RXNE != 0 {
                buf[n] = read_dr(self.base);
                n += 1;
            } else if n > 0 {
                break;
            }
        }
        Ok(n)
    }
}

impl embedded_io::Write for UsartTx {
    fn write(&mut self, buf: &[u8]) -> Result<usize, UsartError> {
        for &byte in buf {
            while sr(self.base) & SR_TXE == 0 {}
            write_dr(self.base, byte);
        }
        Ok(buf.len())
    }

    fn flush(&mut self) -> Result<(), UsartError> {
        while sr(self.base) & SR_TC == 0 {}
        Ok(())
    }
}

#[panic_handler]
fn panic(_: &PanicInfo) -> ! {
    loop {
        core::hint::spin_loop();
    }
}
