//! Helpers shared by the fuzz targets: value pickers that let the input choose every value
//! (NaN and infinities included) while keeping sizes small, sentinel-filled caller buffers,
//! and the C contract every call must keep.
//!
//! Every target drives hibi through its C ABI (`extern "C"` functions of the `hibi` crate)
//! exactly as a C caller would: pointers, lengths, statuses.

use core::ffi::CStr;

use arbitrary::{Result, Unstructured};
use hibi::*;

/// The byte every caller buffer is filled with before a call.
pub const SENTINEL: u8 = 0xA5;

/// The most bytes an object may need for the targets to create it: larger parameter sets are
/// only validated (`*_memory_size`), so that each execution stays fast.
pub const MAX_OBJECT_BYTES: usize = 1 << 20;

/// The most work units the step calls of one execution may do in all (the budgets themselves
/// are arbitrary; the targets stop stepping once this much work is done).
pub const MAX_WORK: u64 = 1 << 17;

/// The most pixels a render of one execution may draw.
pub const MAX_PIXELS: usize = 64 * 64;

thread_local! {
    /// The params of the latest `create`, for the messages of failed checks.
    pub static LAST: core::cell::RefCell<String> = const { core::cell::RefCell::new(String::new()) };
}

/// Checks what every call must keep: no panic reached the boundary, the status has a
/// message, and a pointer refusal names its argument. Returns whether the call succeeded.
pub fn check(status: hibi_status) -> bool {
    if status == HIBI_ERROR_PANIC {
        eprintln!("a panic; the last params were {}", LAST.with(|l| l.borrow().clone()));
    }
    assert_ne!(status, HIBI_ERROR_PANIC, "a panic reached the C boundary");
    // SAFETY: `hibi_status_string` and `hibi_error_argument` return static C strings.
    let message = unsafe { CStr::from_ptr(hibi_status_string(status)) };
    assert!(!message.is_empty());
    let argument = unsafe { CStr::from_ptr(hibi_error_argument()) };
    match status {
        HIBI_ERROR_NULL_POINTER | HIBI_ERROR_MISALIGNED | HIBI_ERROR_SIZE_OVERFLOW => {
            if argument.is_empty() {
                eprintln!(
                    "status {status} names no argument; the last params were {}",
                    LAST.with(|l| l.borrow().clone())
                );
            }
            assert!(!argument.is_empty(), "status {status} names no argument")
        }
        HIBI_OK => assert!(argument.is_empty(), "a success names argument {argument:?}"),
        _ => {}
    }
    status == HIBI_OK
}

/// A float from the input: usually `default`, else a special value (NaN, ±inf, 0, −0, huge,
/// tiny, subnormal, the neighbours of 1), a nearby value, or any bit pattern.
pub fn float(u: &mut Unstructured, default: f32) -> Result<f32> {
    const SPECIAL: [f32; 16] = [
        f32::NAN,
        f32::INFINITY,
        f32::NEG_INFINITY,
        0.0,
        -0.0,
        1.0,
        -1.0,
        f32::MIN_POSITIVE,
        1e-45,
        f32::MAX,
        f32::MIN,
        1e30,
        1e-30,
        0.999_999_94,
        1.000_000_1,
        0.5,
    ];
    Ok(match u.int_in_range(0u8..=15)? {
        0..=8 => default,
        9 | 10 => SPECIAL[usize::from(u.int_in_range(0u8..=15)?)],
        11 | 12 => default * f32::from(u.int_in_range(-8i8..=8)?) / 4.0,
        13 => default * (1.0 + f32::from(u.int_in_range(-128i8..=127)?) / 1024.0),
        _ => f32::from_bits(u.arbitrary()?),
    })
}

/// A count from the input: usually in `range`, sometimes any `u32`.
pub fn count(u: &mut Unstructured, range: core::ops::RangeInclusive<u32>) -> Result<u32> {
    Ok(if u.ratio(1u8, 16)? { u.arbitrary()? } else { u.int_in_range(range)? })
}

/// An enumeration value: usually one of `0..values`, sometimes any `u32`.
pub fn enumeration(u: &mut Unstructured, values: u32) -> Result<u32> {
    count(u, 0..=values - 1)
}

