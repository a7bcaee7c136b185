//! A shaded preview: bump mapping (Blinn) of the normal map under one light, the paper's way
//! of showing its surfaces (§5), with a skin palette of our own (colour is the paper's open
//! problem): furrows darker and redder than ridge tops.

use super::SkinError;

/// Light and palette for [`shade`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ShadeParams {
    /// Direction towards the light (x right, y up, z out of the surface); need not be unit.
    pub light: [f32; 3],
    /// Ridge-top colour, linear RGB in [0, 1].
    pub ridge: [f32; 3],
    /// Furrow colour, linear RGB in [0, 1].
    pub furrow: [f32; 3],
    /// Light that reaches every pixel, in [0, 1].
    pub ambient: f32,
    /// Strength of the highlight (Blinn–Phong, shininess 24), ≥ 0.
    pub specular: f32,
}

crate::error::error_list! {
    /// Which shading parameter is out of range.
    pub enum ShadeError {
        /// A light component is not finite, or all three are zero.
        Light => c"skin: the shading light direction must be three finite numbers, not all zero",
        /// A `ridge` channel is outside [0, 1].
        Ridge => c"skin: the shading ridge colour must be three numbers in [0, 1]",
        /// A `furrow` channel is outside [0, 1].
        Furrow => c"skin: the shading furrow colour must be three numbers in [0, 1]",
        /// `ambient` is outside [0, 1].
        Ambient => c"skin: the shading ambient must be in [0, 1]",
        /// `specular` is negative or not finite.
        Specular => c"skin: the shading specular must be finite and >= 0",
    }
}

impl ShadeParams {
    /// Checks every field against its documented range.
    pub fn validate(&self) -> Result<(), ShadeError> {
        let unit = |c: [f32; 3]| c.iter().all(|v| (0.0..=1.0).contains(v));
        let checks = [
            (light_direction(self.light).is_some(), ShadeError::Light),
            (unit(self.ridge), ShadeError::Ridge),
            (unit(self.furrow), ShadeError::Furrow),
            ((0.0..=1.0).contains(&self.ambient), ShadeError::Ambient),
            (self.specular.is_finite() && self.specular >= 0.0, ShadeError::Specular),
        ];
        match checks.iter().find(|(ok, _)| !ok) {
            Some(&(_, e)) => Err(e),
            None => Ok(()),
        }
    }
}

/// The unit vector along `l`; None when a component is not finite or all are zero. Any finite
/// non-zero direction works, however large or small its components: when their squares would
/// overflow or lose precision, `l` is first scaled by its largest component.
fn light_direction(l: [f32; 3]) -> Option<[f32; 3]> {
    let largest = l[0].abs().max(l[1].abs()).max(l[2].abs());
    if !(l.iter().all(|v| v.is_finite()) && largest > 0.0) {
        return None;
    }
    let square = |v: [f32; 3]| v[0] * v[0] + v[1] * v[1] + v[2] * v[2];
    let squared = square(l);
    let l = if squared.is_finite() && squared >= f32::MIN_POSITIVE { l } else { l.map(|v| v / largest) };
    let length = crate::scalar::sqrtf(square(l));
    Some([l[0] / length, l[1] / length, l[2] / length])
}

impl Default for ShadeParams {
    /// Light from the upper left, a light skin tone.
    fn default() -> Self {
        ShadeParams {
            light: [-0.5, 0.6, 0.62],
            ridge: [0.90, 0.68, 0.56],
            furrow: [0.55, 0.33, 0.28],
            ambient: 0.35,
            specular: 0.12,
        }
    }
}

