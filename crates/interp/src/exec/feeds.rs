//! F and S words: the feed of each move and the spindle speed.

use swarf_syntax::{Block, Diagnostic, Dialect, Word};

use crate::state::{FeedMode, State};

/// The block's F word (the first one), read in the feed mode.
pub(super) fn feed_word(st: &mut State, f: Option<&Word>) {
    st.block_has_feed = f.is_some();
    if let Some(f) = f {
        st.feed_word = f.value;
        st.feed_mm_per_min = match st.feed_mode {
            FeedMode::PerMinute => st.mm(f.value),
            // Per revolution and inverse time are kept as given; each move's feed in mm/min
            // comes from them (`move_feed`).
            FeedMode::PerRevolution | FeedMode::InverseTime => f.value,
        };
    }
}

/// The S word: the spindle speed (rpm under G97, surface speed under G96), or with G92 the
/// most rpm G96 may reach (the Fanuc family's `G92 S`).
pub(super) fn spindle_speed(st: &mut State, s: Option<&Word>, g92: bool) {
    let s = s.filter(|s| s.value >= 0.0);
    if let Some(s) = s {
        if g92 && st.dialect != Dialect::LinuxCnc {
            st.spindle_clamp = Some(s.value);
            return;
        }
        if st.css {
            st.surface_speed = s.value;
        } else {
            st.spindle_rpm = s.value;
            return;
        }
    } else if !st.css {
        // G97 without S keeps the last speed (the one G96 reached).
        return;
    }
    if st.dialect == Dialect::LinuxCnc {
        // LinuxCNC's G96 follows the X position of a lathe; the speed is read as written.
        st.spindle_rpm = st.surface_speed;
        return;
    }
    // A milling cutter cuts at its diameter: the radius in the D register (or the tool's own
    // register when no D has been given).
    let register = if st.d_word > 0 { st.d_word } else { st.tool };
    let radius = st
        .setup
        .registers
        .get(&register)
        .map_or(0.0, |r| r.radius + r.radius_wear);
    if radius <= 0.0 {
        if let Some(s) = s {
            st.diagnostics.push(Diagnostic::note(
                s.span,
                "N-CSS-DIAMETER",
                format!(
                    "G96: the tool's diameter is not known (no radius in offset register {register}), so the spindle speed for S{} is not known",
                    s.value
                ),
            ));
        }
        st.spindle_rpm = st.spindle_clamp.unwrap_or(0.0);
        return;
    }
    let diameter = 2.0 * radius;
    // V = pi D N / 1000 (m/min, mm) or pi D N / 12 (ft/min, inch).
    let rpm = if st.metric {
        1000.0 * st.surface_speed / (std::f64::consts::PI * diameter)
    } else {
        12.0 * st.surface_speed / (std::f64::consts::PI * diameter / 25.4)
    };
    st.spindle_rpm = st.spindle_clamp.map_or(rpm, |c| rpm.min(c));
}

/// The feed of one cutting move in mm/min, from the feed mode: F per minute as programmed; F
/// per revolution times the spindle speed; under G93 F times the move's length (LinuxCNC and
/// Fanuc: the move takes 1/F minutes), or as Syntec's manual defines it, F times the length of
/// a line and F times the radius of an arc (`radius`). Reports a move that cannot feed.
pub(super) fn move_feed(st: &mut State, block: &Block, length: f64, radius: Option<f64>) -> f64 {
    let (feed, problem) = match st.feed_mode {
        FeedMode::PerMinute => (
            st.feed_mm_per_min,
            "a cutting move needs a feed rate: program F before or in this block",
        ),
        FeedMode::PerRevolution => {
            let per_rev = st.mm(st.feed_mm_per_min);
            if per_rev > 0.0 && st.spindle_rpm <= 0.0 {
                st.diagnostics.push(Diagnostic::error(
                    block.span,
                    "E-NO-FEED",
                    "a feed per revolution (G95) needs a spindle speed: program S before or in this block",
                ));
                return 0.0;
            }
            (
                per_rev * st.spindle_rpm,
                "a cutting move needs a feed per revolution: program F before or in this block",
            )
        }
        FeedMode::InverseTime => {
            if !st.block_has_feed {
                let alarm = if st.dialect == Dialect::Syntec {
                    " (alarm Cor85)"
                } else {
                    ""
                };
                st.diagnostics.push(Diagnostic::error(
                    block.span,
                    "E-NO-FEED",
                    format!(
                        "in inverse-time mode (G93) every cutting block needs its own F{alarm}"
                    ),
                ));
                return 0.0;
            }
            let f = st.feed_mm_per_min;
            let feed = match radius {
                Some(r) if st.dialect == Dialect::Syntec => f * r,
                _ => f * length,
            };
            (feed, "F must be positive in inverse-time mode (G93)")
        }
    };
    // A move of no length under G93 takes no time whatever its F.
    let inverse_nothing = st.feed_mode == FeedMode::InverseTime && st.feed_mm_per_min > 0.0;
    if feed <= 0.0 && !inverse_nothing {
        st.diagnostics
            .push(Diagnostic::error(block.span, "E-NO-FEED", problem));
        return 0.0;
    }
    feed.max(0.0)
}