/// A work budget: 0, 1, small, or any `u64`.
pub fn budget(u: &mut Unstructured) -> Result<u64> {
    Ok(match u.int_in_range(0u8..=7)? {
        0 => 0,
        1 => 1,
        2 => u64::MAX,
        3..=5 => u64::from(u.arbitrary::<u16>()?),
        _ => u.arbitrary()?,
    })
}

/// A buffer length around `need` (the length the call needs): exact, a few short or long,
/// zero, or any length up to `limit`.
pub fn length(u: &mut Unstructured, need: usize, limit: usize) -> Result<usize> {
    Ok(match u.int_in_range(0u8..=7)? {
        0..=3 => need,
        4 => need.saturating_sub(usize::from(u.int_in_range(1u8..=3)?)),
        5 => need + usize::from(u.int_in_range(1u8..=3)?),
        6 => 0,
        _ => u.int_in_range(0..=limit.max(need))?,
    }
    .min(limit.max(need)))
}

/// A caller buffer of `len` elements of `size` bytes, filled with [`SENTINEL`], at a byte
/// offset (usually 0, sometimes misaligned) or NULL, with guard bytes after it.
pub struct Buffer {
    words: Vec<u64>,
    offset: usize,
    /// Elements the call is told the buffer holds.
    pub len: usize,
    size: usize,
    null: bool,
}

impl Buffer {
    /// A buffer whose length, offset and NULL-ness the input chooses around `need` elements.
    pub fn pick(u: &mut Unstructured, need: usize, limit: usize, size: usize) -> Result<Buffer> {
        let len = length(u, need, limit)?;
        let null = u.ratio(1u8, 32)?;
        let offset = if u.ratio(1u8, 16)? { usize::from(u.int_in_range(1u8..=7)?) } else { 0 };
        Ok(Buffer::new(len, size, offset, null))
    }

    /// A buffer of `len` elements of `size` bytes at byte `offset`, or NULL.
    pub fn new(len: usize, size: usize, offset: usize, null: bool) -> Buffer {
        let bytes = offset + len * size + 16;
        let mut words = vec![0u64; bytes.div_ceil(8)];
        words.iter_mut().for_each(|w| *w = u64::from_ne_bytes([SENTINEL; 8]));
        Buffer { words, offset, len, size, null }
    }

    /// The pointer to pass.
    pub fn ptr<T>(&mut self) -> *mut T {
        if self.null {
            core::ptr::null_mut()
        } else {
            // SAFETY: `offset` is within the allocation.
            unsafe { self.words.as_mut_ptr().cast::<u8>().add(self.offset).cast() }
        }
    }

    /// Whether the pointer is NULL.
    pub fn is_null(&self) -> bool {
        self.null
    }

    /// Whether a call needing `need` elements aligned to `align` may accept this buffer, and
    /// whether it must (a misaligned or NULL pointer with length 0 may go either way).
    pub fn fits(&self, need: usize, align: usize) -> (bool, bool) {
        let long = self.len >= need;
        let possible = long && (self.len == 0 || (!self.null && !self.misaligned(align)));
        let required = long && !self.null && !self.misaligned(align);
        (possible, required)
    }

    /// Whether the pointer is misaligned for `align`.
    pub fn misaligned(&self, align: usize) -> bool {
        !self.null && self.offset % align != 0
    }

    fn bytes(&self) -> &[u8] {
        // SAFETY: plain bytes of the allocation.
        unsafe { core::slice::from_raw_parts(self.words.as_ptr().cast::<u8>(), self.words.len() * 8) }
    }

    /// Whether no byte was written.
    pub fn untouched(&self) -> bool {
        self.bytes().iter().all(|&b| b == SENTINEL)
    }

    /// Whether no byte outside the first `written` elements was written.
    pub fn untouched_past(&self, written: usize) -> bool {
        assert!(written <= self.len, "{written} elements written into a buffer of {}", self.len);
        let b = self.bytes();
        b[..self.offset].iter().all(|&x| x == SENTINEL)
            && b[self.offset + written * self.size..].iter().all(|&x| x == SENTINEL)
    }

