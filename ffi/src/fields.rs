//! The C structs of parameters and their core twins, converted both ways from one list of
//! field names per struct ([`convert!`]). A C struct has the core struct's field names; an
//! enumeration or a flag is a `uint32_t` in C ([`Field`]), checked on the way in.

/// A C field and the core field it stands for.
pub(crate) trait Field<Core>: Sized {
    /// The core value; `None` where a C enumeration or flag holds no valid value.
    fn to_core(&self) -> Option<Core>;
    /// The C value.
    fn from_core(core: &Core) -> Self;
}

/// Fields that are the same type in C and in the core.
macro_rules! same {
    ($($t:ty),*) => {$(
        impl Field<$t> for $t {
            fn to_core(&self) -> Option<$t> {
                Some(*self)
            }
            fn from_core(core: &$t) -> Self {
                *core
            }
        }
    )*};
}
same!(u32, u64, f32);

impl<C: Field<R> + Copy, R: Copy + Default, const N: usize> Field<[R; N]> for [C; N] {
    fn to_core(&self) -> Option<[R; N]> {
        let mut out = [R::default(); N];
        for (o, c) in out.iter_mut().zip(self) {
            *o = c.to_core()?;
        }
        Some(out)
    }
    fn from_core(core: &[R; N]) -> Self {
        core.map(|r| C::from_core(&r))
    }
}

/// A flag: 0 or 1 in C.
impl Field<bool> for u32 {
    fn to_core(&self) -> Option<bool> {
        match self {
            0 => Some(false),
            1 => Some(true),
            _ => None,
        }
    }
    fn from_core(core: &bool) -> Self {
        u32::from(*core)
    }
}

/// The core's enumerations as their numbers in C (`from_u32` is declared with each).
macro_rules! enumeration {
    ($($t:ty),+ $(,)?) => {$(
        impl Field<$t> for u32 {
            fn to_core(&self) -> Option<$t> {
                <$t>::from_u32(*self)
            }
            fn from_core(core: &$t) -> Self {
                *core as u32
            }
        }
    )+};
}

enumeration!(
    hibi_core::Spread,
    hibi_core::mud::Topology,
    hibi_core::mud::Boundary,
    hibi_core::mud::Solver,
    hibi_core::mud::Drive,
    hibi_core::skin::SiteLayout,
);

/// [`Field`] for a C struct whose fields are the core struct's, listed once. With a cookie,
/// the C struct also carries the marker its `_default` function sets: `from_core` sets it;
/// check it before `to_core`.
macro_rules! convert {
    ($c:ident <=> $core:ident $(, cookie: $cookie:ident)? $(, reserved: $reserved:ident)? { $($field:ident),+ $(,)? }) => {
        impl $crate::fields::Field<$core> for $c {
            fn to_core(&self) -> Option<$core> {
                Some($core { $($field: $crate::fields::Field::to_core(&self.$field)?),+ })
            }
            fn from_core(p: &$core) -> Self {
                $c { $(cookie: $cookie,)? $($reserved: 0,)? $($field: $crate::fields::Field::from_core(&p.$field)),+ }
            }
        }
    };
}
pub(crate) use convert;
