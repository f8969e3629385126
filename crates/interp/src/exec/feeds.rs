//! F and S words: the feed of each move and the spindle speed.

use swarf_syntax::{Block, Dialect, Word};

use crate::state::{FeedMode, State};

/// The block's F word (the first one), read in the feed mode.
pub(super) fn feed_word(st: &mut State, f: Option<&Word>) {
    st.block_has_feed = f.is_some();
    if let Some(f) = f {
        st.feed_word = f.value;
        st.feed_mm_per_min = match st.feed_mode {
            FeedMode::PerMinute => st.mm(f.value),
            // Per revolution and inverse time are kept as given (see `move_feed`).
            FeedMode::PerRevolution | FeedMode::InverseTime => f.value,
        };
    }
}

/// The S word: rpm (G97) or surface speed (G96), or with G92 the rpm G96 may reach.
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
    // A cutter cuts at its diameter: the D register's radius (or the tool's own).
    let register = if st.d_word > 0 { st.d_word } else { st.tool };
    let radius = st.setup.offsets(register).1;
    if radius <= 0.0 {
        if let Some(s) = s {
            let message = format!(
                "G96: the tool's diameter is not known (no radius in offset register {register}), so the spindle speed for S{} is not known",
                s.value
            );
            st.note(s.span, "N-CSS-DIAMETER", message);
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

/// The feed of one cutting move in mm/min: F per minute; F per revolution times the speed; under
/// G93 F times the length (Syntec: of a line, or the arc's `radius`). Reports one that cannot feed.
pub(crate) fn move_feed(st: &mut State, block: &Block, length: f64, radius: Option<f64>) -> f64 {
    let syntec = st.dialect == Dialect::Syntec;
    let (feed, problem) = match st.feed_mode {
        FeedMode::PerMinute => (
            st.feed_mm_per_min,
            "a cutting move needs a feed rate: program F before or in this block",
        ),
        FeedMode::PerRevolution => {
            let per_rev = st.mm(st.feed_mm_per_min);
            if per_rev > 0.0 && st.spindle_rpm <= 0.0 {
                let message = "a feed per revolution (G95) needs a spindle speed: program S before or in this block";
                return st.fail(block.span, "E-NO-FEED", message);
            }
            (
                per_rev * st.spindle_rpm,
                "a cutting move needs a feed per revolution: program F before or in this block",
            )
        }
        FeedMode::InverseTime => {
            if !st.block_has_feed {
                let alarm = if syntec { " (alarm Cor85)" } else { "" };
                let message = format!(
                    "in inverse-time mode (G93) every cutting block needs its own F{alarm}"
                );
                return st.fail(block.span, "E-NO-FEED", message);
            }
            let f = st.feed_mm_per_min;
            let feed = match radius {
                Some(r) if syntec => f * r,
                _ => f * length,
            };
            (feed, "F must be positive in inverse-time mode (G93)")
        }
    };
    // A move of no length under G93 takes no time whatever its F.
    let inverse_nothing = st.feed_mode == FeedMode::InverseTime && st.feed_mm_per_min > 0.0;
    if feed <= 0.0 && !inverse_nothing {
        return st.fail(block.span, "E-NO-FEED", problem);
    }
    feed.max(0.0)
}
