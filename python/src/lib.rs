//! `hibi._hibi`: the models of `hibi-core` for Python. The bindings hold no model logic: each
//! class converts its keyword arguments into the core's parameter struct, owns the memory the
//! core asks for, and calls the core's public API with the GIL released; results come back as
//! NumPy arrays that take over the Rust buffers (no copy).

use pyo3::exceptions::{PyRuntimeError, PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyBytes, PyDict, PyList, PyString};

mod arrays;
mod glass;
mod mud;
mod reference;
mod skin;

pub use arrays::{Rendered, Wanted};

/// A `ValueError` with the core's message (which names the field).
pub fn value_error(message: impl std::fmt::Display) -> PyErr {
    PyValueError::new_err(message.to_string())
}

/// A `RuntimeError`: something the parameters could not have prevented.
pub fn runtime_error(message: impl std::fmt::Display) -> PyErr {
    PyRuntimeError::new_err(message.to_string())
}

/// A keyword argument's value as `T`, or a `TypeError` naming the model and the field.
pub fn field<'py, T: FromPyObjectOwned<'py>>(model: &str, name: &str, value: &Bound<'py, PyAny>) -> PyResult<T> {
    value.extract::<T>().map_err(|e| {
        let e: PyErr = e.into();
        PyTypeError::new_err(format!("{model}: {name}: {}", e.value(value.py())))
    })
}

/// One of `choices` (the enumeration's names as the CLI spells them, `-` or `_`), or a
/// `ValueError` naming the field and the choices.
pub fn choice<'py, T: Copy>(model: &str, name: &str, value: &Bound<'py, PyAny>, choices: &[(&str, T)]) -> PyResult<T> {
    let text: String = field(model, name, value)?;
    let wanted = text.replace('-', "_");
    choices.iter().find(|(n, _)| n.replace('-', "_") == wanted).map(|&(_, v)| v).ok_or_else(|| {
        let names: Vec<&str> = choices.iter().map(|(n, _)| *n).collect();
        value_error(format!("{model}: {name} must be one of {}, not {text:?}", names.join(", ")))
    })
}

/// The name of a `choices` value.
pub fn choice_name<T: PartialEq + Copy>(value: T, choices: &[(&'static str, T)]) -> &'static str {
    choices.iter().find(|(_, v)| *v == value).map_or("?", |(n, _)| n)
}

/// An unknown keyword argument, as Python reports one.
pub fn unknown(model: &str, name: &str) -> PyErr {
    PyTypeError::new_err(format!("{model}() got an unexpected keyword argument '{name}'"))
}

/// The layers asked for: one name (returns the array) or a sequence of names (returns a dict).
pub fn layer_request(layers: Option<&Bound<'_, PyAny>>, default: &str) -> PyResult<(Wanted, bool)> {
    let Some(layers) = layers else {
        return Ok((Wanted::of(&[default.to_owned()])?, true));
    };
    if let Ok(name) = layers.cast::<PyString>() {
        return Ok((Wanted::of(&[name.extract::<String>()?])?, true));
    }
    let names: Vec<String> = layers
        .extract()
        .map_err(|_| PyTypeError::new_err("render: layers must be a layer name or a sequence of layer names"))?;
    Ok((Wanted::of(&names)?, false))
}

/// A finished render as Python values: the array, or a dict of them.
pub fn rendered<'py>(py: Python<'py>, out: Rendered, single: bool) -> PyResult<Bound<'py, PyAny>> {
    let dict = out.into_dict(py)?;
    if single {
        let (_, value) = dict.iter().next().ok_or_else(|| runtime_error("render: no layer drawn"))?;
        Ok(value)
    } else {
        Ok(dict.into_any())
    }
}

/// A PNG file's bytes for an image array: `uint8` of shape (h, w) (grey), (h, w, 3) (RGB) or
/// (h, w, 4) (RGBA), or `uint16` of shape (h, w) (16-bit grey). The encoder and its settings
/// are fixed (the `png` crate at the version Cargo.lock pins, balanced compression, no
/// time stamp), so the same pixels give the same bytes.
#[pyfunction]
fn encode_png<'py>(py: Python<'py>, image: &Bound<'py, PyAny>) -> PyResult<Bound<'py, PyBytes>> {
    use numpy::{PyArrayDyn, PyArrayMethods, PyUntypedArrayMethods};
    let (colour, depth, width, height, data) = if let Ok(a) = image.cast::<PyArrayDyn<u8>>() {
        let shape = a.shape().to_vec();
        let colour = match shape.as_slice() {
            [_, _] => png::ColorType::Grayscale,
            [_, _, 3] => png::ColorType::Rgb,
            [_, _, 4] => png::ColorType::Rgba,
            _ => return Err(value_error("encode_png: a uint8 image has shape (h, w), (h, w, 3) or (h, w, 4)")),
        };
        let data = a.to_vec().map_err(|_| value_error("encode_png: the image must be contiguous"))?;
        (colour, png::BitDepth::Eight, shape[1], shape[0], data)
    } else if let Ok(a) = image.cast::<PyArrayDyn<u16>>() {
        let shape = a.shape().to_vec();
        if shape.len() != 2 {
            return Err(value_error("encode_png: a uint16 image has shape (h, w)"));
        }
        let data = a.to_vec().map_err(|_| value_error("encode_png: the image must be contiguous"))?;
        let bytes = data.iter().flat_map(|v| v.to_be_bytes()).collect();
        (png::ColorType::Grayscale, png::BitDepth::Sixteen, shape[1], shape[0], bytes)
    } else {
        return Err(PyTypeError::new_err("encode_png: image must be a uint8 or uint16 NumPy array"));
    };
    let (Ok(w), Ok(h)) = (u32::try_from(width), u32::try_from(height)) else {
        return Err(value_error("encode_png: the image is too large for PNG"));
    };
    if w == 0 || h == 0 {
        return Err(value_error("encode_png: the image must have pixels"));
    }
    let bytes = py.detach(move || {
        let mut out = Vec::new();
        let mut e = png::Encoder::new(&mut out, w, h);
        e.set_color(colour);
        e.set_depth(depth);
        e.set_compression(png::Compression::Balanced);
        let mut writer = e.write_header().map_err(|e| e.to_string())?;
        writer.write_image_data(&data).map_err(|e| e.to_string())?;
        writer.finish().map_err(|e| e.to_string())?;
        Ok::<_, String>(out)
    });
    Ok(PyBytes::new(py, &bytes.map_err(runtime_error)?))
}

/// Every preset name of each model, as `{"mud": [...], "glass": [...], "skin": [...]}`.
#[pyfunction]
fn presets(py: Python<'_>) -> PyResult<Bound<'_, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("mud", PyList::new(py, hibi_core::mud::PRESETS)?)?;
    d.set_item("glass", PyList::new(py, hibi_core::glass::PRESETS)?)?;
    d.set_item("skin", PyList::new(py, hibi_core::skin::PRESETS)?)?;
    Ok(d)
}

#[pymodule]
fn _hibi(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<mud::PyMud>()?;
    m.add_class::<glass::PyGlass>()?;
    m.add_class::<skin::PySkin>()?;
    m.add_class::<mud::PyMudProgress>()?;
    m.add_class::<glass::PyGlassProgress>()?;
    m.add_class::<skin::PySkinProgress>()?;
    m.add_function(wrap_pyfunction!(encode_png, m)?)?;
    m.add_function(wrap_pyfunction!(presets, m)?)?;
    m.add_function(wrap_pyfunction!(reference::_reference, m)?)?;
    m.add("LAYERS", arrays::LAYER_NAMES.to_vec())?;
    Ok(())
}
