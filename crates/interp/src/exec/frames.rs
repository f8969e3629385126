//! The coordinate frames: work offsets, the G52 local and G92 shifts, polar coordinates (G16),
//! rotation (G68, G168), scaling (G51) and mirror images (G51.1).

use glam::{DVec2, DVec3};
use swarf_syntax::codes::Code;
use swarf_syntax::{Dialect, Word};

use super::{Axes, axis_words, given};
use crate::machine::find;
use crate::state::{Rotation, Scaling, State, plane_axes};

/// G54–G59, G54.1 Pn, G59.n.
pub(super) fn work_offset(st: &mut State, w: &Word, words: &[Word]) {
    let name = match Code::from_value(b'G', w.value) {
        Some(c) if c.tenths == 541 => {
            let p = find(words, b'P').map_or(1.0, |p| p.value);
            format!("G54.1P{}", p.round())
        }
        Some(c) => c.to_string(),
        None => return,
    };
    st.wcs_offset = st.setup.work_offset(&name);
    st.wcs_rotation = st.wcs_rotations.get(&name).copied().unwrap_or(0.0);
    st.wcs = name;
    st.resync();
}

pub(super) fn polar(st: &mut State, on: bool) {
    if !on {
        st.polar = None;
        return;
    }
    let (u, v) = plane_axes(st.plane);
    // G90 G16: the pole is the work origin (with G52); G91 G16: the current position.
    let current = DVec2::new(st.program_pos[u], st.program_pos[v]);
    st.polar = Some(if st.absolute { DVec2::ZERO } else { current });
}

/// LNC G168 X Y Q: rotation about X Y by measured angle Q (1–4) of `measured_angles`.
pub(super) fn measured_rotation(st: &mut State, w: &Word, words: &[Word]) {
    let q = find(words, b'Q').map_or(1.0, |q| q.value.round());
    let i = (1.0..=4.0).contains(&q).then(|| q as usize - 1);
    let Some(degrees) = i.and_then(|i| st.setup.machine.measured_angles.get(i).copied()) else {
        let message = format!(
            "G168 Q{q} needs measurement result {q} in the setup (`[machine] measured_angles`)"
        );
        return st.fail(w.span, "E-MEASUREMENT", message);
    };
    rotate(st, words, degrees);
}

/// G68 X Y R (centre, or the current point; angle absolute, or under G91 added).
pub(super) fn rotation(st: &mut State, w: &Word, words: &[Word], on: bool) {
    if !on {
        st.rotation = None;
        return;
    }
    let degrees = match (find(words, b'R'), st.rotation) {
        (Some(r), Some(prev)) if !st.absolute => prev.degrees + st.angle(r),
        (Some(r), _) => st.angle(r),
        (None, _) if st.dialect == Dialect::Lnc => {
            let message = "LNC alarms on G68 without the angle R: the rotation is not turned on";
            return st.fail(w.span, "E-WORD-MISSING", message);
        }
        (None, _) => {
            let message =
                "G68 without R rotates by 0° (the angle in the control's parameter is not known)";
            st.warning(w.span, "W-WORD-MISSING", message);
            0.0
        }
    };
    // The tool stays where it is: the new frame applies to the next move's end point.
    rotate(st, words, degrees);
}

/// Turns the plane by `degrees` about the block's X Y Z (absolute in either mode) or the current
/// point.
fn rotate(st: &mut State, words: &[Word], degrees: f64) {
    let (u, v) = plane_axes(st.plane);
    let c = given(st, &axis_words(words, b'X'), st.program_pos);
    st.rotation = Some(Rotation {
        plane: st.plane,
        center: DVec2::new(c[u], c[v]),
        degrees,
    });
}

/// G51 X Y Z P (or I J K per axis) / G50.
pub(super) fn scaling(st: &mut State, w: &Word, words: &[Word], on: bool) {
    if !on {
        st.scaling = None;
        return;
    }
    let center = given(st, &axis_words(words, b'X'), st.program_pos);
    // Scale factors: P for all axes, or I/J/K per axis (read as written, e.g. P2.0 or P0.5).
    let p = find(words, b'P').map(|p| p.value);
    let ijk = [b'I', b'J', b'K'].map(|l| find(words, l).map(|f| f.value));
    let factors = DVec3::from_array(ijk.map(|f| f.or(p).unwrap_or(1.0)));
    if p.is_none() && ijk.iter().all(Option::is_none) {
        let message = "G51 without P or I/J/K scales by 1";
        st.warning(w.span, "W-WORD-MISSING", message);
    }
    st.scaling = Some(Scaling { center, factors });
}

/// G51.1 X Y Z: mirror about the given positions / G50.1 X Y Z: cancel (all axes if none).
pub(super) fn mirror(st: &mut State, words: &[Word], on: bool) {
    let axes = axis_words(words, b'X');
    let none = axes.iter().all(Option::is_none);
    for (i, w) in axes.iter().enumerate() {
        if let (true, Some(w)) = (on, w) {
            (st.mirror_center[i], st.mirror[i]) = (st.length(w), -1.0);
        } else if !on && (none || w.is_some()) {
            st.mirror[i] = 1.0;
        }
    }
}

/// G52 X Y Z: the local coordinate system (relative to the work system; `G52 X0 Y0 Z0` cancels).
pub(super) fn local(st: &mut State, axes: &Axes<'_>) {
    st.local = given(st, axes, st.local);
    st.resync();
}

/// G92 X Y Z: the current position becomes the given coordinates.
pub(super) fn set_position(st: &mut State, axes: &Axes<'_>) {
    if st.preset_rotation != 0.0 {
        // Under Syntec's G92.1 rotation the offsets are in the machine's axes.
        let wanted = st.scaled(given(st, axes, st.program_pos));
        let q = crate::state::rotate_xy(wanted, st.preset_rotation);
        st.shift = st.position - st.wcs_offset - st.local - q;
        st.resync();
        return;
    }
    for (i, w) in axes.iter().enumerate() {
        if let Some(w) = w {
            st.shift[i] += st.program_pos[i] - st.length(w);
        }
    }
    st.resync();
}

/// Syntec G92.1 X Y Z R: the program zero preset at X Y Z from the work origin (#1901…), the XY
/// plane turned by R degrees about it (#1930); K, not explained by the manual, is not used.
pub(super) fn preset_zero(st: &mut State, words: &[Word]) {
    st.shift = given(st, &axis_words(words, b'X'), st.shift);
    st.preset_rotation = find(words, b'R').map_or(st.preset_rotation, |r| st.angle(r));
    st.resync();
}