    /// Element `i`, read as `T`.
    pub fn get<T: Copy>(&self, i: usize) -> T {
        assert!(i < self.len && size_of::<T>() == self.size);
        // SAFETY: within the allocation; `read_unaligned` for the misaligned offsets.
        unsafe { self.words.as_ptr().cast::<u8>().add(self.offset + i * self.size).cast::<T>().read_unaligned() }
    }
}

/// Memory for a `*_create_in` call: `need` bytes aligned to `align`, with the length and
/// alignment the input chooses (usually exact and aligned). Returns the memory (keep it alive
/// while the object lives), the pointer and the length to pass.
pub fn caller_memory(
    u: &mut Unstructured,
    need: usize,
    align: usize,
) -> Result<(Vec<u64>, *mut core::ffi::c_void, usize)> {
    let len = length(u, need, need + 64)?;
    let offset = if u.ratio(1u8, 8)? { usize::from(u.int_in_range(1u8..=15)?) } else { 0 };
    let null = u.ratio(1u8, 32)?;
    let mut memory = vec![0u64; (offset + len).div_ceil(8) + align.div_ceil(8) + 1];
    let base = memory.as_mut_ptr().cast::<u8>();
    // SAFETY: within the allocation (it holds `align` bytes more than `offset + len`).
    let ptr = unsafe { base.add(base.align_offset(align)).add(offset) };
    let ptr = if null { core::ptr::null_mut() } else { ptr.cast() };
    Ok((memory, ptr, len))
}

/// Whether every float is finite.
pub fn finite(values: &[f32]) -> bool {
    values.iter().all(|v| v.is_finite())
}

/// A NUL-terminated name from the input: one of `known`, or any bytes.
pub fn name(u: &mut Unstructured, known: &[&str]) -> Result<Vec<u8>> {
    let mut bytes: Vec<u8> = if u.ratio(3u8, 4)? {
        u.choose(known)?.as_bytes().to_vec()
    } else {
        let raw: &[u8] = u.arbitrary()?;
        raw.iter().copied().filter(|&b| b != 0).take(64).collect()
    };
    bytes.push(0);
    Ok(bytes)
}

/// The mud presets.
pub const MUD_PRESETS: &[&str] =
    &["fig6a", "fig6b", "fig6c", "fig6d", "fig7a", "fig7b", "fig8", "fig9a", "fig9b", "fig9c", "fig10", "fig13"];
/// The glass presets.
pub const GLASS_PRESETS: &[&str] = &[
    "fig14a", "fig14b", "fig14c", "fig14d", "fig15a", "fig15b", "fig15c", "fig15d", "fig16a", "fig16b", "fig16c",
    "fig16d",
];
/// The skin presets.
pub const SKIN_PRESETS: &[&str] = &[
    "fig13a", "fig13b", "fig13c", "fig14a", "fig14b", "fig14c", "fig15a", "fig15b", "fig15c", "fig16a", "fig16b",
    "fig17a", "fig17b", "fig17c", "fig18a", "fig18b", "fig18c", "fig19a", "fig19b", "fig19c", "fig19d", "fig19e",
    "fig19f", "fig20",
];

/// Starting params: the defaults, or a preset the input names (a refused name must write
/// nothing; the defaults are used then).
fn start<P: Copy>(
    u: &mut Unstructured,
    known: &[&str],
    default: P,
    preset: unsafe extern "C" fn(*const core::ffi::c_char, *mut P) -> hibi_status,
    same: impl Fn(&P, &P) -> bool,
) -> Result<P> {
    if !u.ratio(1u8, 3)? {
        return Ok(default);
    }
    let name = name(u, known)?;
    let mut out = default;
    // SAFETY: `name` is NUL-terminated; `out` is writable.
    let status = unsafe { preset(name.as_ptr().cast(), &mut out) };
    if !check(status) {
        assert!(same(&out, &default), "a refused preset wrote its output");
    }
    Ok(out)
}

/// Equality of two params structs, field by field as `Debug` shows them (NaN equals NaN).
pub fn same<T: core::fmt::Debug>(a: &T, b: &T) -> bool {
    format!("{a:?}") == format!("{b:?}")
}

