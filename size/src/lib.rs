//! What every binary of the size report shares: a fake UART at a fixed
//! address (volatile reads and writes, so nothing is optimised away) and the
//! panic handler.
//!
//! Each binary is `no_main`: its `_start` is the entry the linker keeps, and
//! everything else it links is what the row costs. No runtime, no vector
//! table: the figures are the decoder's (or encoder's) and the few
//! instructions of the loop around it.
#![no_std]

use core::cell::UnsafeCell;

/// The data register of the fake UART.
const UART_DATA: *mut u32 = 0x4000_4404 as *mut u32;
/// The fake output register the binaries write what they decoded to.
const OUT: *mut u32 = 0x4000_4408 as *mut u32;

/// Read one byte from the UART.
#[inline(always)]
pub fn read_byte() -> u8 {
    // SAFETY: a fixed device address, as a PAC would read it; never
    // dereferenced on a host.
    unsafe { core::ptr::read_volatile(UART_DATA) as u8 }
}

/// Report a value (a decoded field, an encoded byte).
#[inline(always)]
pub fn out(value: u32) {
    // SAFETY: as `read_byte`.
    unsafe { core::ptr::write_volatile(OUT, value) }
}

/// A `static` the binary mutates from its single thread of execution: the
/// report reads the symbol's size from the ELF (the RAM row).
pub struct Static<T>(UnsafeCell<T>);

// SAFETY: the size-report binaries have one thread and no interrupts.
unsafe impl<T> Sync for Static<T> {}

impl<T> Static<T> {
    /// Wrap `value`.
    pub const fn new(value: T) -> Self {
        Static(UnsafeCell::new(value))
    }

    /// The value, for the binary's one thread.
    #[allow(clippy::mut_from_ref)]
    #[inline(always)]
    pub fn get(&self) -> &mut T {
        // SAFETY: one thread, and `_start` takes this reference once.
        unsafe { &mut *self.0.get() }
    }
}

/// A panic that stays reachable after optimisation links this handler and
/// core's panic functions; report.py scans each binary's symbols for them and
/// names what it finds.
#[cfg(not(test))]
#[panic_handler]
fn panic(_: &core::panic::PanicInfo) -> ! {
    loop {
        out(0xdead);
    }
}
