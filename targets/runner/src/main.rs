//! Runs the golden scenes on this target and prints one line per scene and a summary
//! (`hibi-scenes on TARGET: N scenes, M differ`); exits 0 when every scene matches its golden,
//! 1 otherwise. See `targets/run`.
#![cfg_attr(target_os = "none", no_std, no_main)]

use core::fmt::Write;

/// The target triple this was built for.
const TARGET: &str = env!("HIBI_TARGET");

/// Runs every scene, writing the report to `out`; true when all match.
fn scenes(out: &mut dyn Write) -> bool {
    let Some(mut memory) = hibi_scenes::Memory::take() else {
        return false;
    };
    matches!(hibi_scenes::check(&mut memory, TARGET, out), Ok(0))
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
    let ok = scenes(&mut Stdout);
    std::process::exit(if ok { 0 } else { 1 });
}

/// Cortex-M (mps2-an386 under qemu-system-arm): semihosting for output and exit; the stack
/// is painted at reset (cortex-m-rt's `paint-stack`) and its peak reported.
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
        let _ = writeln!(out, "stack peak {} bytes", stack_peak());
        debug::exit(if ok { debug::EXIT_SUCCESS } else { debug::EXIT_FAILURE });
        loop {}
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
        let ok = super::scenes(&mut Uart);
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
        let ok = super::scenes(&mut Stdout);
        exit(if ok { 0 } else { 1 })
    }

    #[panic_handler]
    fn panic(info: &core::panic::PanicInfo) -> ! {
        let _ = writeln!(Stdout, "panic: {info}");
        exit(1)
    }
}