/// Mud params from the input: the defaults or a preset, small lattices, and any value in
/// every other field (the cookie too, rarely).
pub fn mud_params(u: &mut Unstructured) -> Result<hibi_mud_params> {
    let mut p = start(u, MUD_PRESETS, hibi_mud_params_default(), hibi_mud_params_preset, same)?;
    if u.ratio(1u8, 64)? {
        p.cookie = u.arbitrary()?;
    }
    p.topology = enumeration(u, 3)?;
    p.boundary = enumeration(u, 2)?;
    p.solver = if u.ratio(1u8, 4)? { enumeration(u, 2)? } else { HIBI_MUD_QUASI_STATIC };
    p.drive = enumeration(u, 2)?;
    p.columns = count(u, 0..=14)?;
    p.rows = count(u, 0..=14)?;
    p.seed = u.arbitrary()?;
    p.layer_thickness = float(u, p.layer_thickness)?;
    p.element_size = float(u, p.element_size)?;
    p.long_step = float(u, p.long_step)?;
    p.short_step = float(u, p.short_step)?;
    p.shrink_ratio = float(u, p.shrink_ratio)?;
    p.displacement_tolerance = float(u, p.displacement_tolerance)?;
    p.damping_factor = float(u, p.damping_factor)?;
    p.density = float(u, p.density)?;
    p.young_modulus = float(u, p.young_modulus)?;
    p.shear_modulus = float(u, p.shear_modulus)?;
    p.break_stretch_mean = float(u, p.break_stretch_mean)?;
    p.break_stretch_spread = float(u, p.break_stretch_spread)?;
    p.break_stretch_size_exponent = float(u, p.break_stretch_size_exponent)?;
    p.anisotropy_direction = float(u, p.anisotropy_direction)?;
    p.anisotropy_ratio = float(u, p.anisotropy_ratio)?;
    p.stiffness_anisotropy_ratio = float(u, p.stiffness_anisotropy_ratio)?;
    p.target_shrink = float(u, p.target_shrink)?;
    p.target_crack_density = float(u, p.target_crack_density)?;
    Ok(p)
}

/// Glass params from the input: small plates and capacities, any value in every other field.
pub fn glass_params(u: &mut Unstructured) -> Result<hibi_glass_params> {
    let mut p = start(u, GLASS_PRESETS, hibi_glass_params_default(), hibi_glass_params_preset, same)?;
    if u.ratio(1u8, 64)? {
        p.cookie = u.arbitrary()?;
    }
    let [w, h] = [u.int_in_range(1u8..=160)?, u.int_in_range(1u8..=160)?];
    p.width = float(u, f32::from(w))?;
    p.height = float(u, f32::from(h))?;
    p.impact = [float(u, p.width / 2.0)?, float(u, p.height / 2.0)?];
    p.seed = u.arbitrary()?;
    p.radial_mean = float(u, p.radial_mean)?;
    p.ring_threshold = float(u, p.ring_threshold)?;
    p.large_slope = float(u, p.large_slope)?;
    p.large_offset = float(u, p.large_offset)?;
    p.ring_slope = float(u, p.ring_slope)?;
    p.ring_offset = float(u, p.ring_offset)?;
    p.ring_radius_slope = float(u, p.ring_radius_slope)?;
    p.ring_radius_offset = float(u, p.ring_radius_offset)?;
    p.large_speed = float(u, p.large_speed)?;
    p.radial_speed = float(u, p.radial_speed)?;
    p.ring_speed = float(u, p.ring_speed)?;
    p.spread_ratio = float(u, p.spread_ratio)?;
    p.spread = enumeration(u, 2)?;
    p.turn_limit = float(u, p.turn_limit)?;
    p.turn_delay = float(u, p.turn_delay)?;
    p.sector_angle = float(u, p.sector_angle)?;
    p.sector_radius = float(u, p.sector_radius)?;
    p.tip_repulsion = float(u, p.tip_repulsion)?;
    p.crack_attraction = float(u, p.crack_attraction)?;
    p.wander = float(u, p.wander)?;
    p.ring_adherence = float(u, p.ring_adherence)?;
    p.max_cracks = count(u, 0..=256)?;
    p.max_vertices = count(u, 0..=4096)?;
    Ok(p)
}

