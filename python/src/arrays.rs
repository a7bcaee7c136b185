//! Render layers as owned Rust buffers that become NumPy arrays without a copy, and the
//! point arrays of networks, cells and fragments.

use hibi_core::raster::{Layers, Tile, scratch_len};
use numpy::IntoPyArray;
use numpy::ndarray::{Array2, Array3};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::{runtime_error, value_error};

/// Every layer a render can draw, as Rust and C spell them.
pub const LAYER_NAMES: [&str; 8] = ["mask", "height", "height16", "normal", "normal_rgb8", "time", "cell", "preview"];

/// A render's `threads`, or a `ValueError` when it is 0.
pub fn threads(threads: usize) -> PyResult<usize> {
    if threads == 0 {
        return Err(value_error("render: threads must be at least 1"));
    }
    Ok(threads)
}

/// Which layers to draw (in the order asked).
#[derive(Clone, Debug, Default)]
pub struct Wanted {
    names: Vec<usize>,
}

impl Wanted {
    /// The layers named, or a `ValueError` naming an unknown one.
    pub fn of(names: &[String]) -> PyResult<Wanted> {
        let mut out = Wanted::default();
        if names.is_empty() {
            return Err(value_error("render: layers must name at least one layer"));
        }
        for n in names {
            let k = LAYER_NAMES.iter().position(|l| l == n).ok_or_else(|| {
                value_error(format!("render: layers: no layer {n:?} (one of {})", LAYER_NAMES.join(", ")))
            })?;
            if !out.names.contains(&k) {
                out.names.push(k);
            }
        }
        Ok(out)
    }

    /// Buffers for a `width` × `height` raster (the scratch always: it is cheap beside the
    /// layers, and the core reads only what it needs).
    pub fn buffers(&self, width: u32, height: u32) -> PyResult<Rendered> {
        let pixels = (width as usize).checked_mul(height as usize).filter(|&p| p > 0);
        let Some(pixels) = pixels else {
            return Err(value_error("render: width and height must be > 0 and their product must fit in memory"));
        };
        let scratch = scratch_len(width, height).ok_or_else(|| value_error("render: width and height too large"))?;
        let mut r = Rendered {
            columns: width,
            rows: height,
            order: self.names.clone(),
            scratch: vec![0; scratch],
            ..Rendered::default()
        };
        for &k in &self.names {
            match LAYER_NAMES[k] {
                "mask" => r.mask = Some(vec![0; pixels]),
                "height" => r.height = Some(vec![0.0; pixels]),
                "height16" => r.height16 = Some(vec![0; pixels]),
                "normal" => r.normal = Some(vec![0.0; 3 * pixels]),
                "normal_rgb8" => r.normal_rgb8 = Some(vec![0; 3 * pixels]),
                "time" => r.time = Some(vec![0.0; pixels]),
                "cell" => r.cell = Some(vec![0; pixels]),
                "preview" => r.preview = Some(vec![0; 4 * pixels]),
                _ => unreachable!("a listed layer"),
            }
        }
        Ok(r)
    }
}

/// The buffers of one render.
#[derive(Default)]
pub struct Rendered {
    columns: u32,
    rows: u32,
    order: Vec<usize>,
    mask: Option<Vec<u8>>,
    height: Option<Vec<f32>>,
    height16: Option<Vec<u16>>,
    normal: Option<Vec<f32>>,
    normal_rgb8: Option<Vec<u8>>,
    time: Option<Vec<f32>>,
    cell: Option<Vec<u32>>,
    preview: Option<Vec<u8>>,
    scratch: Vec<u32>,
}

