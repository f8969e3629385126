//! Example programs, one or more per dialect, built into the app and offered in its menu.

use swarf_syntax::Dialect;

/// A built-in example program.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Example {
    /// The file name it is shown and saved as.
    pub name: &'static str,
    /// The dialect it is written for (selected when it is opened).
    pub dialect: Dialect,
    /// The program text.
    pub text: &'static str,
}

/// The example `name` in `assets/examples/`, written for `dialect`.
macro_rules! example {
    ($name:literal, $dialect:ident) => {
        Example {
            name: $name,
            dialect: Dialect::$dialect,
            text: include_str!(concat!("../../../assets/examples/", $name)),
        }
    };
}

/// Every example, in menu order.
pub const EXAMPLES: &[Example] = &[
    example!("pocket.nc", Fanuc),
    example!("fanuc-drill-plate.nc", Fanuc),
    example!("syntec-bolt-circle.nc", Syntec),
    example!("lnc-chamfered-pocket.nc", Lnc),
    example!("kt-tapping.nc", Kt),
    example!("gsk-facing.nc", Gsk),
    example!("linuxcnc-engrave-sub.ngc", LinuxCnc),
];
