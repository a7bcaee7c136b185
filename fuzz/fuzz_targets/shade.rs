//! `hibi_skin_shade` through the C ABI: any height and normal values (NaN and infinities
//! included), any lengths, any light and palette.
#![no_main]

use core::ptr::null;

use arbitrary::{Result, Unstructured};
use hibi::*;
use hibi_fuzz::*;
use libfuzzer_sys::fuzz_target;

fn run(u: &mut Unstructured) -> Result<()> {
    let pixels = usize::from(u.int_in_range(0u8..=64)?);
    let mut params = hibi_skin_shade_params_default();
    for v in params.light.iter_mut().chain(&mut params.ridge).chain(&mut params.furrow) {
        *v = float(u, *v)?;
    }
    params.ambient = float(u, params.ambient)?;
    params.specular = float(u, params.specular)?;
    let height_len = length(u, pixels, pixels + 4)?;
    let normal_len = length(u, 3 * pixels, 3 * pixels + 4)?;
    let height: Vec<f32> = (0..height_len).map(|_| float(u, 0.5)).collect::<Result<_>>()?;
    let normal: Vec<f32> = (0..normal_len).map(|_| float(u, 0.577)).collect::<Result<_>>()?;
    let mut rgb = Buffer::pick(u, 3 * height_len, 3 * height_len + 8, 1)?;
    let null_params = u.ratio(1u8, 48)?;
    let p: *const hibi_skin_shade_params = if null_params { null() } else { &params };
    let hp = if height_len == 0 && u.arbitrary()? { null() } else { height.as_ptr() };
    let np = if normal_len == 0 && u.arbitrary()? { null() } else { normal.as_ptr() };
    // SAFETY: inputs readable for their lengths, `rgb` NULL or writable for its length.
    let status = unsafe { hibi_skin_shade(hp, height_len, np, normal_len, p, rgb.ptr(), rgb.len) };
    let unit = |c: f32| (0.0..=1.0).contains(&c);
    let light = finite(&params.light) && params.light.iter().any(|&c| c != 0.0);
    let valid = !null_params
        && light
        && params.ridge.iter().all(|&c| unit(c))
        && params.furrow.iter().all(|&c| unit(c))
        && unit(params.ambient)
        && params.specular.is_finite()
        && params.specular >= 0.0
        && normal_len >= 3 * height_len;
    let (possible, required) = rgb.fits(3 * height_len, 1);
    if check(status) {
        assert!(valid && possible, "shade accepted {params:?} ({height_len}, {normal_len}, {})", rgb.len);
        assert!(rgb.untouched_past(3 * height_len));
    } else {
        assert!(!(valid && required), "shade refused {params:?} ({height_len}, {normal_len}, {}): {status}", rgb.len);
        assert!(rgb.untouched(), "a failing shade wrote");
    }
    Ok(())
}

fuzz_target!(|data: &[u8]| {
    let _ = run(&mut Unstructured::new(data));
});
