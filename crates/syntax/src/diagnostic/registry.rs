//! Every diagnostic code, declared once with its severity and what it means: `swarf explain`
//! and docs/interpreter.md read this table, and the diagnostics' constructors are checked by it.

use super::Severity;

/// One diagnostic code: its severity and a one-line explanation.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct DiagnosticDef {
    /// The stable code, such as `E-ARC-RADIUS`.
    pub code: &'static str,
    /// The severity every diagnostic with this code has.
    pub severity: Severity,
    /// What the code means, in one sentence.
    pub summary: &'static str,
}

/// Builds [`DIAGNOSTICS`] from rows of `code severity "explanation"`.
macro_rules! registry {
    ($($code:literal $severity:ident $summary:literal)*) => {
        /// Every diagnostic code, sorted by code.
        pub const DIAGNOSTICS: &[DiagnosticDef] = &[$(DiagnosticDef {
            code: $code,
            severity: Severity::$severity,
            summary: $summary,
        }),*];
    };
}

registry! {
    "E-ARC-CENTER" Error "An arc has no usable centre: neither I/J/K nor R, an R arc that ends where it starts, a centre at the start point, or a centre word missing under G90.1."
    "E-ARC-NO-END" Error "An arc with R has no end point (a full circle needs I/J/K)."
    "E-ARC-R-AND-IJK" Error "An arc gives both R and I/J/K, which this control refuses."
    "E-ARC-RADIUS" Error "An arc's R is smaller than half the distance from its start to its end point."
    "E-ARC-WORD" Error "A centre word that does not belong to the arc's plane: LinuxCNC refuses the block."
    "E-CODE-DIALECT" Error "The code belongs to another supported control, not to the selected dialect."
    "E-CODE-NUMBER" Error "A G or M word whose number is not a valid code number."
    "E-COMMA-WORD" Error "A comma not followed by `C` (chamfer), `R` (corner rounding) or `A` (angle)."
    "E-COMMENT-UNCLOSED" Error "A comment `(` is not closed with `)` on its line."
    "E-COMP-ARC" Error "G40, G41 or G42 in a block that moves in G02/G03: the control alarms and stops."
    "E-COMP-CANCEL" Error "The move that ends cutter compensation (the first after G40) is an arc: the control alarms."
    "E-COMP-GOUGE" Error "The compensated path would cut into the part, and this control (LinuxCNC, or the setup's `overcut_alarm`) alarms."
    "E-COMP-ON" Error "G41/G42 while cutter compensation is already on (LinuxCNC)."
    "E-COMP-ORIENTATION" Error "A lathe tool orientation outside 0 to 9."
    "E-COMP-PLANE" Error "Cutter compensation in a plane the control does not compensate in."
    "E-COMP-START" Error "The move that starts cutter compensation (the first after G41/G42) is an arc: the control alarms."
    "E-COORDINATE-RANGE" Error "A move, arc centre or hole beyond ±1e9 mm, a feed too low to finish or a dwell beyond 1e9 s (only a variable gone astray gives one): the run stops at the block."
    "E-CORNER-NEXT" Error "A `,C`/`,R` corner without a cutting move in the next block: the corner is drawn sharp."
    "E-CYCLE-LEVELS" Error "A canned cycle's levels are in the wrong order (G87 needs Z above R)."
    "E-CYCLE-PECK" Error "A peck depth Q too small to go deeper: the rest of the hole is cut in one feed."
    "E-ENCODING" Error "Bytes that are not valid in the file's encoding: replaced with U+FFFD."
    "E-EXPR" Error "An expression that cannot be read: a missing value, an unknown function, a number with an exponent."
    "E-EXPR-BRACKET" Error "A `[` is not closed with `]`."
    "E-EXPR-DEPTH" Error "Brackets nested deeper than the control (or the parser's bound) allows."
    "E-G53-INCREMENTAL" Error "G53 under G91: the control refuses the block, which is not run."
    "E-LINE-LENGTH" Error "A line too long to read in full: only its first bytes are read."
    "E-LOOP-NUMBER" Error "`DO` or `END` with a loop number other than 1 to 3."
    "E-MACRO-ALARM" Error "The program raised a macro alarm (`#3000`) and stops there."
    "E-MACRO-DIVIDE" Error "A division (or `MOD`) by zero."
    "E-MACRO-DOMAIN" Error "A function argument outside its domain (`SQRT[-1]`, `ASIN[2]`, `LN[0]`)."
    "E-MACRO-GOTO" Error "A `GOTO` to a sequence number that is not in the program."
    "E-MACRO-LOOP" Error "A `DOm` without its `ENDm`, or an `ENDm` without its `WHILE … DOm`."
    "E-MACRO-SYNTAX" Error "A macro statement that is not well formed (`IF`, `THEN`, `WHILE`, a `<name>`)."
    "E-MACRO-VALUE" Error "A value the control rejects: an overflow, `BIN` of a value that is not BCD."
    "E-MACRO-VARIABLE" Error "A variable that does not exist, is read-only or is badly numbered."
    "E-MEASUREMENT" Error "LNC G168 asks for a measured angle the setup does not give (`[machine] measured_angles`)."
    "E-MODAL-CONFLICT" Error "Two codes of one modal group in one block, which this control refuses."
    "E-MOTION-LIMIT" Error "The run stopped at `[machine] max_motions` moves: the toolpath would not fit in memory."
    "E-NESTING" Error "Calls nested more than 16 deep (a subprogram that calls itself?)."
    "E-NO-FEED" Error "A cutting move without the feed it needs: an F in G93, a spindle speed in G95 or G33."
    "E-NO-MOTION-MODE" Error "Axis words with no motion mode active (after G80): add G00 or G01."
    "E-NUMBER-RANGE" Error "A word's number is out of the range its address or code takes."
    "E-OFFSET-REGISTER" Error "G45–G48 needs a D register the setup does not have: the move is not offset."
    "E-OVERTRAVEL" Error "A move leaves the machine's travel (the setup's `travel_mm`): an overtravel alarm."
    "E-OWORD" Error "A LinuxCNC O-word that is not well formed or has no matching keyword."
    "E-PATTERN-NO-CYCLE" Error "A hole pattern without a stored canned cycle to run at its holes."
    "E-PATTERN-SIZE" Error "A hole pattern with too many holes to draw."
    "E-POSITION-OFFSET" Error "G45–G48 under G41/G42 (COR-082): the move is not offset."
    "E-PROGRAM-NUMBER" Error "A program number `O` without its digits (up to 8)."
    "E-PROGRAM-SIZE" Error "A program too large to hold whole: it is read up to the 256 MiB its lines, blocks, expressions and diagnostics may take, and the rest is not read."
    "E-PROGRAM-TWICE" Error "One program number or subroutine defined twice: a call runs the first."
    "E-RUNAWAY" Error "The run stopped at `[machine] max_blocks` blocks or `max_work` steps of work in them (an endless loop?)."
    "E-SAME-BLOCK" Error "Two codes the control's manual forbids in one block."
    "E-SEQUENCE-NUMBER" Error "A sequence number `N` that is not first in its block."
    "E-SHIFT-DIRECTION" Error "The setup's G76/G87 `shift_direction` lies along the drilling axis: no shift is made."
    "E-SLANT-ANGLE" Error "A GSK slanted cycle drills along another axis than its slant angle E was given for."
    "E-STROKE-LIMIT" Error "A move leaves the G22 stroke limits or enters the protected zone: an overtravel alarm."
    "E-SUBPROGRAM" Error "A called program or label that is neither in the program nor in a file beside it."
    "E-SYNTAX-CHAR" Error "Characters that are not part of any word the dialect reads."
    "E-TOO-LARGE" Error "The program holds more expressions than the parser can index."
    "E-TOOL-UNKNOWN" Error "A tool that is not in the setup's tool table: LinuxCNC stops."
    "E-UNKNOWN-CODE" Error "A G code no supported control has, or a code from a variable that the dialect does not have."
    "E-WORD-INDEXED" Error "Syntec's indexed words (`F2=`, `S1=`) in a dialect that does not read them."
    "E-WORD-MISSING" Error "A code without a word it needs (G04 without P or X, G65 without P)."
    "E-WORD-TWICE" Error "One address given twice in a block."
    "E-WORD-UNUSED" Error "A word no code of the block uses, which LinuxCNC refuses."
    "E-WORD-VALUE" Error "An address without a number after it."
    "N-AFTER-TAPE-END" Note "Text after the closing `%`, which the control does not read."
    "N-C-AXIS" Note "A hole's C-axis angle is not drawn: the backplot shows X, Y and Z only."
    "N-CSS-DIAMETER" Note "G96 with no known tool diameter: the spindle speed is not known."
    "N-DIAGNOSTICS-LEFT-OUT" Note "A run with more diagnostics than it keeps: the ones after the first thousand different ones are counted, not listed."
    "N-F2-IGNORED" Note "Syntec's `F2=` retract feed does nothing in normal drilling: the tool retracts at rapid."
    "N-LEAST-INCREMENT" Note "A word without a decimal point, read in least input increments (`1000` is 1 mm)."
    "N-M99-MAIN-REPEATS" Note "M99 in the main program: the control runs it again endlessly; one pass is run and drawn."
    "N-OFFSET-UNSET" Note "An offset register the setup does not give: its value is taken as 0."
    "N-PROBE" Note "A skip or measuring move is drawn as its full programmed move."
    "N-PROGRAM-END" Note "The main program ends where the next `O` program starts."
    "N-STOCK-ASSUMED" Note "The setup has no `[stock]`: the stock cut is a box around the feed moves, below the highest feed's start."
    "N-TOOL-ASSUMED" Note "A tool with no `[tools.N]` in the setup: the stock is cut with a flat end mill twice its register's radius across, or 10 mm."
    "W-ARC-AS-LINE" Warning "Syntec: an arc with neither R nor I/J/K moves in a straight line (G01)."
    "W-ARC-R-AND-IJK" Warning "An arc gives both R and I/J/K: R is used and I/J/K are ignored."
    "W-ARC-SPIRAL" Warning "LNC: an arc's end point is off its circle, so the radius changes along it (a spiral)."
    "W-COMP-GOUGE" Warning "The compensated path would cut into the part (the control does not alarm)."
    "W-COMP-LOOKAHEAD" Warning "Too many blocks without motion in the plane under cutter compensation: an overcut or undercut is possible."
    "W-CORNER-SKIPPED" Warning "A `,C`/`,R` corner between moves not both in the selected plane: drawn sharp."
    "W-FILE-CHANGED" Warning "The file changed while it was read (its length or time of change differs after the reading): what was read may be part old, part new."
    "W-G53-INCREMENTAL" Warning "G53 under G91, which this control ignores: the block is an incremental move."
    "W-LINUXCNC-G84-PLANE" Warning "LinuxCNC runs G84 outside the XY plane with its feed moves' axes rotated: drawn where the machine goes."
    "W-MODAL-LAST" Warning "Two codes of one modal group in one block: the last one is used."
    "W-NOT-DOCUMENTED" Warning "A code the manual only lists, with no format or motion: the block is not run."
    "W-NOT-INTERPRETED" Warning "A code or word the interpreter does not run yet: it is skipped, and this says so."
    "W-OFFSET-UNSET" Warning "An offset register not among the setup's registers: its value is taken as 0."
    "W-PROGRAM-NUMBER" Warning "A file found by its name for a call opens with another program number: it runs as the program called."
    "W-RAPID-INTO-STOCK" Warning "A rapid move meets the stock (the setup's `[stock]`, or the one assumed): the tool would crash into material."
    "W-SHANK-CUT" Warning "A cutting move leaves material standing higher above the tool's tip than its flutes reach (`[tools.N] flute_length`): the shank rubs."
    "W-SPINDLE-STOPPED" Warning "A tapping or boring cycle with the spindle stopped: the control alarms."
    "W-STRAY-COLON" Warning "A `:` at the end of a block, read as the end of the block (`;`)."
    "W-UNKNOWN-M" Warning "An M code not in the dialect's list: a machine-specific code, not drawn."
    "W-WORD-IGNORED" Warning "A word the block's code does not use here (an arc word outside G02/G03): ignored."
    "W-WORD-MISSING" Warning "A code without a word it usually takes, run with a default (G68 without R rotates by 0°)."
    "W-WORD-UNUSED" Warning "A word no code of the block uses: the control ignores it."
}

impl DiagnosticDef {
    /// The registered entry of `code`, if it is one.
    pub fn lookup(code: &str) -> Option<&'static DiagnosticDef> {
        let i = DIAGNOSTICS.binary_search_by(|d| d.code.cmp(code)).ok()?;
        DIAGNOSTICS.get(i)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_registry_is_sorted_unique_and_prefixed_by_severity() {
        for pair in DIAGNOSTICS.windows(2) {
            assert!(
                pair[0].code < pair[1].code,
                "{} / {}",
                pair[0].code,
                pair[1].code
            );
        }
        for d in DIAGNOSTICS {
            let prefix = match d.severity {
                Severity::Error => "E-",
                Severity::Warning => "W-",
                Severity::Note => "N-",
            };
            assert!(d.code.starts_with(prefix), "{} is a {}", d.code, d.severity);
            assert!(
                !d.summary.is_empty() && !d.summary.contains('\n'),
                "{}",
                d.code
            );
            assert_eq!(DiagnosticDef::lookup(d.code), Some(d));
        }
        assert_eq!(DiagnosticDef::lookup("E-NO-SUCH-CODE"), None);
    }
}
