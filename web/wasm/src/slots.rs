//! Parameter structs as flat lists of `f64` slots, with a text that names each slot, so that
//! the JavaScript glue builds its parameter objects from the core's own structs and defaults
//! (no field list is written twice). A line of the description is `path kind`: the path joins
//! field names and array indices with dots (`level.0.profile.points.3.1`); the kind is `f32`,
//! `u32`, `bool`, `u64` (two slots: the low and the high 32 bits) or `enum:a|b|c` (the slot
//! holds the variant's number, which is its index in the list).

use alloc::string::String;
use alloc::vec::Vec;

pub trait Slots {
    /// Appends one line per slot (two for a `u64`'s one line) under `path`.
    fn describe(&self, path: &str, out: &mut String);
    /// Appends the value's slots.
    fn put(&self, out: &mut Vec<f64>);
    /// Reads the value from the front of `slots`; false if a slot holds no valid value.
    fn take(&mut self, slots: &mut &[f64]) -> bool;
}

fn line(path: &str, kind: &str, out: &mut String) {
    out.push_str(path);
    out.push(' ');
    out.push_str(kind);
    out.push('\n');
}

fn next(slots: &mut &[f64]) -> Option<f64> {
    let (&first, rest) = slots.split_first()?;
    *slots = rest;
    Some(first)
}

pub fn join(path: &str, name: &str) -> String {
    let mut p = String::from(path);
    if !p.is_empty() {
        p.push('.');
    }
    p.push_str(name);
    p
}

impl Slots for f32 {
    fn describe(&self, path: &str, out: &mut String) {
        line(path, "f32", out);
    }
    fn put(&self, out: &mut Vec<f64>) {
        out.push(f64::from(*self));
    }
    fn take(&mut self, slots: &mut &[f64]) -> bool {
        next(slots).map(|v| *self = v as f32).is_some()
    }
}

impl Slots for u32 {
    fn describe(&self, path: &str, out: &mut String) {
        line(path, "u32", out);
    }
    fn put(&self, out: &mut Vec<f64>) {
        out.push(f64::from(*self));
    }
    fn take(&mut self, slots: &mut &[f64]) -> bool {
        match next(slots) {
            Some(v) if v >= 0.0 && v <= f64::from(u32::MAX) && f64::from(v as u32) == v => {
                *self = v as u32;
                true
            }
            _ => false,
        }
    }
}

impl Slots for bool {
    fn describe(&self, path: &str, out: &mut String) {
        line(path, "bool", out);
    }
    fn put(&self, out: &mut Vec<f64>) {
        out.push(if *self { 1.0 } else { 0.0 });
    }
    fn take(&mut self, slots: &mut &[f64]) -> bool {
        match next(slots) {
            Some(v) if v == 0.0 || v == 1.0 => {
                *self = v == 1.0;
                true
            }
            _ => false,
        }
    }
}

impl Slots for u64 {
    fn describe(&self, path: &str, out: &mut String) {
        line(path, "u64", out);
    }
    fn put(&self, out: &mut Vec<f64>) {
        out.push((*self & 0xffff_ffff) as f64);
        out.push((*self >> 32) as f64);
    }
    fn take(&mut self, slots: &mut &[f64]) -> bool {
        let (mut lo, mut hi) = (0u32, 0u32);
        if !(lo.take(slots) && hi.take(slots)) {
            return false;
        }
        *self = u64::from(lo) | u64::from(hi) << 32;
        true
    }
}

impl<T: Slots, const N: usize> Slots for [T; N] {
    fn describe(&self, path: &str, out: &mut String) {
        for (i, v) in self.iter().enumerate() {
            v.describe(&join(path, itoa(i).as_str()), out);
        }
    }
    fn put(&self, out: &mut Vec<f64>) {
        self.iter().for_each(|v| v.put(out));
    }
    fn take(&mut self, slots: &mut &[f64]) -> bool {
        self.iter_mut().all(|v| v.take(slots))
    }
}

fn itoa(i: usize) -> String {
    use core::fmt::Write;
    let mut s = String::new();
    let _ = write!(s, "{i}");
    s
}

