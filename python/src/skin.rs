//! `hibi.Skin`: Model C, skin from hierarchical Voronoi cells, over `hibi_core::skin`.

use hibi_core::Spread;
use hibi_core::skin::{
    LevelParams, MAX_LEVELS, MAX_SEGMENTS, Profile, ShadeParams, SiteLayout, Skin, SkinError, SkinParams, SkinProgress,
    SkinRender, SkinStore,
};
use numpy::IntoPyArray;
use ouroboros::self_referencing;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList, PyTuple};

use crate::arrays::{offsets, rows_f64, rows_i64};
use crate::{choice, choice_name, field, layer_request, rendered, runtime_error, unknown, value_error};

const LAYOUTS: [(&str, SiteLayout); 3] =
    [("triangular", SiteLayout::Triangular), ("square", SiteLayout::Square), ("random", SiteLayout::Random)];
const SPREADS: [(&str, Spread); 2] = [("normal", Spread::Normal), ("uniform", Spread::Uniform)];

/// One level's keywords over `l`.
fn level(k: usize, l: &mut LevelParams, d: &Bound<'_, PyDict>) -> PyResult<()> {
    for (key, value) in d.iter() {
        let key: String = key.extract()?;
        let name = format!("level[{k}].{key}");
        match key.as_str() {
            "spacing" => l.spacing = field("skin", &name, &value)?,
            "perturbation" => l.perturbation = field("skin", &name, &value)?,
            "perturbation_decay" => l.perturbation_decay = field("skin", &name, &value)?,
            "perturbation_depth" => l.perturbation_depth = field("skin", &name, &value)?,
            "stretch" => {
                let (x, y): (f32, f32) = field("skin", &name, &value)?;
                l.stretch = [x, y];
            }
            "roundness" => l.roundness = field("skin", &name, &value)?,
            "profile" => {
                let points: Vec<(f32, f32)> = field("skin", &name, &value)?;
                let n = points.len();
                if n < 4 || !(n - 1).is_multiple_of(3) || n > 3 * MAX_SEGMENTS + 1 {
                    return Err(value_error(format!(
                        "skin: {name} must be 3k + 1 points (x', z) for k = 1..={MAX_SEGMENTS} Bezier segments, not {n}"
                    )));
                }
                let mut p = Profile::cubic([[0.0; 2]; 4]);
                p.segments = ((n - 1) / 3) as u32;
                for (slot, (x, z)) in p.points.iter_mut().zip(points) {
                    *slot = [x, z];
                }
                l.profile = p;
            }
            _ => return Err(unknown("Skin", &name)),
        }
    }
    Ok(())
}

/// The parameters: the preset's (or the paper's defaults), then every keyword given;
/// `level` is a list of dicts, one per level from the coarsest, each over the preset's.
fn params(preset: Option<&str>, kwargs: Option<&Bound<'_, PyDict>>) -> PyResult<SkinParams> {
    let mut p = match preset {
        Some(name) => hibi_core::skin::preset(name).ok_or_else(|| {
            value_error(format!("skin: preset must be one of {}, not {name:?}", hibi_core::skin::PRESETS.join(", ")))
        })?,
        None => SkinParams::default(),
    };
    for (key, value) in kwargs.into_iter().flat_map(|d| d.iter()) {
        let key: String = key.extract()?;
        match key.as_str() {
            "width" => p.width = field("skin", &key, &value)?,
            "height" => p.height = field("skin", &key, &value)?,
            "seed" => p.seed = field("skin", &key, &value)?,
            "layout" => p.layout = choice("skin", &key, &value, &LAYOUTS)?,
            "jitter" => p.jitter = choice("skin", &key, &value, &SPREADS)?,
            "jitter_ratio" => p.jitter_ratio = field("skin", &key, &value)?,
            "periodic" => p.periodic = field("skin", &key, &value)?,
            "levels" => p.levels = field("skin", &key, &value)?,
            "level" => {
                let list = value.cast::<PyList>().map_err(|_| {
                    pyo3::exceptions::PyTypeError::new_err("skin: level must be a list of dicts, one per level")
                })?;
                if list.len() > MAX_LEVELS {
                    return Err(value_error(format!("skin: level has at most {MAX_LEVELS} entries")));
                }
                for (k, d) in list.iter().enumerate() {
                    let d = d.cast::<PyDict>().map_err(|_| {
                        pyo3::exceptions::PyTypeError::new_err(format!("skin: level[{k}] must be a dict"))
                    })?;
                    level(k, &mut p.level[k], d)?;
                }
            }
            _ => return Err(unknown("Skin", &key)),
        }
    }
    Ok(p)
}