/// Skin params from the input: small surfaces, any value in every other field.
pub fn skin_params(u: &mut Unstructured) -> Result<hibi_skin_params> {
    let mut p = start(u, SKIN_PRESETS, hibi_skin_params_default(), hibi_skin_params_preset, same)?;
    if u.ratio(1u8, 64)? {
        p.cookie = u.arbitrary()?;
    }
    p.layout = enumeration(u, 3)?;
    p.jitter = enumeration(u, 2)?;
    p.periodic = enumeration(u, 2)?;
    p.width = count(u, 0..=48)?;
    p.height = count(u, 0..=48)?;
    p.seed = u.arbitrary()?;
    p.jitter_ratio = float(u, p.jitter_ratio)?;
    p.levels = count(u, 0..=4)?;
    for level in &mut p.level {
        level.spacing = float(u, level.spacing)?;
        level.perturbation = float(u, level.perturbation)?;
        level.perturbation_decay = float(u, level.perturbation_decay)?;
        level.perturbation_depth = count(u, 0..=6)?;
        level.stretch = [float(u, level.stretch[0])?, float(u, level.stretch[1])?];
        if u.ratio(1u8, 4)? {
            level.profile.segments = count(u, 0..=5)?;
            for point in &mut level.profile.points {
                *point = [float(u, point[0])?, float(u, point[1])?];
            }
        }
        level.roundness = float(u, level.roundness)?;
    }
    Ok(p)
}

/// Creates an object from `params` as the input chooses: `*_memory_size` first (its status
/// must be `*_create`'s when it refuses, and neither may write), then, for an object of at
/// most [`MAX_OBJECT_BYTES`], `*_create` or `*_create_in` into memory of any length and
/// alignment. Returns the object and its caller memory (empty for `*_create`), which must
/// outlive it.
pub fn create<P: core::fmt::Debug, O>(
    u: &mut Unstructured,
    params: &P,
    memory_size: unsafe extern "C" fn(*const P, *mut usize) -> hibi_status,
    memory_align: extern "C" fn() -> usize,
    create: unsafe extern "C" fn(*const P, *mut *mut O) -> hibi_status,
    create_in: unsafe extern "C" fn(*const P, *mut core::ffi::c_void, usize, *mut *mut O) -> hibi_status,
) -> Result<Option<(*mut O, Vec<u64>)>> {
    const UNWRITTEN: usize = usize::MAX - 3;
    LAST.with(|l| *l.borrow_mut() = format!("{params:?}"));
    let mut size = UNWRITTEN;
    // SAFETY: valid pointers.
    let status = unsafe { memory_size(params, &mut size) };
    let dangling = core::ptr::NonNull::<O>::dangling().as_ptr();
    let mut object = dangling;
    if !check(status) {
        assert_eq!(size, UNWRITTEN, "a failing memory_size wrote its output");
        // SAFETY: valid pointers.
        let again = unsafe { create(params, &mut object) };
        assert_eq!(again, status, "memory_size and create disagree");
        assert_eq!(object, dangling, "a failing create wrote its output");
        return Ok(None);
    }
    if size > MAX_OBJECT_BYTES {
        return Ok(None);
    }
    if u.arbitrary()? {
        // SAFETY: valid pointers.
        let status = unsafe { create(params, &mut object) };
        if !check(status) {
            assert_eq!(object, dangling, "a failing create wrote its output");
            assert!(status == HIBI_ERROR_OUT_OF_MEMORY, "memory_size accepted what create refused: status {status}");
            return Ok(None);
        }
        Ok(Some((object, Vec::new())))
    } else {
        let align = memory_align();
        let (memory, ptr, len) = caller_memory(u, size, align)?;
        // SAFETY: `ptr` is NULL or writable for `len` bytes.
        let status = unsafe { create_in(params, ptr, len, &mut object) };
        let fits = !ptr.is_null() && len >= size && (ptr as usize) % align == 0;
        if !check(status) {
            assert_eq!(object, dangling, "a failing create_in wrote its output");
            assert!(!fits, "create_in refused memory that fits: status {status}");
            return Ok(None);
        }
        assert!(fits, "create_in accepted memory that does not fit");
        Ok(Some((object, memory)))
    }
}

/// An out-pointer to `value`, or (rarely) NULL.
pub fn out<T>(u: &mut Unstructured, value: &mut T) -> Result<*mut T> {
    Ok(if u.ratio(1u8, 48)? { core::ptr::null_mut() } else { value })
}
