//! The controllers Swarf can read programs for.

use std::fmt;
use std::str::FromStr;

use crate::Word;

crate::ast::named_enum! {
    /// A controller family whose reading of G-code Swarf reproduces, in menu order.
    #[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default, serde::Serialize, serde::Deserialize)]
    pub enum Dialect;
    /// The name used on the command line and in settings files.
    fn name;
    #[default]
    Fanuc    "fanuc"    "Generic Fanuc 0i-M style milling control.";
    Syntec   "syntec"   "Syntec 900M.";
    Lnc      "lnc"      "LNC / Baoyuan.";
    Kt       "kt"       "KT.";
    Gsk      "gsk"      "GSK 988TD (slanted-hole cycles).";
    LinuxCnc "linuxcnc" "LinuxCNC rs274ngc.";
}

impl Dialect {
    /// A human-readable label for menus.
    pub fn label(self) -> &'static str {
        [
            "Fanuc 0i-M",
            "Syntec 900M",
            "LNC / Baoyuan",
            "KT",
            "GSK 988TD",
            "LinuxCNC",
        ][self as usize]
    }

    /// Whether `;` starts a comment (LinuxCNC) rather than ending the block (Fanuc family).
    pub fn semicolon_is_comment(self) -> bool {
        self.rules().semicolon_comment
    }

    /// The dialect's lexical and numeric rules.
    pub fn rules(self) -> &'static Rules {
        static RULES: [Rules; 6] = [FANUC, SYNTEC, LNC, KT, GSK, LINUXCNC];
        &RULES[self as usize]
    }

    /// Reads a literal word as the control does, given its `quantity`, the `calculator` setting
    /// ([`Rules::calculator_input`]) and `inch`; in ordinary units, [`Quantity::Raw`] unchanged.
    pub fn read(self, word: &Word, quantity: Quantity, calculator: bool, inch: bool) -> f64 {
        let rules = self.rules();
        let v = word.value;
        if word.expr.is_some() {
            // Macro values are always in ordinary units.
            return v;
        }
        let least_length = if inch { 0.0001 } else { 0.001 };
        // Seconds, or `ms` milliseconds by the rule.
        let seconds = |rule: TimeRule, ms: f64| match rule {
            TimeRule::Seconds => v,
            TimeRule::PointSecondsElseMs if word.has_point => v,
            TimeRule::PointSecondsElseMs | TimeRule::Millis => ms / 1000.0,
        };
        match quantity {
            Quantity::Raw => v,
            Quantity::Length | Quantity::Angle if word.has_point || calculator => v,
            Quantity::Length | Quantity::LeastLength => v * least_length,
            Quantity::Angle => v * 0.001,
            Quantity::DwellX => seconds(rules.dwell_x, v),
            // Milliseconds, whole numbers only: the fraction is dropped (`G04 P2.5` = 2 ms).
            Quantity::DwellP => seconds(rules.dwell_p, v.trunc()),
            Quantity::CycleDwellP => seconds(rules.cycle_dwell_p, v.trunc()),
        }
    }
}

/// What a word's number means in its block, which decides how the control reads it.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Quantity {
    /// Read as written (feeds, speeds, code numbers, counts, register numbers).
    Raw,
    /// A coordinate or distance: without a decimal point it is in least input increments
    /// (0.001 mm / 0.0001 inch) unless calculator-type input is on.
    Length,
    /// A length always in least input increments (GSK's Q peck depth).
    LeastLength,
    /// An angle: without a decimal point it is in 0.001° unless calculator-type input is on.
    Angle,
    /// The X (or U) word of a G04 dwell.
    DwellX,
    /// The P word of a G04 dwell.
    DwellP,
    /// The P (bottom dwell) word of a canned cycle.
    CycleDwellP,
}

/// How a dialect reads a time word.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum TimeRule {
    /// Always seconds.
    Seconds,
    /// Always milliseconds (whole numbers).
    Millis,
    /// Seconds with a decimal point, milliseconds without (Syntec's decimal-point rule).
    PointSecondsElseMs,
}

