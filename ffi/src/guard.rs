//! The one guard every exported function runs in, and the checks of what C hands in.
//!
//! [`guard`] catches any panic so that none unwinds into C (which is undefined behaviour) and
//! turns it into `HIBI_ERROR_PANIC` or the function's neutral value. A panic inside a guard
//! prints nothing: the first guarded call installs a panic hook that stays silent while the
//! panicking thread is inside a guard and hands every other panic (the host's own, if it is
//! Rust) to the hook that was there before. The host's stderr is its own; the status is how
//! hibi reports. The pointer helpers turn NULL, misaligned and overflowing arguments into
//! statuses before anything is touched.

use core::cell::Cell;
use core::ffi::{CStr, c_char};
use core::mem::{align_of, size_of};
use std::panic::{AssertUnwindSafe, catch_unwind};
use std::sync::{Once, OnceLock};

use crate::status::{
    HIBI_ERROR_MISALIGNED, HIBI_ERROR_NULL_POINTER, HIBI_ERROR_PANIC, HIBI_ERROR_SIZE_OVERFLOW, HIBI_OK, hibi_status,
    message, refuse_argument,
};

/// What an exported function's body gives back, and what C sees instead if it panics.
pub trait Outcome {
    /// The C return type.
    type C;
    /// The value C sees on success.
    fn into_c(self) -> Self::C;
    /// The value C sees when the body panicked.
    fn on_panic() -> Self::C;
}

impl Outcome for Result<(), hibi_status> {
    type C = hibi_status;
    fn into_c(self) -> hibi_status {
        self.err().unwrap_or(HIBI_OK)
    }
    fn on_panic() -> hibi_status {
        HIBI_ERROR_PANIC
    }
}

impl Outcome for () {
    type C = ();
    fn into_c(self) {}
    fn on_panic() {}
}

impl Outcome for usize {
    type C = usize;
    fn into_c(self) -> usize {
        self
    }
    fn on_panic() -> usize {
        0
    }
}

impl Outcome for *const c_char {
    type C = *const c_char;
    fn into_c(self) -> *const c_char {
        self
    }
    fn on_panic() -> *const c_char {
        message(HIBI_ERROR_PANIC).as_ptr()
    }
}

std::thread_local! {
    /// How many guards this thread is inside (exported functions do not call each other,
    /// but counting keeps nesting sound).
    static GUARDED: Cell<u32> = const { Cell::new(0) };
}

/// A panic hook, as `std::panic::take_hook` hands it over.
type Hook = Box<dyn Fn(&std::panic::PanicHookInfo<'_>) + Sync + Send + 'static>;

/// The hook installed before hibi's, which gets every panic outside a guard.
static PREVIOUS: OnceLock<Hook> = OnceLock::new();

/// hibi's hook: silent inside a guard, the previous hook's outside.
fn silent_hook(info: &std::panic::PanicHookInfo<'_>) {
    // `try_with`: a panic while the thread's locals are being torn down is not ours.
    if GUARDED.try_with(Cell::get).unwrap_or(0) == 0
        && let Some(previous) = PREVIOUS.get()
    {
        previous(info);
    }
}

/// Installs, once per process, the hook that keeps panics inside a guard silent. It allocates
/// nothing: the hook is a plain function (a zero-sized box), and the previous hook is kept in
/// a static rather than captured in a boxed closure.
fn install_silent_hook() {
    static INSTALL: Once = Once::new();
    if std::thread::panicking() {
        return; // the hook cannot be swapped now (a call from a host's unwinding); later
    }
    INSTALL.call_once(|| {
        let _ = PREVIOUS.set(std::panic::take_hook());
        std::panic::set_hook(Box::new(silent_hook));
    });
}

/// Runs an exported function's body; no panic crosses into C, and none prints. The body
/// starts with no refused argument on record (see `hibi_error_argument`).
pub(crate) fn guard<T: Outcome>(body: impl FnOnce() -> T) -> T::C {
    crate::status::clear_argument();
    guard_query(body)
}

/// As [`guard`], keeping the refused argument on record: for the functions that report on
/// earlier calls (`hibi_status_string`, `hibi_error_argument`, `hibi_version`).
pub(crate) fn guard_query<T: Outcome>(body: impl FnOnce() -> T) -> T::C {
    install_silent_hook();
    // `try_with` (here and for the refused argument): a call from a thread-local destructor,
    // after this thread's locals are gone, must not panic outside `catch_unwind`.
    let _ = GUARDED.try_with(|g| g.set(g.get() + 1));
    let result = catch_unwind(AssertUnwindSafe(body));
    let _ = GUARDED.try_with(|g| g.set(g.get() - 1));
    match result {
        Ok(outcome) => outcome.into_c(),
        Err(_) => T::on_panic(),
    }
}

/// Checks that argument `name`, `ptr`, is non-null and aligned for `T`; on failure `name` is
/// put on record for `hibi_error_argument`.
pub(crate) fn check_pointer<T>(ptr: *const T, name: &'static CStr) -> Result<(), hibi_status> {
    if ptr.is_null() {
        Err(refuse_argument(name, HIBI_ERROR_NULL_POINTER))
    } else if !ptr.cast::<u8>().align_offset(align_of::<T>()).eq(&0) {
        Err(refuse_argument(name, HIBI_ERROR_MISALIGNED))
    } else {
        Ok(())
    }
}

/// The object behind a handle passed in by C.
///
/// # Safety
/// A non-null, aligned `ptr` must point to a live `T` that nothing else uses during the call.
pub(crate) unsafe fn object<'a, T>(ptr: *mut T, name: &'static CStr) -> Result<&'a mut T, hibi_status> {
    check_pointer(ptr, name)?;
    // SAFETY: non-null and aligned (checked); liveness and exclusivity are the caller's contract.
    Ok(unsafe { &mut *ptr })
}

