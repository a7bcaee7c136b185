//! Runs the golden scenes on this target and prints one line per scene and a summary
//! (`hibi-scenes on TARGET: N scenes, M differ`); exits 0 when every scene matches its golden,
//! 1 otherwise. See `targets/run`.
#![cfg_attr(target_os = "none", no_std, no_main)]

use core::fmt::Write;

/// The target triple this was built for.
const TARGET: &str = env!("HIBI_TARGET");

/// Runs every scene, writing the report to `out`; true when all match.
#[cfg(not(hibi_small))]
fn scenes(out: &mut dyn Write) -> bool {
    let Some(mut memory) = hibi_scenes::Memory::take() else {
        return false;
    };
    matches!(hibi_scenes::check(&mut memory, TARGET, out), Ok(0))
}

/// The 64 KiB part: the 64 KiB scenes only, in their arena, each with its instruction count.
#[cfg(hibi_small)]
fn scenes(out: &mut dyn Write) -> bool {
    let Some(arena) = hibi_scenes::small_arena() else {
        return false;
    };
    let mut instructions = platform::meter(out);
    let meter: hibi_scenes::Meter<'_> = (&mut instructions, "instructions");
    matches!(hibi_scenes::check_small(arena, TARGET, out, Some(meter)), Ok(0))
}

/// Bytes of stack painted below the scenes' caller on the targets without a runtime that
/// paints it (all but Cortex-M): far more than the scenes need (about 32 KiB), and within the
/// stack of each (8 MiB on the host and under qemu-user, the top of 64 MiB of RAM on riscv32).
#[cfg(not(all(target_os = "none", target_arch = "arm")))]
const STACK_MEASURED: usize = 512 * 1024;

/// Runs the scenes with the stack below painted, and writes their stack peak.
#[cfg(not(all(target_os = "none", target_arch = "arm")))]
fn scenes_measured(out: &mut dyn Write) -> bool {
    // SAFETY: STACK_MEASURED bytes below this frame are this thread's stack, unused (see
    // STACK_MEASURED).
    let (ok, peak) = unsafe { hibi_scenes::stack::measured(STACK_MEASURED, || scenes(out)) };
    let _ = writeln!(out, "stack peak {peak} bytes (painted below the scenes' caller)");
    ok
}

#[cfg(not(target_os = "none"))]
fn main() {
    struct Stdout;
    impl Write for Stdout {
        fn write_str(&mut self, s: &str) -> core::fmt::Result {
            print!("{s}");
            Ok(())
        }
    }
    let ok = scenes_measured(&mut Stdout);
    std::process::exit(if ok { 0 } else { 1 });
}

/// Cortex-M (mps2-an386 or lm3s6965evb under qemu-system-arm): semihosting for output and
/// exit; the stack is painted at reset (cortex-m-rt's `paint-stack`) and its peak reported.
#[cfg(all(target_os = "none", target_arch = "arm"))]
mod platform {
    use core::fmt::Write;
    use cortex_m_rt::entry;
    use cortex_m_semihosting::{debug, hio};

    /// Semihosting stdout.
    struct Out(hio::HostStream);

    impl Write for Out {
        fn write_str(&mut self, s: &str) -> core::fmt::Result {
            self.0.write_str(s)
        }
    }

    unsafe extern "C" {
        static _stack_start: u32;
        static _stack_end: u32;
    }

    /// The deepest the stack has reached: painted words from its end up that are unchanged.
    fn stack_peak() -> usize {
        let (top, end) = (&raw const _stack_start as usize, &raw const _stack_end as usize);
        let mut at = end;
        // SAFETY: [end, top) is the stack region cortex-m-rt painted; reading it is sound.
        while at < top && unsafe { (at as *const u32).read_volatile() } == cortex_m_rt::STACK_PAINT_VALUE {
            at += 4;
        }
        top - at
    }

    #[entry]
    fn main() -> ! {
        let Ok(stdout) = hio::hstdout() else {
            debug::exit(debug::EXIT_FAILURE);
            loop {}
        };
        let mut out = Out(stdout);
        let ok = super::scenes(&mut out);
        let peak = stack_peak();
        let region = &raw const _stack_start as usize - &raw const _stack_end as usize;
        let _ = writeln!(out, "stack peak {peak} bytes of {region}");
        // A stack that reached the end of its region has run into the static memory below it.
        let fits = peak < region;
        if !fits {
            let _ = writeln!(out, "FAILED   the stack overflowed its {region} bytes");
        }
        debug::exit(if ok && fits { debug::EXIT_SUCCESS } else { debug::EXIT_FAILURE });
        loop {}
    }

    /// SysTick reloads (every 2^24 ticks), counted by its exception.
    #[cfg(hibi_small)]
    static WRAPS: core::sync::atomic::AtomicU32 = core::sync::atomic::AtomicU32::new(0);

    #[cfg(hibi_small)]
    #[cortex_m_rt::exception]
    fn SysTick() {
        WRAPS.fetch_add(1, core::sync::atomic::Ordering::Relaxed);
    }

    /// SysTick ticks since `meter` started it.
    #[cfg(hibi_small)]
    fn ticks() -> u64 {
        use core::sync::atomic::Ordering::Relaxed;
        loop {
            let wraps = WRAPS.load(Relaxed);
            let current = cortex_m::peripheral::SYST::get_current();
            if WRAPS.load(Relaxed) == wraps {
                return u64::from(wraps) * (1 << 24) + u64::from(0x00ff_ffff - current);
            }
        }
    }