/// A dialect's lexical and numeric rules, as data (see [`Dialect::rules`]).
#[derive(Debug, Clone, PartialEq)]
pub struct Rules {
    /// `;` starts a comment (LinuxCNC) instead of ending the block (Fanuc family).
    pub semicolon_comment: bool,
    /// `//` starts a comment to the end of the line (Syntec examples).
    pub slash_comment: bool,
    /// `:` followed by digits at the start of a block is a program number (ISO `:1234`).
    pub colon_program_number: bool,
    /// `:=` assigns a variable (Syntec macro syntax).
    pub colon_assign: bool,
    /// LinuxCNC O-word control lines (`o100 sub`, `o100 if […]`) and `#<named>` parameters.
    pub o_words: bool,
    /// Fanuc Macro B statements (`IF`, `GOTO`, `WHILE … DOm`, `ENDm`).
    pub macro_b: bool,
    /// Comma words `,C` `,R` (and `,A`).
    pub comma_words: bool,
    /// Indexed words `F2=` and `S1=`.
    pub indexed_words: bool,
    /// `AND` binds like `*` and `OR`/`XOR` like `+` (Fanuc); otherwise the logical operators bind
    /// loosest (LinuxCNC), below the comparisons.
    pub fanuc_logic_precedence: bool,
    /// Calculator-type input at power-on: a number without a decimal point is read in mm (inch,
    /// degrees) instead of least input increments. A setting; this is the manual's default.
    pub calculator_input: bool,
    /// How `G04 X` is read.
    pub dwell_x: TimeRule,
    /// How `G04 P` is read.
    pub dwell_p: TimeRule,
    /// How a canned cycle's `P` is read.
    pub cycle_dwell_p: TimeRule,
    /// The largest `N` number the control accepts.
    pub max_sequence_number: u32,
    /// The most significant digits a numeric word may have (0: no limit).
    pub max_digits: u8,
    /// The deepest bracket nesting the control accepts in an expression.
    pub max_bracket_depth: u8,
}

const FANUC: Rules = Rules {
    semicolon_comment: false,
    slash_comment: false,
    colon_program_number: true,
    colon_assign: false,
    o_words: false,
    macro_b: true,
    comma_words: true,
    indexed_words: false,
    fanuc_logic_precedence: true,
    calculator_input: false,
    dwell_x: TimeRule::PointSecondsElseMs,
    dwell_p: TimeRule::Millis,
    cycle_dwell_p: TimeRule::Millis,
    max_sequence_number: 99_999,
    max_digits: 9,
    max_bracket_depth: 5,
};

/// Syntec 900M (§2.3: decimal-point input; `G04 X2500` = 2.5 s; `P` in ms, fraction dropped;
/// cycle P seconds with a point, ms without).
const SYNTEC: Rules = Rules {
    slash_comment: true,
    colon_assign: true,
    indexed_words: true,
    cycle_dwell_p: TimeRule::PointSecondsElseMs,
    max_bracket_depth: 32,
    ..FANUC
};

/// LNC / Baoyuan (§2.3: `G04 P_`/`X_` in seconds; no decimal-point rule given, so the Fanuc
/// reading of integers is kept; comma words `,C` `,R`).
const LNC: Rules = Rules {
    dwell_x: TimeRule::Seconds,
    dwell_p: TimeRule::Seconds,
    cycle_dwell_p: TimeRule::Seconds,
    ..FANUC
};

/// KT (§2.3: dwell "the same as G04", examples `G04 P2000` = 2 s).
const KT: Rules = Rules {
    comma_words: false,
    ..FANUC
};

/// GSK 988TD (§2.3: coordinates written without a point are millimetres in the examples; `P` in
/// 1 ms; `Q` always in least units).
const GSK: Rules = Rules {
    comma_words: false,
    calculator_input: true,
    ..FANUC
};

/// LinuxCNC: every number is read as written; dwell in seconds.
const LINUXCNC: Rules = Rules {
    semicolon_comment: true,
    colon_program_number: false,
    o_words: true,
    macro_b: false,
    comma_words: false,
    fanuc_logic_precedence: false,
    calculator_input: true,
    max_digits: 0,
    max_bracket_depth: 64,
    ..LNC
};

/// The error for a dialect name Swarf does not know.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct UnknownDialect(pub String);

impl fmt::Display for UnknownDialect {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let names: Vec<&str> = Dialect::ALL.iter().map(|d| d.name()).collect();
        let (name, names) = (&self.0, names.join(", "));
        write!(f, "unknown dialect `{name}` (expected one of: {names})")
    }
}

impl std::error::Error for UnknownDialect {}

impl FromStr for Dialect {
    type Err = UnknownDialect;

    fn from_str(s: &str) -> Result<Self, Self::Err> {
        let lower = s.trim().to_ascii_lowercase();
        let found = Dialect::ALL.into_iter().find(|d| d.name() == lower);
        found.ok_or_else(|| UnknownDialect(s.to_string()))
    }
}