/// What a `const` pointer passed in by C points to (an object's handle, for the read-only
/// functions, or a struct of the caller's): a shared reference, so that threads may call the
/// read-only functions on one object at once.
///
/// # Safety
/// A non-null, aligned `ptr` must point to a live `T` that nothing mutates during the call.
pub(crate) unsafe fn object_ref<'a, T>(ptr: *const T, name: &'static CStr) -> Result<&'a T, hibi_status> {
    check_pointer(ptr, name)?;
    // SAFETY: non-null and aligned (checked); liveness and no concurrent mutation are the
    // caller's contract.
    Ok(unsafe { &*ptr })
}

/// The body of the `hibi_*_params_preset` functions: looks `name` up with `preset` and writes
/// its C form to `*out`; an unknown name gives `unknown` and writes nothing.
///
/// # Safety
/// `name` must be NULL or a NUL-terminated string; `out` NULL or writable.
pub(crate) unsafe fn write_preset<P, C>(
    name: *const core::ffi::c_char,
    out: *mut C,
    preset: impl FnOnce(&str) -> Option<P>,
    to_c: impl FnOnce(&P) -> C,
    unknown: hibi_status,
) -> Result<(), hibi_status> {
    check_pointer(name, c"name")?;
    check_pointer(out, c"out")?;
    // SAFETY: non-null (checked); NUL-terminated by the caller's contract.
    let name = unsafe { core::ffi::CStr::from_ptr(name) };
    let params = name.to_str().ok().and_then(preset).ok_or(unknown)?;
    // SAFETY: checked; the caller's contract.
    unsafe { write_out(out, c"out", to_c(&params)) }
}

/// Writes `value` through an out-parameter. Call it only once everything else succeeded, so
/// that nothing is written on failure.
///
/// # Safety
/// A non-null, aligned `ptr` must be valid for a write of `T`.
pub(crate) unsafe fn write_out<T>(ptr: *mut T, name: &'static CStr, value: T) -> Result<(), hibi_status> {
    check_pointer(ptr, name)?;
    // SAFETY: non-null and aligned (checked); validity is the caller's contract.
    unsafe { ptr.write(value) };
    Ok(())
}