/// [`Slots`] for a core enumeration: its variants by `ALL`, named by their `Debug` text in
/// snake case.
macro_rules! enumeration {
    ($($t:ty),+ $(,)?) => {$(
        impl Slots for $t {
            fn describe(&self, path: &str, out: &mut String) {
                let mut kind = String::from("enum:");
                for (i, v) in <$t>::ALL.iter().enumerate() {
                    if i > 0 {
                        kind.push('|');
                    }
                    kind.push_str(&$crate::slots::snake(&alloc::format!("{v:?}")));
                }
                line(path, &kind, out);
            }
            fn put(&self, out: &mut Vec<f64>) {
                let i = <$t>::ALL.iter().position(|v| v == self).unwrap_or(0);
                out.push(i as f64);
            }
            fn take(&mut self, slots: &mut &[f64]) -> bool {
                let mut i = 0u32;
                match i.take(slots).then(|| <$t>::ALL.get(i as usize)).flatten() {
                    Some(v) => {
                        *self = *v;
                        true
                    }
                    None => false,
                }
            }
        }
    )+};
}

/// [`Slots`] for a struct of the core, its fields listed once (the destructuring makes the
/// compiler check that the list is every field).
macro_rules! record {
    ($($t:ty { $($field:ident),+ $(,)? })+) => {$(
        impl Slots for $t {
            fn describe(&self, path: &str, out: &mut String) {
                let Self { $($field),+ } = self;
                $( $field.describe(&join(path, stringify!($field)), out); )+
            }
            fn put(&self, out: &mut Vec<f64>) {
                let Self { $($field),+ } = self;
                $( $field.put(out); )+
            }
            fn take(&mut self, slots: &mut &[f64]) -> bool {
                let Self { $($field),+ } = self;
                true $( && $field.take(slots) )+
            }
        }
    )+};
}

/// `QuasiStatic` → `quasi_static`.
pub fn snake(name: &str) -> String {
    let mut s = String::new();
    for (i, c) in name.chars().enumerate() {
        if c.is_ascii_uppercase() {
            if i > 0 {
                s.push('_');
            }
            s.push(c.to_ascii_lowercase());
        } else {
            s.push(c);
        }
    }
    s
}

use hibi_core::glass::{GlassParams, GlassRender};
use hibi_core::mud::{Boundary, Drive, MudParams, MudRender, Solver, Topology};
use hibi_core::skin::{LevelParams, Profile, ShadeParams, SiteLayout, SkinParams, SkinRender};

enumeration!(Topology, Boundary, Solver, Drive, hibi_core::Spread, SiteLayout);

record! {
    MudParams {
        topology, boundary, solver, drive, columns, rows, seed, layer_thickness, element_size, long_step,
        short_step, shrink_ratio, displacement_tolerance, damping_factor, density, young_modulus,
        shear_modulus, break_stretch_mean, break_stretch_spread, break_stretch_size_exponent,
        anisotropy_direction, anisotropy_ratio, stiffness_anisotropy_ratio, target_shrink,
        target_crack_density,
    }
    GlassParams {
        width, height, impact, seed, radial_mean, ring_threshold, large_slope, large_offset, ring_slope,
        ring_offset, ring_radius_slope, ring_radius_offset, large_speed, radial_speed, ring_speed,
        spread_ratio, spread, turn_limit, turn_delay, sector_angle, sector_radius, tip_repulsion,
        crack_attraction, wander, ring_adherence, max_cracks, max_vertices,
    }
    Profile { segments, points }
    LevelParams { spacing, perturbation, perturbation_decay, perturbation_depth, stretch, profile, roundness }
    SkinParams { width, height, seed, layout, jitter, jitter_ratio, periodic, levels, level }
    MudRender { width, height, width_scale, min_width, groove_depth, offset, bump, until }
    GlassRender { width, height, line_width, bump, until }
    ShadeParams { light, ridge, furrow, ambient, specular }
    SkinRender { cell_level, shade }
}

/// The description of `value`'s slots and their number.
pub fn description<T: Slots>(value: &T) -> (String, usize) {
    let mut text = String::new();
    value.describe("", &mut text);
    let count = text.lines().map(|l| if l.ends_with(" u64") { 2 } else { 1 }).sum();
    (text, count)
}

use hibi_core::glass::{GlassProgress, ImpactCounts};
use hibi_core::mud::{CrackStatistics, MudProgress};
use hibi_core::skin::SkinProgress;

record! {
    MudProgress { shrink, time, broken_springs, crack_density, finished, work }
    GlassProgress { time, cracks, growing, vertices, finished, capacity_reached, work }
    SkinProgress { cells, roots, root_total, finished, capacity_reached, work }
    ImpactCounts { radial, large, rings }
    CrackStatistics {
        crack_density, cells, mean_cell_area, cell_area_spread, junctions, t_junctions,
        mean_widest_junction_angle, dead_ends,
    }
}