    /// An instruction counter: SysTick on the core clock, which under QEMU's `-icount shift=0`
    /// advances with the instructions executed (1 ns of virtual time each), scaled by a
    /// calibration against a loop of known length (cortex-m 0.7.10's `delay(n)`: n + 1 times
    /// `subs` and `bne`, 2·(n + 1) instructions). Writes the calibration to `out`.
    #[cfg(hibi_small)]
    pub(super) fn meter(out: &mut dyn Write) -> impl FnMut() -> u64 + use<> {
        use cortex_m::peripheral::syst::SystClkSource;
        let Some(mut peripherals) = cortex_m::Peripherals::take() else {
            let _ = writeln!(out, "meter: the core peripherals are taken");
            debug::exit(debug::EXIT_FAILURE);
            loop {}
        };
        let syst = &mut peripherals.SYST;
        syst.set_clock_source(SystClkSource::Core);
        syst.set_reload(0x00ff_ffff);
        syst.clear_current();
        syst.enable_interrupt();
        syst.enable_counter();
        // Cleared, the counter reads 0 until its first tick reloads it.
        while cortex_m::peripheral::SYST::get_current() == 0 {}
        const LOOP: u32 = 20_000_000;
        let looped = 2 * (u64::from(LOOP) + 1);
        let t0 = ticks();
        cortex_m::asm::delay(LOOP);
        let t1 = ticks();
        if t1 <= t0 || t1 - t0 > looped {
            let _ = writeln!(out, "meter: SysTick does not count ({t0} then {t1} ticks)");
            debug::exit(debug::EXIT_FAILURE);
            loop {}
        }
        let per = t1 - t0;
        let _ = writeln!(out, "meter: SysTick, {per} ticks for a loop of {looped} instructions");
        move || ticks() * looped / per
    }

    #[panic_handler]
    fn panic(info: &core::panic::PanicInfo) -> ! {
        if let Ok(mut out) = hio::hstdout() {
            let _ = writeln!(out, "panic: {info}");
        }
        debug::exit(debug::EXIT_FAILURE);
        loop {}
    }
}

/// RISC-V (QEMU virt, `-bios none`): a start routine of our own, the 16550 UART for output,
/// the SiFive test device to exit.
#[cfg(all(target_os = "none", target_arch = "riscv32"))]
mod platform {
    use core::fmt::Write;

    core::arch::global_asm!(
        ".section .text.start, \"ax\"",
        ".global _start",
        "_start:",
        "  la sp, _stack_top",
        "  la t0, _bss_start",
        "  la t1, _bss_end",
        "1:",
        "  bgeu t0, t1, 2f",
        "  sw zero, 0(t0)",
        "  addi t0, t0, 4",
        "  j 1b",
        "2:",
        "  call {main}",
        "3:",
        "  j 3b",
        main = sym main,
    );

    const UART: *mut u8 = 0x1000_0000 as *mut u8;
    const TEST_DEVICE: *mut u32 = 0x10_0000 as *mut u32;

    struct Uart;

    impl Write for Uart {
        fn write_str(&mut self, s: &str) -> core::fmt::Result {
            for b in s.bytes() {
                // SAFETY: the virt machine's UART transmit register.
                unsafe { UART.write_volatile(b) };
            }
            Ok(())
        }
    }

    fn exit(code: u32) -> ! {
        // SAFETY: the virt machine's test device: 0x5555 passes, (code << 16) | 0x3333 fails.
        unsafe { TEST_DEVICE.write_volatile(if code == 0 { 0x5555 } else { (code << 16) | 0x3333 }) };
        loop {}
    }

    extern "C" fn main() -> ! {
        let ok = super::scenes_measured(&mut Uart);
        exit(if ok { 0 } else { 1 })
    }

    #[panic_handler]
    fn panic(info: &core::panic::PanicInfo) -> ! {
        let _ = writeln!(Uart, "panic: {info}");
        exit(1)
    }
}

/// AArch64 under qemu-user: a static Linux executable without libc (the `write` and
/// `exit_group` system calls).
#[cfg(all(target_os = "none", target_arch = "aarch64"))]
mod platform {
    use core::fmt::Write;

    core::arch::global_asm!(
        ".section .text._start, \"ax\"",
        ".global _start",
        "_start:",
        "  mov x29, #0",
        "  mov x30, #0",
        "  bl {main}",
        main = sym main,
    );

    struct Stdout;

    impl Write for Stdout {
        fn write_str(&mut self, s: &str) -> core::fmt::Result {
            let mut rest = s.as_bytes();
            while !rest.is_empty() {
                let written: isize;
                // SAFETY: write(1, ptr, len) reads only `rest`.
                unsafe {
                    core::arch::asm!("svc 0", in("x8") 64, inout("x0") 1isize => written,
                        in("x1") rest.as_ptr(), in("x2") rest.len(), options(nostack));
                }
                if written <= 0 {
                    return Err(core::fmt::Error);
                }
                rest = &rest[written as usize..];
            }
            Ok(())
        }
    }

    fn exit(code: i32) -> ! {
        // SAFETY: exit_group does not return.
        unsafe { core::arch::asm!("svc 0", in("x8") 94, in("x0") code as isize, options(noreturn, nostack)) }
    }

    extern "C" fn main() -> ! {
        let ok = super::scenes_measured(&mut Stdout);
        exit(if ok { 0 } else { 1 })
    }

    #[panic_handler]
    fn panic(info: &core::panic::PanicInfo) -> ! {
        let _ = writeln!(Stdout, "panic: {info}");
        exit(1)
    }
}
