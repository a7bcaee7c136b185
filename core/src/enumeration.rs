//! Enumerations whose numbers are part of the C API (and so of the determinism contract).
//!
//! Each is declared once with [`enumeration!`]: the `#[repr(u32)]` enum, `ALL` (every
//! variant, in declaration order) and `from_u32`, which the C layer reads a `uint32_t` field
//! with. Variants are numbered 0, 1, 2, ... in declaration order, as the error lists'
//! ([`crate::error`]), unless they give their numbers (the random streams, whose numbers are
//! keys with gaps between the models). The C constants (`HIBI_MUD_SQUARE`, ...) are checked
//! against the numbers when `hibi` compiles, so a reordering cannot go unnoticed.

/// Declares an enumeration (see the module docs):
///
/// ```ignore
/// enumeration! {
///     /// What happens at the lattice's edges.
///     pub enum Boundary {
///         /// Free edges.
///         Open,
///         /// The lattice wraps around.
///         Periodic,
///     }
///     default Open
/// }
/// ```
macro_rules! enumeration {
    (
        $(#[$meta:meta])*
        pub enum $name:ident {
            $( $(#[$variant_meta:meta])* $variant:ident $(= $number:literal)?, )+
        }
        $(default $default:ident)?
    ) => {
        $(#[$meta])*
        #[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
        #[repr(u32)]
        pub enum $name {
            $( $(#[$variant_meta])* $variant $(= $number)?, )+
        }

        impl $name {
            /// Every variant, in declaration order.
            pub const ALL: [$name; [$(stringify!($variant)),+].len()] = [$($name::$variant),+];

            /// The variant numbered `number`, if there is one.
            pub const fn from_u32(number: u32) -> Option<Self> {
                let mut i = 0;
                while i < Self::ALL.len() {
                    if Self::ALL[i] as u32 == number {
                        return Some(Self::ALL[i]);
                    }
                    i += 1;
                }
                None
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