fn params_dict<'py>(py: Python<'py>, p: &SkinParams) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("width", p.width)?;
    d.set_item("height", p.height)?;
    d.set_item("seed", p.seed)?;
    d.set_item("layout", choice_name(p.layout, &LAYOUTS))?;
    d.set_item("jitter", choice_name(p.jitter, &SPREADS))?;
    d.set_item("jitter_ratio", p.jitter_ratio)?;
    d.set_item("periodic", p.periodic)?;
    d.set_item("levels", p.levels)?;
    let levels = PyList::empty(py);
    for l in p.level.iter().take((p.levels as usize).min(MAX_LEVELS)) {
        let e = PyDict::new(py);
        e.set_item("spacing", l.spacing)?;
        e.set_item("perturbation", l.perturbation)?;
        e.set_item("perturbation_decay", l.perturbation_decay)?;
        e.set_item("perturbation_depth", l.perturbation_depth)?;
        e.set_item("stretch", (l.stretch[0], l.stretch[1]))?;
        e.set_item("profile", l.profile.used().iter().map(|q| (q[0], q[1])).collect::<Vec<_>>())?;
        e.set_item("roundness", l.roundness)?;
        levels.append(e)?;
    }
    d.set_item("level", levels)?;
    Ok(d)
}

fn error(e: SkinError) -> PyErr {
    match e {
        SkinError::Param(p) => value_error(p),
        SkinError::Shade(s) => value_error(s),
        SkinError::Level => value_error("skin: cell_level must be below levels"),
        SkinError::Raster(r) => value_error(r),
        other => runtime_error(format!("skin: {other:?}")),
    }
}

#[self_referencing]
struct Surface {
    store: SkinStore,
    #[borrows(mut store)]
    #[not_covariant]
    skin: Skin<'this, f32>,
}

/// Where a skin's build stands (`hibi_core::skin::SkinProgress`).
#[pyclass(module = "hibi._hibi", name = "SkinProgress", frozen, get_all, skip_from_py_object)]
#[derive(Clone, Copy)]
pub struct PySkinProgress {
    /// Cells built, all levels.
    cells: u32,
    /// Level-0 centre points whose cells are built.
    roots: u32,
    /// Level-0 centre points in all.
    root_total: u32,
    /// Every cell is built.
    finished: bool,
    /// A cell outline or a parent's centre points outgrew their capacity: the build stopped.
    capacity_reached: bool,
    /// Work done, in the units of `step`'s budget.
    work: u64,
}

#[pymethods]
impl PySkinProgress {
    fn __repr__(&self) -> String {
        let b = |v: bool| if v { "True" } else { "False" };
        format!(
            "SkinProgress(cells={}, roots={}, root_total={}, finished={}, capacity_reached={}, work={})",
            self.cells,
            self.roots,
            self.root_total,
            b(self.finished),
            b(self.capacity_reached),
            self.work
        )
    }
}

impl From<SkinProgress> for PySkinProgress {
    fn from(p: SkinProgress) -> Self {
        PySkinProgress {
            cells: p.cells,
            roots: p.roots,
            root_total: p.root_total,
            finished: p.finished,
            capacity_reached: p.capacity_reached,
            work: p.work,
        }
    }
}

/// Model C (Ishii et al.): skin as hierarchical Voronoi cells.
///
/// Keywords are ``hibi_core::skin::SkinParams``'s fields over the preset's (or the paper's
/// defaults): width, height, seed, layout ("triangular", "square", "random"), jitter
/// ("normal", "uniform"), jitter_ratio, periodic, levels, and level: a list of dicts, one per
/// level from the coarsest, with spacing, perturbation, perturbation_decay,
/// perturbation_depth, stretch (x, y), profile (3k + 1 points (x', z)) and roundness.
#[pyclass(module = "hibi._hibi", name = "Skin")]
pub struct PySkin {
    surface: Surface,
}

#[pymethods]
impl PySkin {
    #[new]
    #[pyo3(signature = (preset=None, **kwargs))]
    fn new(py: Python<'_>, preset: Option<&str>, kwargs: Option<&Bound<'_, PyDict>>) -> PyResult<Self> {
        let p = params(preset, kwargs)?;
        let memory = p.memory().map_err(value_error)?;
        let surface = py.detach(|| {
            SurfaceTryBuilder { store: memory.allocate(), skin_builder: |s| Skin::new(&p, s.buffers()) }.try_build()
        });
        Ok(PySkin { surface: surface.map_err(error)? })
    }

    /// Builds cells for at most about `budget` units of work (GIL released).
    fn step(&mut self, py: Python<'_>, budget: u64) -> PySkinProgress {
        let s = &mut self.surface;
        py.detach(|| s.with_skin_mut(|k| k.step(budget))).into()
    }

    /// Builds every cell (GIL released). With `callback`, in steps of `budget` units, calling
    /// `callback(progress)` after each.
    #[pyo3(signature = (callback=None, budget=1_000_000))]
    fn run(&mut self, py: Python<'_>, callback: Option<&Bound<'_, PyAny>>, budget: u64) -> PyResult<PySkinProgress> {
        let Some(callback) = callback else {
            let s = &mut self.surface;
            return Ok(py.detach(|| s.with_skin_mut(|k| k.run())).into());
        };
        loop {
            let p = self.step(py, budget);
            callback.call1((Bound::new(py, p)?,))?;
            if p.finished || p.capacity_reached {
                return Ok(p);
            }
        }
    }

