//! A second Rust static library linked next to libhibi.a: its own copy of std, its own
//! allocator calls, threads and panics, and a name of its own.

/// Sums 1..=n on another thread and returns the sum plus the length of its decimal text,
/// plus 1 when `n` is 0: that panics, and this library's unwinder catches it.
#[unsafe(no_mangle)]
pub extern "C" fn second_work(n: u32) -> u64 {
    // Silent: the panic below is caught, and the test wants nothing on stderr.
    std::panic::set_hook(Box::new(|_| {}));
    let caught = std::panic::catch_unwind(|| {
        if n == 0 {
            panic!("n is zero");
        }
    });
    let sum = std::thread::spawn(move || (1..=u64::from(n)).sum::<u64>()).join().unwrap_or(0);
    let text = format!("{sum}");
    sum + text.len() as u64 + u64::from(caught.is_err())
}
