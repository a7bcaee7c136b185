//! # hibi-ffi: the C ABI of hibi
//!
//! Builds `libhibi.so` and `libhibi.a`; the header is `include/hibi.h`, generated from this
//! crate by cbindgen. Conventions (after Box2D v3 and rustls-ffi):
//!
//! - every name starts with `hibi_`; functions are `hibi_<object>_<verb>`;
//! - fallible functions return a [`hibi_status`] (`HIBI_OK` = 0) and write their outputs
//!   through out-parameters only on success; `hibi_status_string` explains any code;
//! - every buffer pointer is followed by its length; NULL, misaligned and short buffers and
//!   out-of-range enumeration values are statuses, never crashes;
//! - objects are created in library memory (`*_create` / `*_destroy`) or in caller memory
//!   (`*_memory_size` + `*_create_in`);
//! - every exported function runs inside one guard: no panic ever unwinds into C, and none
//!   prints (the first call installs a panic hook that is silent inside hibi's calls and
//!   passes every other panic to the hook before it).
#![allow(non_camel_case_types)]
// Doc comments here are the C header's comments (cbindgen): units read "[px]", not links.
#![allow(rustdoc::broken_intra_doc_links)]
#![deny(unsafe_op_in_unsafe_fn)]

use core::ffi::c_char;

pub mod constants;
mod fields;
pub mod glass;
mod guard;
pub mod mud;
pub mod mud_builds;
mod object;
pub mod polygons;
mod raster;
pub mod rng;
pub mod skin;
pub mod status;

pub use constants::*;
pub use glass::*;
pub use mud::*;
pub use mud_builds::*;
pub use polygons::*;
pub use rng::*;
pub use skin::*;
pub use status::*;

/// The library's version, "MAJOR.MINOR.PATCH", as a static NUL-terminated string.
#[unsafe(no_mangle)]
pub extern "C" fn hibi_version() -> *const c_char {
    guard::guard_query(|| concat!(env!("CARGO_PKG_VERSION"), "\0").as_ptr().cast::<c_char>())
}

/// The major version, as in `hibi_version()` (`CARGO_PKG_VERSION_MAJOR`; checked when the
/// library is built).
pub const HIBI_VERSION_MAJOR: u32 = 0;
/// The minor version, as in `hibi_version()`.
pub const HIBI_VERSION_MINOR: u32 = 1;
/// The patch version, as in `hibi_version()`.
pub const HIBI_VERSION_PATCH: u32 = 0;

/// A decimal number at compile time (the version fields cargo passes).
const fn parse_version(field: &str) -> u32 {
    let bytes = field.as_bytes();
    let mut value = 0;
    let mut i = 0;
    while i < bytes.len() {
        value = value * 10 + (bytes[i] - b'0') as u32;
        i += 1;
    }
    value
}

// The header's version macros must match the package version: bump them together.
const _: () = assert!(
    HIBI_VERSION_MAJOR == parse_version(env!("CARGO_PKG_VERSION_MAJOR"))
        && HIBI_VERSION_MINOR == parse_version(env!("CARGO_PKG_VERSION_MINOR"))
        && HIBI_VERSION_PATCH == parse_version(env!("CARGO_PKG_VERSION_PATCH")),
    "HIBI_VERSION_MAJOR/MINOR/PATCH differ from the package version in Cargo.toml"
);