/// Out-parameters of one call, checked together before the call does anything and written
/// together once it has succeeded, so that nothing is written on failure.
pub(crate) struct Outs<T, const N: usize>([(*mut T, &'static CStr); N]);

impl<T, const N: usize> Outs<T, N> {
    /// Checks every pointer (required: non-null and aligned).
    pub(crate) fn check(outs: [(*mut T, &'static CStr); N]) -> Result<Self, hibi_status> {
        outs.iter().try_for_each(|&(ptr, name)| check_pointer(ptr, name))?;
        Ok(Outs(outs))
    }

    /// Writes `values`, in order.
    ///
    /// # Safety
    /// Every pointer must be valid for a write of `T` (they were checked non-null and aligned).
    pub(crate) unsafe fn write(self, values: [T; N]) -> Result<(), hibi_status> {
        for ((ptr, _), value) in self.0.into_iter().zip(values) {
            // SAFETY: checked; the caller's contract.
            unsafe { ptr.write(value) };
        }
        Ok(())
    }
}

/// An optional out-parameter: NULL (not written) or checked as a required one.
pub(crate) struct Optional<T>(Option<Outs<T, 1>>);

impl<T> Optional<T> {
    /// Checks a non-null `ptr` as [`Outs::check`] does.
    pub(crate) fn check(ptr: *mut T, name: &'static CStr) -> Result<Self, hibi_status> {
        Ok(Optional(if ptr.is_null() { None } else { Some(Outs::check([(ptr, name)])?) }))
    }

    /// Writes `value` unless the pointer was NULL.
    ///
    /// # Safety
    /// As [`Outs::write`].
    pub(crate) unsafe fn write(self, value: T) -> Result<(), hibi_status> {
        // SAFETY: the caller's contract.
        self.0.map_or(Ok(()), |out| unsafe { out.write([value]) })
    }
}

/// The body of the queries that read an object and write one value: checks the object `ptr`
/// (argument `name`), reads it, and writes the value to the required `out`; nothing is written
/// when the read fails.
///
/// # Safety
/// As [`object_ref`] for `ptr`; `out` as [`write_out`].
pub(crate) unsafe fn query<T, O>(
    ptr: *const T,
    name: &'static CStr,
    (out, out_name): (*mut O, &'static CStr),
    read: impl FnOnce(&T) -> Result<O, hibi_status>,
) -> Result<(), hibi_status> {
    // SAFETY: the caller's contract.
    let object = unsafe { object_ref(ptr, name) }?;
    let value = read(object)?;
    // SAFETY: the caller's contract.
    unsafe { write_out(out, out_name, value) }
}

/// The body of the calls that change an object and report on it (step, impact): checks the
/// object `ptr` (argument `name`) and the optional report `out`, makes the change, and writes
/// its report unless `out` is NULL; nothing is written when the change fails.
///
/// # Safety
/// As [`object`] for `ptr`; `out` NULL or as [`Outs::write`].
pub(crate) unsafe fn update<T, O>(
    ptr: *mut T,
    name: &'static CStr,
    (out, out_name): (*mut O, &'static CStr),
    change: impl FnOnce(&mut T) -> Result<O, hibi_status>,
) -> Result<(), hibi_status> {
    // SAFETY: the caller's contract.
    let object = unsafe { object(ptr, name) }?;
    let out = Optional::check(out, out_name)?;
    let report = change(object)?;
    // SAFETY: checked; the caller's contract.
    unsafe { out.write(report) }
}

/// Checks caller buffer `name` of `len` elements of `T` at a non-empty `ptr`: non-null,
/// aligned, and its size in bytes fits `isize`.
fn check_buffer<T>(ptr: *const T, len: usize, name: &'static CStr) -> Result<(), hibi_status> {
    check_pointer(ptr, name)?;
    if len.checked_mul(size_of::<T>()).is_none_or(|bytes| bytes > isize::MAX as usize) {
        return Err(refuse_argument(name, HIBI_ERROR_SIZE_OVERFLOW));
    }
    Ok(())
}

/// The caller buffer `ptr[0..len]`; NULL is accepted for an empty buffer.
///
/// # Safety
/// A non-null, aligned `ptr` must be valid for reads and writes of `len` elements of `T`, not
/// aliased during the call.
pub(crate) unsafe fn buffer<'a, T>(ptr: *mut T, len: usize, name: &'static CStr) -> Result<&'a mut [T], hibi_status> {
    if len == 0 {
        return Ok(&mut []);
    }
    check_buffer(ptr, len, name)?;
    // SAFETY: non-null, aligned, size fits isize (checked); validity is the caller's contract.
    Ok(unsafe { core::slice::from_raw_parts_mut(ptr, len) })
}

/// `text`, which ends in NUL, as a C string (an argument's name, at compile time).
pub(crate) const fn c_name(text: &'static str) -> &'static CStr {
    match CStr::from_bytes_with_nul(text.as_bytes()) {
        Ok(name) => name,
        Err(_) => panic!("a C name ends in one NUL"),
    }
}

/// The read-only caller buffer `ptr[0..len]`; NULL is accepted for an empty buffer.
///
/// # Safety
/// A non-null, aligned `ptr` must be valid for reads of `len` elements of `T`, not written
/// during the call.
pub(crate) unsafe fn input<'a, T>(ptr: *const T, len: usize, name: &'static CStr) -> Result<&'a [T], hibi_status> {
    if len == 0 {
        return Ok(&[]);
    }
    check_buffer(ptr, len, name)?;
    // SAFETY: non-null, aligned, size fits isize (checked); validity is the caller's contract.
    Ok(unsafe { core::slice::from_raw_parts(ptr, len) })
}

/// Copies what a finished build holds from index `first` into `out[0..len]`, as many as
/// there are (none before the build is finished, or from `first` past the end), and writes how
/// many to `*written`.
///
/// # Safety
/// As the callers'.
pub(crate) unsafe fn copy_from<T: Copy>(
    all: &[T],
    first: usize,
    (out, len, name): (*mut T, usize, &'static CStr),
    written: *mut usize,
) -> Result<(), hibi_status> {
    check_pointer(written, c"written")?;
    // SAFETY: the caller's contract.
    let out = unsafe { buffer(out, len, name) }?;
    let from = all.get(first..).unwrap_or(&[]);
    let n = from.len().min(out.len());
    out[..n].copy_from_slice(&from[..n]);
    // SAFETY: checked; the caller's contract.
    unsafe { write_out(written, c"written", n) }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::status::HIBI_ERROR_BUFFER_TOO_SMALL;

    #[test]
    fn a_panic_becomes_a_status_and_never_unwinds() {
        let status = guard(|| -> Result<(), hibi_status> { panic!("deliberate") });
        assert_eq!(status, HIBI_ERROR_PANIC);
        assert_eq!(guard(|| -> usize { panic!("deliberate") }), 0);
        assert_eq!(guard(|| Err(HIBI_ERROR_BUFFER_TOO_SMALL)), HIBI_ERROR_BUFFER_TOO_SMALL);
        assert_eq!(guard(|| Ok(())), HIBI_OK);
    }

    /// The child half of the next test: panics inside a guard, and once outside.
    #[test]
    fn child_panics_inside_and_outside_a_guard() {
        if std::env::var_os("HIBI_GUARD_CHILD").is_none() {
            return;
        }
        let status = guard(|| -> Result<(), hibi_status> { panic!("inside-a-guard") });
        assert_eq!(status, HIBI_ERROR_PANIC);
        let outside = std::thread::spawn(|| panic!("outside-a-guard")).join();
        assert!(outside.is_err());
    }

    /// A panic caught at the C boundary prints nothing on the host's stderr, while a panic
    /// outside hibi's guards still reaches the previous hook.
    #[test]
    fn a_caught_panic_prints_nothing() {
        let exe = std::env::current_exe().expect("the test binary");
        let child = std::process::Command::new(exe)
            .args([
                "--exact",
                "guard::tests::child_panics_inside_and_outside_a_guard",
                "--nocapture",
                "--test-threads=1",
            ])
            .env("HIBI_GUARD_CHILD", "1")
            .output()
            .expect("run the child test");
        let stderr = String::from_utf8_lossy(&child.stderr);
        let stdout = String::from_utf8_lossy(&child.stdout);
        assert!(child.status.success(), "{stdout}\n{stderr}");
        assert!(stdout.contains("1 passed"), "the child test did not run:\n{stdout}");
        assert!(!stderr.contains("inside-a-guard"), "a guarded panic printed:\n{stderr}");
        assert!(stderr.contains("outside-a-guard"), "an unguarded panic was silenced:\n{stderr}");
    }

    #[test]
    fn pointer_checks_name_the_problem() {
        let mut words = [0u32; 4];
        let base = words.as_mut_ptr();
        assert_eq!(check_pointer(core::ptr::null::<u32>(), c"p"), Err(HIBI_ERROR_NULL_POINTER));
        assert_eq!(check_pointer(base.cast::<u8>().wrapping_add(1).cast::<u32>(), c"p"), Err(HIBI_ERROR_MISALIGNED));
        assert_eq!(check_pointer(base, c"p"), Ok(()));
        // SAFETY: a null pointer with length 0 is the empty buffer; no access happens.
        assert_eq!(unsafe { buffer(core::ptr::null_mut::<u32>(), 0, c"p") }.map(|b| b.len()), Ok(0));
        // SAFETY: the checks fail before any access.
        assert_eq!(unsafe { buffer(base, usize::MAX / 2, c"p") }.err(), Some(HIBI_ERROR_SIZE_OVERFLOW));
        // SAFETY: `words` is valid for 4 u32.
        assert_eq!(unsafe { buffer(base, 4, c"p") }.map(|b| b.len()), Ok(4));
        // SAFETY: as above, read only; the failing checks happen before any access.
        unsafe {
            assert_eq!(input(core::ptr::null::<u32>(), 0, c"p").map(<[u32]>::len), Ok(0));
            assert_eq!(input(core::ptr::null::<u32>(), 1, c"p").err(), Some(HIBI_ERROR_NULL_POINTER));
            assert_eq!(input(base.cast_const(), usize::MAX / 2, c"p").err(), Some(HIBI_ERROR_SIZE_OVERFLOW));
            assert_eq!(input(base.cast_const(), 4, c"p").map(<[u32]>::len), Ok(4));
        }
    }
}