    /// Where the build stands.
    #[getter]
    fn progress(&self) -> PySkinProgress {
        self.surface.with_skin(|k| k.progress()).into()
    }

    /// The parameters, every field by its Rust name (`level`: one dict per level).
    #[getter]
    fn params<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        self.surface.with_skin(|k| params_dict(py, k.params()))
    }

    /// Every cell built: `points` (n, 2) `float64` px (the outline's fixed point divided
    /// by 2^`fixed_point_bits`), `fixed` (n, 2) `int64` (the outline as the core keeps it),
    /// `offsets` (cells + 1) `int64`; per cell `level`, `parent` (`0xFFFFFFFF` at level 0),
    /// `site` (`uint32`) and `centre` (cells, 2) `float64` px.
    fn cells<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let s = &self.surface;
        let (fixed, counts, levels, parents, sites, centres, bits) = py.detach(|| {
            s.with_skin(|k| {
                let cells = k.cells();
                let mut fixed = Vec::new();
                let mut counts = Vec::with_capacity(cells.len());
                for c in cells {
                    let o = k.outline(c);
                    fixed.extend(o.iter().flatten());
                    counts.push(o.len());
                }
                let levels: Vec<u32> = cells.iter().map(|c| c.level).collect();
                let parents: Vec<u32> = cells.iter().map(|c| c.parent).collect();
                let sites: Vec<u32> = cells.iter().map(|c| c.site).collect();
                let centres: Vec<i64> = cells.iter().flat_map(|c| c.centre).collect();
                (fixed, counts, levels, parents, sites, centres, k.fixed_point_bits())
            })
        });
        let unit = (bits as f64).exp2();
        let d = PyDict::new(py);
        d.set_item("points", rows_f64(py, fixed.iter().map(|&v| v as f64 / unit).collect(), 2)?)?;
        d.set_item("fixed", rows_i64(py, fixed, 2)?)?;
        d.set_item("offsets", offsets(py, counts.into_iter()))?;
        d.set_item("level", levels.into_pyarray(py))?;
        d.set_item("parent", parents.into_pyarray(py))?;
        d.set_item("site", sites.into_pyarray(py))?;
        d.set_item("centre", rows_f64(py, centres.iter().map(|&v| v as f64 / unit).collect(), 2)?)?;
        d.set_item("fixed_point_bits", bits)?;
        Ok(d)
    }

    /// Draws `layers` (a name, or a sequence of: mask, height, height16, normal,
    /// normal_rgb8, cell, preview) over the surface's width × height pixels, GIL released.
    /// `cell_level` picks the level of the cell map; the rest light the preview. On `threads`
    /// threads, a band of rows each (the same arrays on any number).
    #[pyo3(signature = (layers=None, *, cell_level=0, light=None, ridge=None, furrow=None, ambient=None, specular=None, threads=1))]
    #[allow(clippy::too_many_arguments)]
    fn render<'py>(
        &self,
        py: Python<'py>,
        layers: Option<&Bound<'py, PyAny>>,
        cell_level: u32,
        light: Option<[f32; 3]>,
        ridge: Option<[f32; 3]>,
        furrow: Option<[f32; 3]>,
        ambient: Option<f32>,
        specular: Option<f32>,
        threads: usize,
    ) -> PyResult<Bound<'py, PyAny>> {
        let threads = crate::arrays::threads(threads)?;
        let (wanted, single) = layer_request(layers, "height")?;
        let d = ShadeParams::default();
        let shade = ShadeParams {
            light: light.unwrap_or(d.light),
            ridge: ridge.unwrap_or(d.ridge),
            furrow: furrow.unwrap_or(d.furrow),
            ambient: ambient.unwrap_or(d.ambient),
            specular: specular.unwrap_or(d.specular),
        };
        let r = SkinRender { cell_level, shade };
        let (w, h) = self.surface.with_skin(|k| (k.params().width, k.params().height));
        let mut out = wanted.buffers(w, h)?;
        let s = &self.surface;
        py.detach(|| s.with_skin(|k| out.draw(threads, |tile, layers| k.render_tile(&r, tile, layers))))
            .map_err(error)?;
        rendered(py, out, single)
    }

    fn __repr__(&self) -> String {
        self.surface.with_skin(|k| {
            let p = k.params();
            format!(
                "Skin(width={}, height={}, levels={}, seed={}, {:?})",
                p.width,
                p.height,
                p.levels,
                p.seed,
                k.progress()
            )
        })
    }

    /// Every preset name (the paper's figures).
    #[staticmethod]
    fn presets<'py>(py: Python<'py>) -> PyResult<Bound<'py, PyTuple>> {
        PyTuple::new(py, hibi_core::skin::PRESETS)
    }
}
