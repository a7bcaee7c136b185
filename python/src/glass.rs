//! `hibi.Glass`: Model B, a glass plate hit by a ball, over `hibi_core::glass`.

use hibi_core::Spread;
use hibi_core::glass::{
    Glass, GlassError, GlassMemory, GlassParamError, GlassParams, GlassProgress, GlassRender, GlassStore, ImpactCounts,
};
use numpy::IntoPyArray;
use ouroboros::self_referencing;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyTuple};

use crate::arrays::{offsets, rows_f32};
use crate::{choice, choice_name, field, layer_request, rendered, runtime_error, unknown, value_error};

const SPREADS: [(&str, Spread); 2] = [("normal", Spread::Normal), ("uniform", Spread::Uniform)];

/// The `f32` fields of [`GlassParams`], by name.
macro_rules! float_fields {
    ($m:ident) => {
        $m!(
            width,
            height,
            radial_mean,
            ring_threshold,
            large_slope,
            large_offset,
            ring_slope,
            ring_offset,
            ring_radius_slope,
            ring_radius_offset,
            large_speed,
            radial_speed,
            ring_speed,
            spread_ratio,
            turn_limit,
            turn_delay,
            sector_angle,
            sector_radius,
            tip_repulsion,
            crack_attraction,
            wander,
            ring_adherence
        )
    };
}

/// The parameters: the preset's (or the paper's defaults), then every keyword given. A plate
/// resized without an `impact` is hit at its new centre.
fn params(preset: Option<&str>, kwargs: Option<&Bound<'_, PyDict>>) -> PyResult<GlassParams> {
    let mut p = match preset {
        Some(name) => hibi_core::glass::preset(name).ok_or_else(|| {
            value_error(format!("glass: preset must be one of {}, not {name:?}", hibi_core::glass::PRESETS.join(", ")))
        })?,
        None => GlassParams::default(),
    };
    let plate = [p.width, p.height];
    let mut impact = None;
    for (key, value) in kwargs.into_iter().flat_map(|d| d.iter()) {
        let key: String = key.extract()?;
        macro_rules! floats {
            ($($f:ident),*) => {
                match key.as_str() {
                    $(stringify!($f) => { p.$f = field("glass", &key, &value)?; continue; })*
                    _ => {}
                }
            };
        }
        float_fields!(floats);
        match key.as_str() {
            "impact" => impact = Some(field::<(f32, f32)>("glass", &key, &value)?),
            "spread" => p.spread = choice("glass", &key, &value, &SPREADS)?,
            "seed" => p.seed = field("glass", &key, &value)?,
            "max_cracks" => p.max_cracks = field("glass", &key, &value)?,
            "max_vertices" => p.max_vertices = field("glass", &key, &value)?,
            _ => return Err(unknown("Glass", &key)),
        }
    }
    match impact {
        Some((x, y)) => p.impact = [x, y],
        None if [p.width, p.height] != plate => p.impact = [0.5 * p.width, 0.5 * p.height],
        None => {}
    }
    Ok(p)
}

fn params_dict<'py>(py: Python<'py>, p: &GlassParams) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("impact", (p.impact[0], p.impact[1]))?;
    d.set_item("seed", p.seed)?;
    d.set_item("spread", choice_name(p.spread, &SPREADS))?;
    d.set_item("max_cracks", p.max_cracks)?;
    d.set_item("max_vertices", p.max_vertices)?;
    macro_rules! floats {
        ($($f:ident),*) => { $(d.set_item(stringify!($f), p.$f)?;)* };
    }
    float_fields!(floats);
    Ok(d)
}

fn error(e: GlassError) -> PyErr {
    match e {
        GlassError::Param(p) => value_error(p),
        GlassError::Impact => value_error(GlassParamError::Impact),
        GlassError::Capacity => runtime_error(
            "glass: the plate ran out of room for cracks (max_cracks, max_vertices): no more impacts on it",
        ),
        other => runtime_error(other),
    }
}

#[self_referencing]
struct Plate {
    store: GlassStore,
    #[borrows(mut store)]
    #[covariant]
    glass: Glass<'this>,
}

/// Where a plate stands (`hibi_core::glass::GlassProgress`).
#[pyclass(module = "hibi._hibi", name = "GlassProgress", frozen, get_all, skip_from_py_object)]
#[derive(Clone, Copy)]
pub struct PyGlassProgress {
    /// Time steps of the impact under way.
    time: u32,
    /// Cracks on the plate.
    cracks: u32,
    /// Cracks still growing.
    growing: u32,
    /// Vertices on the plate.
    vertices: u32,
    /// Every crack stopped.
    finished: bool,
    /// A capacity (max_cracks, max_vertices) ran out: generation stopped there.
    capacity_reached: bool,
    /// Work done, in the units of `step`'s budget.
    work: u64,
}

