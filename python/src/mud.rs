//! `hibi.Mud`: Model A, drying mud, over `hibi_core::mud`.

use hibi_core::mud::{Boundary, Drive, Mud, MudError, MudParams, MudProgress, MudRender, MudStore, Solver, Topology};
use numpy::IntoPyArray;
use ouroboros::self_referencing;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyTuple};

use crate::arrays::{offsets, rows_f32};
use crate::{choice, choice_name, field, layer_request, rendered, runtime_error, unknown, value_error};

const TOPOLOGIES: [(&str, Topology); 3] =
    [("square", Topology::Square), ("hexagonal", Topology::Hexagonal), ("irregular", Topology::Irregular)];
const BOUNDARIES: [(&str, Boundary); 2] = [("open", Boundary::Open), ("periodic", Boundary::Periodic)];
const SOLVERS: [(&str, Solver); 2] = [("explicit", Solver::Explicit), ("quasi-static", Solver::QuasiStatic)];
const DRIVES: [(&str, Drive); 2] = [("shrink", Drive::Shrink), ("growth", Drive::Growth)];

/// The `f32` fields of [`MudParams`], by name.
macro_rules! float_fields {
    ($m:ident) => {
        $m!(
            layer_thickness,
            element_size,
            long_step,
            short_step,
            shrink_ratio,
            displacement_tolerance,
            damping_factor,
            density,
            young_modulus,
            shear_modulus,
            break_stretch_mean,
            break_stretch_spread,
            break_stretch_size_exponent,
            anisotropy_direction,
            anisotropy_ratio,
            stiffness_anisotropy_ratio,
            target_shrink,
            target_crack_density
        )
    };
}

/// The parameters: the preset's (or the paper's defaults), then every keyword given.
fn params(preset: Option<&str>, kwargs: Option<&Bound<'_, PyDict>>) -> PyResult<MudParams> {
    let mut p = match preset {
        Some(name) => hibi_core::mud::preset(name).ok_or_else(|| {
            value_error(format!("mud: preset must be one of {}, not {name:?}", hibi_core::mud::PRESETS.join(", ")))
        })?,
        None => MudParams::default(),
    };
    for (key, value) in kwargs.into_iter().flat_map(|d| d.iter()) {
        let key: String = key.extract()?;
        macro_rules! floats {
            ($($f:ident),*) => {
                match key.as_str() {
                    $(stringify!($f) => { p.$f = field("mud", &key, &value)?; continue; })*
                    _ => {}
                }
            };
        }
        float_fields!(floats);
        match key.as_str() {
            "topology" => p.topology = choice("mud", &key, &value, &TOPOLOGIES)?,
            "boundary" => p.boundary = choice("mud", &key, &value, &BOUNDARIES)?,
            "solver" => p.solver = choice("mud", &key, &value, &SOLVERS)?,
            "drive" => p.drive = choice("mud", &key, &value, &DRIVES)?,
            "columns" => p.columns = field("mud", &key, &value)?,
            "rows" => p.rows = field("mud", &key, &value)?,
            "seed" => p.seed = field("mud", &key, &value)?,
            _ => return Err(unknown("Mud", &key)),
        }
    }
    Ok(p)
}

/// The parameters as a dict, every field by its Rust name.
fn params_dict<'py>(py: Python<'py>, p: &MudParams) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("topology", choice_name(p.topology, &TOPOLOGIES))?;
    d.set_item("boundary", choice_name(p.boundary, &BOUNDARIES))?;
    d.set_item("solver", choice_name(p.solver, &SOLVERS))?;
    d.set_item("drive", choice_name(p.drive, &DRIVES))?;
    d.set_item("columns", p.columns)?;
    d.set_item("rows", p.rows)?;
    d.set_item("seed", p.seed)?;
    macro_rules! floats {
        ($($f:ident),*) => { $(d.set_item(stringify!($f), p.$f)?;)* };
    }
    float_fields!(floats);
    Ok(d)
}

