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

/// Every example, in menu order.
pub const EXAMPLES: &[Example] = &[
    Example {
        name: "pocket.nc",
        dialect: Dialect::Fanuc,
        text: include_str!("../../../assets/examples/pocket.nc"),
    },
    Example {
        name: "fanuc-drill-plate.nc",
        dialect: Dialect::Fanuc,
        text: include_str!("../../../assets/examples/fanuc-drill-plate.nc"),
    },
    Example {
        name: "syntec-bolt-circle.nc",
        dialect: Dialect::Syntec,
        text: include_str!("../../../assets/examples/syntec-bolt-circle.nc"),
    },
    Example {
        name: "lnc-chamfered-pocket.nc",
        dialect: Dialect::Lnc,
        text: include_str!("../../../assets/examples/lnc-chamfered-pocket.nc"),
    },
    Example {
        name: "kt-tapping.nc",
        dialect: Dialect::Kt,
        text: include_str!("../../../assets/examples/kt-tapping.nc"),
    },
    Example {
        name: "gsk-facing.nc",
        dialect: Dialect::Gsk,
        text: include_str!("../../../assets/examples/gsk-facing.nc"),
    },
    Example {
        name: "linuxcnc-engrave-sub.ngc",
        dialect: Dialect::LinuxCnc,
        text: include_str!("../../../assets/examples/linuxcnc-engrave-sub.ngc"),
    },
];
