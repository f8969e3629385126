//! The controllers Swarf can read programs for.

use std::fmt;
use std::str::FromStr;

/// A controller family whose reading of G-code Swarf reproduces.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum Dialect {
    /// Generic Fanuc 0i-M style milling control.
    #[default]
    Fanuc,
    /// Syntec 900M.
    Syntec,
    /// LNC / Baoyuan.
    Lnc,
    /// KT.
    Kt,
    /// GSK 988TD (slanted-hole cycles).
    Gsk,
    /// LinuxCNC rs274ngc.
    LinuxCnc,
}

impl Dialect {
    /// Every dialect, in menu order.
    pub const ALL: [Dialect; 6] = [
        Dialect::Fanuc,
        Dialect::Syntec,
        Dialect::Lnc,
        Dialect::Kt,
        Dialect::Gsk,
        Dialect::LinuxCnc,
    ];

    /// The name used on the command line and in settings files.
    pub fn name(self) -> &'static str {
        match self {
            Dialect::Fanuc => "fanuc",
            Dialect::Syntec => "syntec",
            Dialect::Lnc => "lnc",
            Dialect::Kt => "kt",
            Dialect::Gsk => "gsk",
            Dialect::LinuxCnc => "linuxcnc",
        }
    }

    /// A human-readable label for menus.
    pub fn label(self) -> &'static str {
        match self {
            Dialect::Fanuc => "Fanuc 0i-M",
            Dialect::Syntec => "Syntec 900M",
            Dialect::Lnc => "LNC / Baoyuan",
            Dialect::Kt => "KT",
            Dialect::Gsk => "GSK 988TD",
            Dialect::LinuxCnc => "LinuxCNC",
        }
    }

    /// Whether `;` starts a comment (LinuxCNC) rather than ending the block (Fanuc family).
    pub fn semicolon_is_comment(self) -> bool {
        self == Dialect::LinuxCnc
    }
}

impl fmt::Display for Dialect {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// The error for a dialect name Swarf does not know.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct UnknownDialect(pub String);

impl fmt::Display for UnknownDialect {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let names: Vec<&str> = Dialect::ALL.iter().map(|d| d.name()).collect();
        write!(
            f,
            "unknown dialect `{}` (expected one of: {})",
            self.0,
            names.join(", ")
        )
    }
}

impl std::error::Error for UnknownDialect {}

impl FromStr for Dialect {
    type Err = UnknownDialect;

    fn from_str(s: &str) -> Result<Self, Self::Err> {
        let lower = s.trim().to_ascii_lowercase();
        Dialect::ALL
            .into_iter()
            .find(|d| d.name() == lower)
            .ok_or_else(|| UnknownDialect(s.to_string()))
    }
}