/// A run's error: a parameter's names the field (`ValueError`).
fn error(e: MudError) -> PyErr {
    match e {
        MudError::Param(p) => value_error(p),
        other => runtime_error(other),
    }
}

#[self_referencing]
struct Run {
    store: MudStore<f32>,
    #[borrows(mut store)]
    #[not_covariant]
    mud: Mud<'this, f32>,
}

/// Where a drying-mud run stands (`hibi_core::mud::MudProgress`).
#[pyclass(module = "hibi._hibi", name = "MudProgress", frozen, get_all, skip_from_py_object)]
#[derive(Clone, Copy)]
pub struct PyMudProgress {
    /// The misfit between the layers: shrink 1 - r (growth: 1/r - 1).
    shrink: f32,
    /// Time in long steps T.
    time: f32,
    /// Springs broken so far.
    broken_springs: u32,
    /// Crack length per area [1/cm].
    crack_density: f32,
    /// The run reached its end.
    finished: bool,
    /// Work done since the run began, in the units of `step`'s budget.
    work: u64,
}

#[pymethods]
impl PyMudProgress {
    fn __repr__(&self) -> String {
        format!(
            "MudProgress(shrink={}, time={}, broken_springs={}, crack_density={}, finished={}, work={})",
            self.shrink,
            self.time,
            self.broken_springs,
            self.crack_density,
            if self.finished { "True" } else { "False" },
            self.work
        )
    }
}

impl From<MudProgress> for PyMudProgress {
    fn from(p: MudProgress) -> Self {
        PyMudProgress {
            shrink: p.shrink,
            time: p.time,
            broken_springs: p.broken_springs,
            crack_density: p.crack_density,
            finished: p.finished,
            work: p.work,
        }
    }
}

/// Model A (Hirota et al.): a drying layer of mud as a spring lattice.
///
/// Keywords are ``hibi_core::mud::MudParams``'s fields over the preset's (or the paper's
/// defaults): topology ("square", "hexagonal", "irregular"), boundary ("open", "periodic"),
/// solver ("explicit", "quasi-static"), drive ("shrink", "growth"), columns, rows, seed,
/// layer_thickness, element_size, long_step, short_step, shrink_ratio,
/// displacement_tolerance, damping_factor, density, young_modulus, shear_modulus,
/// break_stretch_mean, break_stretch_spread, break_stretch_size_exponent,
/// anisotropy_direction (radians), anisotropy_ratio, stiffness_anisotropy_ratio,
/// target_shrink, target_crack_density. A bad value raises ``ValueError`` naming the field.
#[pyclass(module = "hibi._hibi", name = "Mud")]
pub struct PyMud {
    run: Run,
}

#[pymethods]
impl PyMud {
    #[new]
    #[pyo3(signature = (preset=None, **kwargs))]
    fn new(py: Python<'_>, preset: Option<&str>, kwargs: Option<&Bound<'_, PyDict>>) -> PyResult<Self> {
        let p = params(preset, kwargs)?;
        let memory = p.memory().map_err(value_error)?;
        let run = py.detach(|| {
            RunTryBuilder { store: memory.allocate::<f32>(), mud_builder: |s| Mud::new(&p, s.buffers()) }.try_build()
        });
        Ok(PyMud { run: run.map_err(error)? })
    }

    /// Runs for at most about `budget` units of work (GIL released) and says where it stands.
    fn step(&mut self, py: Python<'_>, budget: u64) -> PyResult<PyMudProgress> {
        let run = &mut self.run;
        py.detach(|| run.with_mud_mut(|m| m.step(budget))).map(Into::into).map_err(error)
    }

