//! Errors that name what the caller wrote.
//!
//! Every parameter-error list is declared once with [`error_list!`]: the enum (numbered from
//! 0 in the order written, which the C statuses follow), `ALL` (every error in number order,
//! checked when the crate compiles), `message()` (the field and its range, NUL-terminated for
//! C), `Display` and `core::error::Error`. The errors that wrap them (`MudError`, ...)
//! implement `Display` and `Error` by hand, with the parameter error as their source.

/// Declares a list of errors (see the module docs):
///
/// ```ignore
/// error_list! {
///     /// A parameter out of its range.
///     pub enum ExampleError {
///         /// `width` must be > 0.
///         Width => c"example: width must be > 0",
///     }
/// }
/// ```
macro_rules! error_list {
    (
        $(#[$meta:meta])*
        pub enum $name:ident {
            $( $(#[$variant_meta:meta])* $variant:ident => $message:literal, )*
        }
    ) => {
        $(#[$meta])*
        #[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
        #[repr(u32)]
        pub enum $name {
            $( $(#[$variant_meta])* $variant, )*
        }

        impl $name {
            /// Every error, in the order of their numbers (`ALL[e as usize] == e`).
            pub const ALL: [$name; [$(stringify!($variant)),*].len()] = [$($name::$variant),*];

            /// What is wrong: the field's name and its range, NUL-terminated for C.
            pub const fn message(self) -> &'static core::ffi::CStr {
                match self {
                    $( $name::$variant => $message, )*
                }
            }
        }

        // `ALL` lists every error in number order (the C statuses are numbered from it).
        const _: () = {
            let mut i = 0;
            while i < $name::ALL.len() {
                assert!($name::ALL[i] as usize == i);
                i += 1;
            }
        };

        impl core::fmt::Display for $name {
            fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
                f.write_str(self.message().to_str().unwrap_or(stringify!($name)))
            }
        }

        impl core::error::Error for $name {}
    };
}

pub(crate) use error_list;

#[cfg(test)]
mod tests {
    extern crate std;
    use std::collections::BTreeSet;
    use std::string::ToString;

    use crate::glass::GlassParamError;
    use crate::mud::MudParamError;
    use crate::skin::{ShadeError, SkinParamError};

    /// Every list's messages are distinct and name their model.
    fn distinct(prefix: &str, messages: impl Iterator<Item = std::string::String>) {
        let mut seen = BTreeSet::new();
        for m in messages {
            assert!(m.starts_with(prefix), "{m}");
            assert!(seen.insert(m.clone()), "repeated: {m}");
        }
    }

    #[test]
    fn every_error_list_has_distinct_messages_naming_its_model() {
        distinct("mud: ", MudParamError::ALL.iter().map(|e| e.to_string()));
        distinct("glass: ", GlassParamError::ALL.iter().map(|e| e.to_string()));
        distinct("skin: ", SkinParamError::ALL.iter().map(|e| e.to_string()));
        distinct("skin: ", ShadeError::ALL.iter().map(|e| e.to_string()));
    }

    #[test]
    fn wrapping_errors_say_what_they_wrap_and_give_it_as_their_source() {
        use core::error::Error;
        let param = MudParamError::Rows;
        let wrapped = crate::mud::MudError::Param(param);
        assert_eq!(wrapped.to_string(), param.to_string());
        assert_eq!(wrapped.source().map(|s| s.to_string()), Some(param.to_string()));
        let short = crate::mud::MudError::BufferTooSmall { needed: 42 };
        assert!(short.to_string().contains("42") && short.source().is_none());
        let glass = crate::glass::GlassError::Param(GlassParamError::Speed);
        assert_eq!(glass.to_string(), GlassParamError::Speed.to_string());
        let skin = crate::skin::SkinError::Shade(ShadeError::Ambient);
        assert_eq!(skin.source().map(|s| s.to_string()), Some(ShadeError::Ambient.to_string()));
        let raster = crate::raster::RasterError::BufferTooSmall { layer: crate::raster::Layer::Mask, needed: 7 };
        assert!(raster.to_string().starts_with("render: ") && raster.to_string().contains('7'));
    }
}