impl Rendered {
    /// The core's view of the buffers.
    pub fn layers(&mut self) -> Layers<'_> {
        Layers {
            mask: self.mask.as_deref_mut(),
            height: self.height.as_deref_mut(),
            height16: self.height16.as_deref_mut(),
            normal: self.normal.as_deref_mut().map(|v| v.as_chunks_mut::<3>().0),
            normal_rgb8: self.normal_rgb8.as_deref_mut().map(|v| v.as_chunks_mut::<3>().0),
            time: self.time.as_deref_mut(),
            cell: self.cell.as_deref_mut(),
            preview: self.preview.as_deref_mut().map(|v| v.as_chunks_mut::<4>().0),
            scratch: Some(&mut self.scratch),
        }
    }

    /// Draws every layer with `draw(tile, layers)`, one render of a tile: in one call on the
    /// calling thread when `threads` is 1, else in full-width bands of rows, one band per
    /// thread on up to `threads` threads (each band its own scratch). The core draws a tile's
    /// pixels bit for bit as the whole raster has them, so the arrays are the same on any
    /// number of threads. The first failure is returned.
    pub fn draw<E: Send>(
        &mut self,
        threads: usize,
        draw: impl Fn(&Tile, Layers) -> Result<(), E> + Sync,
    ) -> Result<(), E> {
        let whole = Tile::whole(self.columns, self.rows);
        if threads <= 1 {
            return draw(&whole, self.layers());
        }
        let rows = self.rows.div_ceil(threads.min(self.rows as usize) as u32).max(1);
        let bands: Vec<(Tile, Layers)> = self.layers().bands(&whole, rows).collect();
        let draw = &draw;
        std::thread::scope(|scope| {
            let running: Vec<_> = bands
                .into_iter()
                .map(|(tile, band)| {
                    scope.spawn(move || {
                        let mut scratch = vec![0u32; scratch_len(tile.width, tile.height).unwrap_or(0)];
                        draw(&tile, Layers { scratch: Some(&mut scratch), ..band })
                    })
                })
                .collect();
            running.into_iter().map(|r| r.join().expect("a render band panicked")).collect::<Result<Vec<()>, E>>()
        })
        .map(|_| ())
    }

    /// The layers as a dict of arrays (height × width, × 3 or 4 channels), in the order asked;
    /// each array owns its Rust buffer.
    pub fn into_dict(self, py: Python<'_>) -> PyResult<Bound<'_, PyDict>> {
        let (h, w) = (self.rows as usize, self.columns as usize);
        let shape = |e| runtime_error(format!("render: {e}"));
        let d = PyDict::new(py);
        let Rendered { order, mask, height, height16, normal, normal_rgb8, time, cell, preview, .. } = self;
        let mut arrays: Vec<(&str, Bound<'_, PyAny>)> = Vec::new();
        if let Some(v) = mask {
            arrays.push(("mask", Array2::from_shape_vec((h, w), v).map_err(shape)?.into_pyarray(py).into_any()));
        }
        if let Some(v) = height {
            arrays.push(("height", Array2::from_shape_vec((h, w), v).map_err(shape)?.into_pyarray(py).into_any()));
        }
        if let Some(v) = height16 {
            arrays.push(("height16", Array2::from_shape_vec((h, w), v).map_err(shape)?.into_pyarray(py).into_any()));
        }
        if let Some(v) = normal {
            arrays.push(("normal", Array3::from_shape_vec((h, w, 3), v).map_err(shape)?.into_pyarray(py).into_any()));
        }
        if let Some(v) = normal_rgb8 {
            let a = Array3::from_shape_vec((h, w, 3), v).map_err(shape)?;
            arrays.push(("normal_rgb8", a.into_pyarray(py).into_any()));
        }
        if let Some(v) = time {
            arrays.push(("time", Array2::from_shape_vec((h, w), v).map_err(shape)?.into_pyarray(py).into_any()));
        }
        if let Some(v) = cell {
            arrays.push(("cell", Array2::from_shape_vec((h, w), v).map_err(shape)?.into_pyarray(py).into_any()));
        }
        if let Some(v) = preview {
            arrays.push(("preview", Array3::from_shape_vec((h, w, 4), v).map_err(shape)?.into_pyarray(py).into_any()));
        }
        for k in order {
            if let Some((name, a)) = arrays.iter().find(|(n, _)| *n == LAYER_NAMES[k]) {
                d.set_item(*name, a)?;
            }
        }
        Ok(d)
    }
}

/// Flat `f32` values as an (n, k) array.
pub fn rows_f32(py: Python<'_>, values: Vec<f32>, k: usize) -> PyResult<Bound<'_, PyAny>> {
    let n = values.len() / k;
    Ok(Array2::from_shape_vec((n, k), values).map_err(runtime_error)?.into_pyarray(py).into_any())
}

/// Flat `f64` values as an (n, k) array.
pub fn rows_f64(py: Python<'_>, values: Vec<f64>, k: usize) -> PyResult<Bound<'_, PyAny>> {
    let n = values.len() / k;
    Ok(Array2::from_shape_vec((n, k), values).map_err(runtime_error)?.into_pyarray(py).into_any())
}

/// Flat `i64` values as an (n, k) array.
pub fn rows_i64(py: Python<'_>, values: Vec<i64>, k: usize) -> PyResult<Bound<'_, PyAny>> {
    let n = values.len() / k;
    Ok(Array2::from_shape_vec((n, k), values).map_err(runtime_error)?.into_pyarray(py).into_any())
}

/// Ring offsets: ring k's points are `points[offsets[k]:offsets[k + 1]]`.
pub fn offsets(py: Python<'_>, counts: impl Iterator<Item = usize>) -> Bound<'_, PyAny> {
    let mut out = vec![0i64];
    let mut total = 0i64;
    for c in counts {
        total += c as i64;
        out.push(total);
    }
    out.into_pyarray(py).into_any()
}

/// Rings (mud cells, glass fragments) as a dict: `points` (n, 2) `float32`, `offsets`
/// (rings + 1) `int64`, `area` (rings) `float64` (signed: holes negative), `hole_of` (rings)
/// `uint32`.
pub fn rings<'py>(
    py: Python<'py>,
    rings: &[hibi_core::polygon::Ring],
    points: Vec<[f32; 2]>,
) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("points", rows_f32(py, points.into_flattened(), 2)?)?;
    d.set_item("offsets", offsets(py, rings.iter().map(|r| r.point_count as usize)))?;
    d.set_item("area", rings.iter().map(|r| r.area).collect::<Vec<f64>>().into_pyarray(py))?;
    d.set_item("hole_of", rings.iter().map(|r| r.hole_of).collect::<Vec<u32>>().into_pyarray(py))?;
    Ok(d)
}