#[pymethods]
impl PyGlassProgress {
    fn __repr__(&self) -> String {
        let b = |v: bool| if v { "True" } else { "False" };
        format!(
            "GlassProgress(time={}, cracks={}, growing={}, vertices={}, finished={}, capacity_reached={}, work={})",
            self.time,
            self.cracks,
            self.growing,
            self.vertices,
            b(self.finished),
            b(self.capacity_reached),
            self.work
        )
    }
}

impl From<GlassProgress> for PyGlassProgress {
    fn from(p: GlassProgress) -> Self {
        PyGlassProgress {
            time: p.time,
            cracks: p.cracks,
            growing: p.growing,
            vertices: p.vertices,
            finished: p.finished,
            capacity_reached: p.capacity_reached,
            work: p.work,
        }
    }
}

fn counts_dict(py: Python<'_>, c: ImpactCounts) -> PyResult<Bound<'_, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("radial", c.radial)?;
    d.set_item("large", c.large)?;
    d.set_item("rings", c.rings)?;
    Ok(d)
}

/// Model B (Agui et al.): cracks growing in a glass plate hit by a ball.
///
/// Keywords are ``hibi_core::glass::GlassParams``'s fields over the preset's (or the paper's
/// defaults): width, height, impact (x, y), seed, radial_mean, ring_threshold, large_slope,
/// large_offset, ring_slope, ring_offset, ring_radius_slope, ring_radius_offset, large_speed,
/// radial_speed, ring_speed, spread_ratio, spread ("normal", "uniform"), turn_limit (radians),
/// turn_delay, sector_angle (radians), sector_radius, tip_repulsion, crack_attraction, wander
/// (radians), ring_adherence, max_cracks, max_vertices. A plate resized without ``impact``
/// is hit at its centre.
#[pyclass(module = "hibi._hibi", name = "Glass")]
pub struct PyGlass {
    plate: Plate,
    memory: GlassMemory,
}

#[pymethods]
impl PyGlass {
    #[new]
    #[pyo3(signature = (preset=None, **kwargs))]
    fn new(py: Python<'_>, preset: Option<&str>, kwargs: Option<&Bound<'_, PyDict>>) -> PyResult<Self> {
        let p = params(preset, kwargs)?;
        let memory = p.memory().map_err(value_error)?;
        let plate = py.detach(|| {
            PlateTryBuilder { store: memory.allocate(), glass_builder: |s| Glass::new(&p, s.buffers()) }.try_build()
        });
        Ok(PyGlass { plate: plate.map_err(error)?, memory })
    }

    /// Grows the cracks for at most about `budget` units of work (GIL released).
    fn step(&mut self, py: Python<'_>, budget: u64) -> PyGlassProgress {
        let plate = &mut self.plate;
        py.detach(|| plate.with_glass_mut(|g| g.step(budget))).into()
    }

    /// Grows every crack to its end (GIL released). With `callback`, in steps of `budget`
    /// units, calling `callback(progress)` after each.
    #[pyo3(signature = (callback=None, budget=100_000))]
    fn run(&mut self, py: Python<'_>, callback: Option<&Bound<'_, PyAny>>, budget: u64) -> PyResult<PyGlassProgress> {
        loop {
            let p = match callback {
                None => {
                    let plate = &mut self.plate;
                    py.detach(|| {
                        plate.with_glass_mut(|g| {
                            loop {
                                let p = g.step(u64::MAX);
                                if p.finished || p.capacity_reached {
                                    break p;
                                }
                            }
                        })
                    })
                    .into()
                }
                Some(_) => self.step(py, budget),
            };
            if let Some(callback) = callback {
                callback.call1((Bound::new(py, p)?,))?;
            }
            if p.finished || p.capacity_reached {
                return Ok(p);
            }
        }
    }

