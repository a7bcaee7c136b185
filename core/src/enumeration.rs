//! Enumerations whose numbers are part of the C API (and so of the determinism contract).
//!
//! Each is declared once with [`enumeration!`]: the `#[repr(u32)]` enum with its numbers,
//! `ALL` (every variant, in declaration order) and `from_u32`, which the C layer reads a
//! `uint32_t` field with. The C constants (`HIBI_MUD_SQUARE`, ...) are checked against the
//! numbers when `hibi` compiles.

/// Declares an enumeration (see the module docs):
///
/// ```ignore
/// enumeration! {
///     /// What happens at the lattice's edges.
///     pub enum Boundary {
///         /// Free edges.
///         Open = 0,
///     }
///     default Open
/// }
/// ```
macro_rules! enumeration {
    (
        $(#[$meta:meta])*
        pub enum $name:ident {
            $( $(#[$variant_meta:meta])* $variant:ident = $number:literal, )+
        }
        $(default $default:ident)?
    ) => {
        $(#[$meta])*
        #[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
        #[repr(u32)]
        pub enum $name {
            $( $(#[$variant_meta])* $variant = $number, )+
        }

        impl $name {
            /// Every variant, in declaration order.
            pub const ALL: [$name; [$(stringify!($variant)),+].len()] = [$($name::$variant),+];

            /// The variant numbered `number`, if there is one.
            pub const fn from_u32(number: u32) -> Option<Self> {
                match number {
                    $( $number => Some($name::$variant), )+
                    _ => None,
                }
            }
        }

        $(
            impl Default for $name {
                fn default() -> Self {
                    $name::$default
                }
            }
        )?
    };
}
pub(crate) use enumeration;
