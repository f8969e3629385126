//! The coordinate frames: work offsets, the G52 local and G92 shifts, polar coordinates (G16),
//! rotation (G68, G168), scaling (G51) and mirror images (G51.1).

use glam::{DVec2, DVec3};
use swarf_syntax::codes::Code;
use swarf_syntax::{Diagnostic, Dialect, Word};

use super::Axes;
use crate::machine::find;
use crate::state::{Polar, Rotation, Scaling, State, plane_axes};

/// G54–G59, G54.1 Pn, G59.n.
pub(super) fn work_offset(st: &mut State, w: &Word, words: &[Word]) {
    let name = match Code::from_value(b'G', w.value).map(|c| c.tenths) {
        Some(541) => {
            let p = find(words, b'P').map_or(1.0, |p| p.value);
            format!("G54.1P{}", p.round())
        }
        Some(t) if t % 10 == 0 => format!("G{}", t / 10),
        Some(t) => format!("G{}.{}", t / 10, t % 10),
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
    let pole = if st.absolute {
        DVec2::ZERO
    } else {
        DVec2::new(st.program_pos[u], st.program_pos[v])
    };
    st.polar = Some(Polar { pole });
}

/// LNC G168 X Y Q: rotation about the centre (or the current point) by measurement result Q
/// (1–4, default 1) from `[machine] measured_angles`.
pub(super) fn measured_rotation(st: &mut State, w: &Word, words: &[Word]) {
    let q = find(words, b'Q').map_or(1.0, |q| q.value.round());
    let Some(degrees) = (1.0..=4.0)
        .contains(&q)
        .then(|| {
            st.setup
                .machine
                .measured_angles
                .get(q as usize - 1)
                .copied()
        })
        .flatten()
    else {
        st.diagnostics.push(Diagnostic::error(
            w.span,
            "E-MEASUREMENT",
            format!(
                "G168 Q{q} needs measurement result {q} in the setup (`[machine] measured_angles`)"
            ),
        ));
        return;
    };
    let (u, v) = plane_axes(st.plane);
    let letters = [b'X', b'Y', b'Z'];
    let center_of = |i: usize| find(words, letters[i]).map_or(st.program_pos[i], |c| st.length(c));
    st.rotation = Some(Rotation {
        plane: st.plane,
        center: DVec2::new(center_of(u), center_of(v)),
        degrees,
    });
}

/// G68 X Y R (centre from the words, or the current position; angle absolute or, under G91,
/// added to the active rotation).
pub(super) fn rotation(st: &mut State, w: &Word, words: &[Word], on: bool) {
    if !on {
        st.rotation = None;
        return;
    }
    let (u, v) = plane_axes(st.plane);
    let letters = [b'X', b'Y', b'Z'];
    // The centre is absolute in either mode; without it, the current position.
    let center_of = |i: usize| find(words, letters[i]).map_or(st.program_pos[i], |c| st.length(c));
    let center = DVec2::new(center_of(u), center_of(v));
    let Some(r) = find(words, b'R') else {
        if st.dialect == Dialect::Lnc {
            st.diagnostics.push(Diagnostic::error(
                w.span,
                "E-WORD-MISSING",
                "LNC alarms on G68 without the angle R: the rotation is not turned on",
            ));
            return;
        }
        st.diagnostics.push(Diagnostic::warning(
            w.span,
            "W-WORD-MISSING",
            "G68 without R rotates by 0° (the angle in the control's parameter is not known)",
        ));
        st.rotation = Some(Rotation {
            plane: st.plane,
            center,
            degrees: 0.0,
        });
        return;
    };
    let angle = st.angle(r);
    let degrees = match (st.absolute, st.rotation) {
        (false, Some(prev)) => prev.degrees + angle,
        _ => angle,
    };
    // The tool stays where it is: the new frame applies to the next move's end point.
    st.rotation = Some(Rotation {
        plane: st.plane,
        center,
        degrees,
    });
}

/// G51 X Y Z P (or I J K per axis) / G50.
pub(super) fn scaling(st: &mut State, w: &Word, words: &[Word], on: bool) {
    if !on {
        st.scaling = None;
        return;
    }
    let letters = [b'X', b'Y', b'Z'];
    let mut center = st.program_pos;
    for (i, l) in letters.iter().enumerate() {
        if let Some(c) = find(words, *l) {
            center[i] = st.length(c);
        }
    }
    // Scale factors: P for all axes, or I/J/K per axis (read as written, e.g. P2.0 or P0.5).
    let p = find(words, b'P').map(|p| p.value);
    let mut factors = DVec3::splat(p.unwrap_or(1.0));
    for (i, l) in [b'I', b'J', b'K'].iter().enumerate() {
        if let Some(f) = find(words, *l) {
            factors[i] = f.value;
        }
    }
    if p.is_none() && [b'I', b'J', b'K'].iter().all(|l| find(words, *l).is_none()) {
        st.diagnostics.push(Diagnostic::warning(
            w.span,
            "W-WORD-MISSING",
            "G51 without P or I/J/K scales by 1",
        ));
    }
    st.scaling = Some(Scaling { center, factors });
}

/// G51.1 X Y Z: mirror about the given axis positions / G50.1 X Y Z: cancel (all axes when none
/// is given).
pub(super) fn mirror(st: &mut State, words: &[Word], on: bool) {
    let letters = [b'X', b'Y', b'Z'];
    let given: Vec<usize> = (0..3)
        .filter(|i| find(words, letters[*i]).is_some())
        .collect();
    for (i, letter) in letters.iter().enumerate() {
        if let Some(w) = find(words, *letter) {
            if on {
                st.mirror_center[i] = st.length(w);
                st.mirror[i] = -1.0;
            } else {
                st.mirror[i] = 1.0;
            }
        } else if !on && given.is_empty() {
            st.mirror[i] = 1.0;
        }
    }
}

/// G52 X Y Z: the local coordinate system (relative to the work system; `G52 X0 Y0 Z0` cancels).
pub(super) fn local(st: &mut State, axes: &Axes<'_>) {
    for (i, w) in axes.iter().enumerate() {
        if let Some(w) = w {
            st.local[i] = st.length(w);
        }
    }
    st.resync();
}

/// G92 X Y Z: the current position becomes the given coordinates.
pub(super) fn set_position(st: &mut State, axes: &Axes<'_>) {
    if st.preset_rotation != 0.0 {
        // Under Syntec's G92.1 rotation the offsets are in the machine's axes: the shift that
        // puts the given program point (unrotated, unscaled) at the current position.
        let mut wanted = st.program_pos;
        for (i, w) in axes.iter().enumerate() {
            if let Some(w) = w {
                wanted[i] = st.length(w);
            }
        }
        let q = crate::state::rotate_xy(st.scaled(wanted), st.preset_rotation);
        st.shift = st.position - st.wcs_offset - st.local - q;
        st.resync();
        return;
    }
    for (i, w) in axes.iter().enumerate() {
        if let Some(w) = w {
            let wanted = st.length(w);
            st.shift[i] += st.program_pos[i] - wanted;
        }
    }
    st.resync();
}

/// G92.1 X Y Z R (Syntec): the program zero is preset at X Y Z from the work origin (the G92
/// offsets #1901…) and the program XY plane turned by R degrees about it (#1930). K is not
/// explained by the manual and is not used.
pub(super) fn preset_zero(st: &mut State, words: &[Word]) {
    for (i, l) in [b'X', b'Y', b'Z'].iter().enumerate() {
        if let Some(w) = find(words, *l) {
            st.shift[i] = st.length(w);
        }
    }
    if let Some(r) = find(words, b'R') {
        st.preset_rotation = st.angle(r);
    }
    st.resync();
}