/// Lights `normal` (and darkens towards the furrows by `height`, scaled to its own range) into
/// 8-bit RGB (sRGB-encoded) in `out`, one pixel per value of `height`: `normal` and `out` must
/// hold at least as many pixels, and the parameters must be in range
/// ([`ShadeParams::validate`]); nothing is written otherwise.
pub fn shade(height: &[f32], normal: &[[f32; 3]], params: &ShadeParams, out: &mut [[u8; 3]]) -> Result<(), SkinError> {
    let pixels = height.len();
    if normal.len() < pixels || out.len() < pixels {
        return Err(SkinError::BufferTooSmall { needed: pixels });
    }
    params.validate().map_err(SkinError::Shade)?;
    let Some(light) = light_direction(params.light) else {
        return Err(SkinError::Shade(ShadeError::Light));
    };
    let light = Light::new(light);
    let (mut low, mut high) = (f32::INFINITY, f32::NEG_INFINITY);
    for &z in &height[..pixels] {
        low = low.min(z);
        high = high.max(z);
    }
    let span = if high > low { high - low } else { 1.0 };
    for i in 0..pixels {
        let [r, g, b, _] = light.shade(normal[i], (height[i] - low) / span, params);
        out[i] = [r, g, b];
    }
    Ok(())
}

/// The light of a shading: its unit direction and Blinn's half vector between it and a viewer
/// straight above.
pub(super) struct Light {
    light: [f32; 3],
    half: [f32; 3],
}

impl Light {
    /// From a unit direction towards the light.
    fn new(light: [f32; 3]) -> Light {
        let h = [light[0], light[1], light[2] + 1.0];
        let hl = crate::scalar::sqrtf(h[0] * h[0] + h[1] * h[1] + h[2] * h[2]);
        Light { light, half: [h[0] / hl, h[1] / hl, h[2] / hl] }
    }

    /// The light of checked shading parameters.
    pub(super) fn of(params: &ShadeParams) -> Option<Light> {
        light_direction(params.light).map(Light::new)
    }

    /// One pixel: normal `n`, height `t` as a fraction of the height range (clamped to
    /// [0, 1]), as 8-bit sRGB with alpha 255. The albedo runs from the furrow colour to the
    /// ridge colour with √t; Lambert's diffuse term plus ambient, and a Blinn–Phong highlight.
    pub(super) fn shade(&self, n: [f32; 3], t: f32, params: &ShadeParams) -> [u8; 4] {
        let (light, half) = (self.light, self.half);
        let t = crate::scalar::sqrtf(t.clamp(0.0, 1.0));
        let diffuse = (n[0] * light[0] + n[1] * light[1] + n[2] * light[2]).max(0.0);
        let gloss = libm::powf((n[0] * half[0] + n[1] * half[1] + n[2] * half[2]).max(0.0), 24.0);
        let lit = params.ambient + (1.0 - params.ambient) * diffuse;
        crate::raster::SRGB8.opaque(core::array::from_fn(|k| {
            let albedo = params.furrow[k] + (params.ridge[k] - params.furrow[k]) * t;
            (albedo * lit + params.specular * gloss).clamp(0.0, 1.0)
        }))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_default_shading_is_valid() {
        assert_eq!(ShadeParams::default().validate(), Ok(()));
    }

    #[test]
    fn any_finite_non_zero_light_is_a_direction() {
        for (light, unit) in [
            ([0.0, 0.0, 1e30], [0.0, 0.0, 1.0]),
            ([-3e38, 0.0, 3e38], [-core::f32::consts::FRAC_1_SQRT_2, 0.0, core::f32::consts::FRAC_1_SQRT_2]),
            ([0.0, 1e-40, 0.0], [0.0, 1.0, 0.0]),
            ([0.0, 0.0, 2.0], [0.0, 0.0, 1.0]),
        ] {
            let got = light_direction(light).unwrap();
            assert!(got.iter().zip(unit).all(|(g, u)| (g - u).abs() < 1e-6), "{light:?}: {got:?}");
            assert_eq!(ShadeParams { light, ..ShadeParams::default() }.validate(), Ok(()));
        }
        for light in [[0.0; 3], [f32::NAN, 0.0, 1.0], [0.0, f32::INFINITY, 1.0]] {
            assert_eq!(light_direction(light), None);
            assert_eq!(ShadeParams { light, ..ShadeParams::default() }.validate(), Err(ShadeError::Light));
        }
    }
}
