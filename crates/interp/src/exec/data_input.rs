//! G10 data input: work offsets (L2, L20) and offset registers (L1, L10–L13).

use swarf_syntax::{Dialect, Word};

use super::tools::known_register;
use super::{axis_words, given};
use crate::machine::find;
use crate::state::State;

/// G10 L2/L20 (work offsets) and L10–L13 / LinuxCNC L1, L10, L11 (offset registers). Returns
/// `false` when the run stops (LinuxCNC: a tool its table does not hold).
pub(super) fn data_input(st: &mut State, w: &Word, words: &[Word]) -> bool {
    let l = find(words, b'L').map(|l| l.value.round() as i64);
    let p = find(words, b'P').map_or(0, |p| p.value.round() as i64);
    let absolute = st.absolute;
    let linuxcnc = st.dialect == Dialect::LinuxCnc;
    match l {
        Some(2 | 20) => {
            let name = match (st.dialect, p) {
                _ if l == Some(20) && !linuxcnc => format!("G54.1P{p}"),
                (_, 0) => st.wcs.clone(),
                (Dialect::LinuxCnc, 7..=9) => format!("G59.{}", p - 6),
                (_, 1..=6) => format!("G{}", 53 + p),
                _ => {
                    let message = format!("G10 L2 P{p} is not a work coordinate system");
                    st.error(w.span, "E-NUMBER-RANGE", message);
                    return true;
                }
            };
            let mut offset = st.setup.work_offset(&name);
            let mut rotation = st.wcs_rotations.get(&name).copied().unwrap_or(0.0);
            if linuxcnc && let Some(r) = find(words, b'R') {
                rotation = r.value;
            }
            if linuxcnc && l == Some(20) {
                // LinuxCNC L20: the offset that makes the current position read as given.
                let axes = axis_words(words, b'X');
                let wanted = given(st, &axes, st.program_pos);
                let full =
                    st.position - crate::state::rotate_xy(wanted + st.local + st.shift, rotation);
                // Under rotation X and Y are coupled: both are set when either is given.
                let xy = axes[0].is_some() || axes[1].is_some();
                for (i, w) in axes.iter().enumerate() {
                    if w.is_some() || (i < 2 && xy && rotation != 0.0) {
                        offset[i] = full[i];
                    }
                }
            } else {
                let set = absolute || linuxcnc;
                for (i, w) in axis_words(words, b'X').iter().enumerate() {
                    if let Some(w) = w {
                        let v = st.length(w);
                        offset[i] = if set { v } else { offset[i] + v };
                    }
                }
            }
            st.setup.work_offsets.insert(name.clone(), offset);
            st.wcs_rotations.insert(name.clone(), rotation);
            if name == st.wcs {
                st.wcs_offset = offset;
                st.wcs_rotation = rotation;
                st.resync();
            }
        }
        Some(1 | 10 | 11 | 12 | 13) => {
            let n = p.max(0) as u32;
            if linuxcnc
                && !known_register(st, n, find(words, b'P').map_or(w.span, |p| p.span), "tool")
            {
                return false;
            }
            let r = find(words, b'R').map(|r| st.mm(r.value));
            let z = find(words, b'Z').map(|z| st.mm(z.value));
            // LinuxCNC L10/L11: the length that makes the current position read Z with this tool,
            // in the current system (L10) or the tool setter's G59.3 without G52/G92 (L11).
            let gauge = st.length_comp.map_or(0.0, |(_, o)| o);
            let length_for = |z: f64| match l {
                Some(10) => st.program_pos.z + gauge - z,
                Some(11) => st.position.z + gauge - st.setup.work_offset("G59.3").z - z,
                _ => z,
            };
            let z = z.map(length_for);
            let reg = st.setup.registers.entry(n).or_default();
            let slot = match (linuxcnc, l) {
                (true, _) => {
                    (reg.length, reg.radius) = (z.unwrap_or(reg.length), r.unwrap_or(reg.radius));
                    return true;
                }
                (_, Some(10)) => &mut reg.length,
                (_, Some(11)) => &mut reg.length_wear,
                (_, Some(12)) => &mut reg.radius,
                _ => &mut reg.radius_wear,
            };
            if let Some(r) = r {
                *slot = if absolute { r } else { *slot + r };
            }
        }
        _ => {
            let message = "this G10 data type is not interpreted yet and is ignored";
            st.warning(w.span, "W-NOT-INTERPRETED", message);
        }
    }
    true
}
