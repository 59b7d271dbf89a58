//! Named choices: the one table of names of each option enum (presets, row models, `R_0`
//! sources, solvers, scoring models), read by [`FromStr`](std::str::FromStr), written by
//! [`Display`](std::fmt::Display) and, with the command line, offered by `clap`, so the
//! command line, the Python package and the reports cannot spell a choice differently.

use thiserror::Error;

/// A name that is not one of a choice's names.
#[derive(Debug, Clone, PartialEq, Eq, Error)]
#[error("unknown {what} `{name}` (expected {})", or_list(.expected))]
pub struct UnknownName {
    /// What was named (`preset`, `rows`, `solver`, ...).
    pub what: &'static str,
    /// The name given.
    pub name: String,
    /// The names there are.
    pub expected: &'static [&'static str],
}

/// `a`, `a or b`, `a, b or c`.
pub fn or_list(names: &[&str]) -> String {
    match names {
        [] => String::new(),
        [one] => one.to_string(),
        [init @ .., last] => format!("{} or {last}", init.join(", ")),
    }
}

/// Implements the name table of a fieldless enum: `ALL` and `NAMES` in table order,
/// `name()`, `Display`, `FromStr` (error [`UnknownName`] naming `$what`) and, with the
/// `cli` feature, `clap::ValueEnum`.
macro_rules! name_table {
    ($ty:ident, $what:literal, [$($variant:ident = $name:literal),+ $(,)?]) => {
        impl $ty {
            /// Every value, in the order of its name table.
            pub const ALL: &'static [$ty] = &[$($ty::$variant),+];
            /// The names of [`ALL`](Self::ALL), in the same order.
            pub const NAMES: &'static [&'static str] = &[$($name),+];

            /// The name (on the command line, in Python and in reports).
            pub fn name(self) -> &'static str {
                match self {
                    $($ty::$variant => $name),+
                }
            }
        }

        impl std::fmt::Display for $ty {
            fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
                f.write_str(self.name())
            }
        }

        impl std::str::FromStr for $ty {
            type Err = $crate::names::UnknownName;
            fn from_str(s: &str) -> Result<Self, Self::Err> {
                Self::ALL
                    .iter()
                    .copied()
                    .find(|v| v.name() == s)
                    .ok_or_else(|| $crate::names::UnknownName {
                        what: $what,
                        name: s.to_string(),
                        expected: Self::NAMES,
                    })
            }
        }

        #[cfg(feature = "cli")]
        impl clap::ValueEnum for $ty {
            fn value_variants<'a>() -> &'a [Self] {
                Self::ALL
            }
            fn to_possible_value(&self) -> Option<clap::builder::PossibleValue> {
                Some(clap::builder::PossibleValue::new(self.name()))
            }
        }
    };
}
pub(crate) use name_table;

#[cfg(test)]
mod tests {
    use super::or_list;

    #[test]
    fn lists() {
        assert_eq!(or_list(&["a"]), "a");
        assert_eq!(or_list(&["a", "b"]), "a or b");
        assert_eq!(or_list(&["a", "b", "c"]), "a, b or c");
    }
}