    /// Runs to the end (GIL released). With `callback`, runs in steps of `budget` units and
    /// calls `callback(progress)` after each.
    #[pyo3(signature = (callback=None, budget=2_000_000))]
    fn run(&mut self, py: Python<'_>, callback: Option<&Bound<'_, PyAny>>, budget: u64) -> PyResult<PyMudProgress> {
        let Some(callback) = callback else {
            let run = &mut self.run;
            return py.detach(|| run.with_mud_mut(|m| m.run())).map(Into::into).map_err(error);
        };
        loop {
            let p = self.step(py, budget)?;
            let finished = p.finished;
            let p = Bound::new(py, p)?;
            callback.call1((p.clone(),))?;
            if finished {
                return Ok(*p.get());
            }
        }
    }

    /// Where the run stands.
    #[getter]
    fn progress(&self) -> PyMudProgress {
        self.run.with_mud(|m| m.progress()).into()
    }

    /// The parameters, every field by its Rust name.
    #[getter]
    fn params<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        self.run.with_mud(|m| params_dict(py, m.params()))
    }

    /// Width and height of the domain (one period when periodic), lattice units.
    #[getter]
    fn extent(&self) -> (f32, f32) {
        let [w, h] = self.run.with_mud(|m| m.extent());
        (w, h)
    }

    /// Crack statistics of the traced network, as a dict.
    fn statistics<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let s = self.run.with_mud(|m| m.statistics());
        let d = PyDict::new(py);
        d.set_item("crack_density", s.crack_density)?;
        d.set_item("cells", s.cells)?;
        d.set_item("mean_cell_area", s.mean_cell_area)?;
        d.set_item("cell_area_spread", s.cell_area_spread)?;
        d.set_item("junctions", s.junctions)?;
        d.set_item("t_junctions", s.t_junctions)?;
        d.set_item("mean_widest_junction_angle", s.mean_widest_junction_angle)?;
        d.set_item("dead_ends", s.dead_ends)?;
        Ok(d)
    }

    /// Every crack segment as an (n, 8) `float32` array: start x, y, end x, y, width at each
    /// end, break time at each end.
    fn segments<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let run = &self.run;
        let v = py.detach(|| {
            let mut v = Vec::new();
            run.with_mud(|m| m.for_each_segment(|s| v.extend([s.start, s.end, s.width, s.time].into_iter().flatten())));
            v
        });
        rows_f32(py, v, 8)
    }

    /// The traced crack network as a dict: `vertices` (v, 2) `float32`, `degree` and
    /// `on_border` (v) `uint32`; edges `from`, `to` (e) `uint32` (`0xFFFFFFFF`: none),
    /// `offsets` (e + 1) `int64` into `points` (p, 2) `float32`, `width` and `time` (p)
    /// `float32`.
    fn network<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let run = &self.run;
        let (vertices, edges, points) = py
            .detach(|| {
                run.with_mud(|m| {
                    let c = m.network_counts();
                    let mut vertices = vec![Default::default(); c.vertices];
                    let mut edges = vec![Default::default(); c.edges];
                    let mut points = vec![Default::default(); c.points];
                    m.network(&mut vertices, &mut edges, &mut points).map(|_| (vertices, edges, points))
                })
            })
            .map_err(error)?;
        let d = PyDict::new(py);
        let at: Vec<f32> = vertices.iter().flat_map(|v: &hibi_core::mud::NetworkVertex| v.at).collect();
        d.set_item("vertices", rows_f32(py, at, 2)?)?;
        d.set_item("degree", vertices.iter().map(|v| v.degree).collect::<Vec<u32>>().into_pyarray(py))?;
        d.set_item("on_border", vertices.iter().map(|v| v.on_border).collect::<Vec<u32>>().into_pyarray(py))?;
        let edges: Vec<hibi_core::mud::NetworkEdge> = edges;
        d.set_item("from", edges.iter().map(|e| e.from).collect::<Vec<u32>>().into_pyarray(py))?;
        d.set_item("to", edges.iter().map(|e| e.to).collect::<Vec<u32>>().into_pyarray(py))?;
        d.set_item("offsets", offsets(py, edges.iter().map(|e| e.point_count as usize)))?;
        let points: Vec<hibi_core::mud::NetworkPoint> = points;
        d.set_item("points", rows_f32(py, points.iter().flat_map(|p| p.at).collect(), 2)?)?;
        d.set_item("width", points.iter().map(|p| p.width).collect::<Vec<f32>>().into_pyarray(py))?;
        d.set_item("time", points.iter().map(|p| p.time).collect::<Vec<f32>>().into_pyarray(py))?;
        Ok(d)
    }

    /// The cells the traced network encloses, as rings (see `hibi.Rings`): `points` (n, 2)
    /// `float32` in lattice units, `offsets`, `area` (holes negative), `hole_of`; and
    /// `wrapping`, the boundaries that wrap around a periodic lattice (not written).
    fn cells<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let run = &self.run;
        let (rings, points, wrapping) = py
            .detach(|| {
                run.with_mud(|m| {
                    let c = m.cell_counts();
                    let mut rings = vec![Default::default(); c.rings];
                    let mut points = vec![[0.0f32; 2]; c.points];
                    m.cells(&mut rings, &mut points).map(|c| (rings, points, c.wrapping))
                })
            })
            .map_err(error)?;
        let d = crate::arrays::rings(py, &rings, points)?;
        d.set_item("wrapping", wrapping)?;
        Ok(d)
    }

    /// Draws `layers` (a name, or a sequence of names: mask, height, height16, normal,
    /// normal_rgb8, time, preview) with the GIL released. `width` defaults to 512 and
    /// `height` to the domain's aspect; the strokes to `MudRender::fit`'s. On `threads`
    /// threads, a band of rows each (the same arrays on any number).
    #[pyo3(signature = (layers=None, *, width=None, height=None, width_scale=None, min_width=None, groove_depth=None, offset=None, bump=None, until=None, threads=1))]
    #[allow(clippy::too_many_arguments)]
    fn render<'py>(
        &self,
        py: Python<'py>,
        layers: Option<&Bound<'py, PyAny>>,
        width: Option<u32>,
        height: Option<u32>,
        width_scale: Option<f32>,
        min_width: Option<f32>,
        groove_depth: Option<f32>,
        offset: Option<(f32, f32)>,
        bump: Option<f32>,
        until: Option<f32>,
        threads: usize,
    ) -> PyResult<Bound<'py, PyAny>> {
        let threads = crate::arrays::threads(threads)?;
        let (wanted, single) = layer_request(layers, "mask")?;
        let extent = self.run.with_mud(|m| m.extent());
        let fit = MudRender::fit(extent, width.unwrap_or(512).max(1));
        let r = MudRender {
            width: width.unwrap_or(fit.width),
            height: height.unwrap_or(fit.height),
            width_scale: width_scale.unwrap_or(fit.width_scale),
            min_width: min_width.unwrap_or(fit.min_width),
            groove_depth: groove_depth.unwrap_or(fit.groove_depth),
            offset: offset.map_or(fit.offset, |(x, y)| [x, y]),
            bump: bump.unwrap_or(fit.bump),
            until: until.unwrap_or(fit.until),
        };
        let mut out = wanted.buffers(r.width, r.height)?;
        let run = &self.run;
        py.detach(|| run.with_mud(|m| out.draw(threads, |tile, layers| m.render_tile(&r, tile, layers))))
            .map_err(value_error)?;
        rendered(py, out, single)
    }

    fn __repr__(&self) -> String {
        self.run.with_mud(|m| {
            let p = m.params();
            format!("Mud(columns={}, rows={}, seed={}, {:?})", p.columns, p.rows, p.seed, m.progress())
        })
    }

    /// Every preset name (the paper's figures).
    #[staticmethod]
    fn presets<'py>(py: Python<'py>) -> PyResult<Bound<'py, PyTuple>> {
        PyTuple::new(py, hibi_core::mud::PRESETS)
    }
}