    /// Hits the plate again at `at` (x, y): a new impact whose cracks grow from there, stopping
    /// on the cracks already there. Returns its counts (radial, large, rings).
    fn impact<'py>(&mut self, py: Python<'py>, at: (f32, f32)) -> PyResult<Bound<'py, PyDict>> {
        let plate = &mut self.plate;
        let c = py.detach(|| plate.with_glass_mut(|g| g.impact([at.0, at.1]))).map_err(error)?;
        counts_dict(py, c)
    }

    /// The counts the first impact drew: radial (M), large (N), rings (R).
    #[getter]
    fn impact_counts<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        counts_dict(py, self.plate.borrow_glass().impact_counts())
    }

    /// Where the plate stands.
    #[getter]
    fn progress(&self) -> PyGlassProgress {
        self.plate.borrow_glass().progress().into()
    }

    /// The parameters, every field by its Rust name (angles in radians).
    #[getter]
    fn params<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        params_dict(py, self.plate.borrow_glass().params())
    }

    /// Every crack's polyline: `points` (p, 2) `float32` px, `time` (p) `float32` (the step
    /// the front passed), `offsets` (c + 1) `int64`; per crack `end` and `kind` (`uint32`
    /// codes of `CrackEnd` and `CrackKind` in the Rust order) and `impact` (`uint32`).
    fn cracks<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let plate = &self.plate;
        let (at, time, counts, ends, kinds, impacts) = py.detach(|| {
            let g = plate.borrow_glass();
            let (mut at, mut time, mut counts) = (Vec::new(), Vec::new(), Vec::new());
            let (mut ends, mut kinds, mut impacts) = (Vec::new(), Vec::new(), Vec::new());
            for i in 0..g.crack_count() {
                let c = g.crack(i).unwrap_or_default();
                ends.push(g.crack(i).map_or(u32::MAX, |c| c.end as u32));
                kinds.push(c.kind as u32);
                impacts.push(c.impact);
                let before = time.len();
                g.for_each_point(i, |q| {
                    at.extend(q.at);
                    time.push(q.time);
                });
                counts.push(time.len() - before);
            }
            (at, time, counts, ends, kinds, impacts)
        });
        let d = PyDict::new(py);
        d.set_item("points", rows_f32(py, at, 2)?)?;
        d.set_item("time", time.into_pyarray(py))?;
        d.set_item("offsets", offsets(py, counts.into_iter()))?;
        d.set_item("end", ends.into_pyarray(py))?;
        d.set_item("kind", kinds.into_pyarray(py))?;
        d.set_item("impact", impacts.into_pyarray(py))?;
        Ok(d)
    }

    /// The fragments the cracks cut the plate into, as rings: `points` (n, 2) `float32` px,
    /// `offsets`, `area` (px², holes negative), `hole_of`.
    fn fragments<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let (plate, words) = (&self.plate, self.memory.scratch);
        let (rings, points) = py
            .detach(|| {
                let g = plate.borrow_glass();
                let mut scratch = vec![0u32; words];
                let (r, p) = g.fragment_counts(&mut scratch)?;
                let mut rings = vec![Default::default(); r];
                let mut points = vec![[0.0f32; 2]; p];
                g.fragments(&mut scratch, &mut rings, &mut points).map(|_| (rings, points))
            })
            .map_err(error)?;
        crate::arrays::rings(py, &rings, points)
    }

    /// Draws `layers` (a name, or a sequence of: mask, height, height16, normal,
    /// normal_rgb8, time, preview) with the GIL released, by default one pixel per px of the
    /// plate; on `threads` threads, a band of rows each (the same arrays on any number).
    #[pyo3(signature = (layers=None, *, width=None, height=None, line_width=None, bump=None, until=None, threads=1))]
    #[allow(clippy::too_many_arguments)]
    fn render<'py>(
        &self,
        py: Python<'py>,
        layers: Option<&Bound<'py, PyAny>>,
        width: Option<u32>,
        height: Option<u32>,
        line_width: Option<f32>,
        bump: Option<f32>,
        until: Option<f32>,
        threads: usize,
    ) -> PyResult<Bound<'py, PyAny>> {
        let threads = crate::arrays::threads(threads)?;
        let (wanted, single) = layer_request(layers, "mask")?;
        let p = *self.plate.borrow_glass().params();
        let plate = [p.width, p.height].map(|v| (v.round() as u32).clamp(1, 65_536));
        let d = GlassRender::default();
        let r = GlassRender {
            width: width.unwrap_or(plate[0]),
            height: height.unwrap_or(plate[1]),
            line_width: line_width.unwrap_or(d.line_width),
            bump: bump.unwrap_or(d.bump),
            until: until.unwrap_or(d.until),
        };
        let mut out = wanted.buffers(r.width, r.height)?;
        let glass = &self.plate;
        py.detach(|| {
            let g = glass.borrow_glass();
            out.draw(threads, |tile, layers| g.render_tile(&r, tile, layers))
        })
        .map_err(value_error)?;
        rendered(py, out, single)
    }

    fn __repr__(&self) -> String {
        let g = self.plate.borrow_glass();
        let p = g.params();
        format!("Glass(width={}, height={}, seed={}, {:?})", p.width, p.height, p.seed, g.progress())
    }

    /// Every preset name (the paper's figures).
    #[staticmethod]
    fn presets<'py>(py: Python<'py>) -> PyResult<Bound<'py, PyTuple>> {
        PyTuple::new(py, hibi_core::glass::PRESETS)
    }
}
