//! Arcs as chords: how finely they are drawn, and their tangents for the corners they make.

use glam::DVec3;
use swarf_interp::{Arc, PlaneArc};

/// Chord tolerance for arc tessellation, in millimetres.
pub const CHORD_TOLERANCE_MM: f64 = 0.01;

/// The unit direction of motion along `arc` at parameter `t` (`None` for a degenerate arc).
fn tangent(arc: &PlaneArc, from: DVec3, to: DVec3, t: f64) -> Option<DVec3> {
    let a = arc.start_angle() + arc.sweep * t;
    let r = arc.radius + (arc.end_radius - arc.radius) * t;
    tangent_with(arc, from, to, r, a.cos(), a.sin())
}

/// [`tangent`] at the start (`end` false) or the end, for the corners at the arc's ends: the
/// angle's cosine and sine read off that end's offset from the centre rather than worked out
/// from the angle.
pub(crate) fn end_tangent(arc: &PlaneArc, from: DVec3, to: DVec3, end: bool) -> Option<DVec3> {
    let (r, (u, v)) = if end {
        (arc.end_radius, arc.end_offset)
    } else {
        (arc.radius, arc.start_offset)
    };
    if r > 0.0 {
        tangent_with(arc, from, to, r, u / r, v / r)
    } else {
        tangent(arc, from, to, f64::from(u8::from(end)))
    }
}

/// The unit direction of motion where the radius is `r` and the angle has cosine `cos` and
/// sine `sin`.
fn tangent_with(
    arc: &PlaneArc,
    from: DVec3,
    to: DVec3,
    r: f64,
    cos: f64,
    sin: f64,
) -> Option<DVec3> {
    let dr = arc.end_radius - arc.radius;
    let mut d = DVec3::ZERO;
    d[arc.iu] = dr * cos - r * sin * arc.sweep;
    d[arc.iv] = dr * sin + r * cos * arc.sweep;
    d[arc.iw] = to[arc.iw] - from[arc.iw];
    d.try_normalize()
}

/// Points along `arc` after `from`, the last exactly `arc.to`, within [`CHORD_TOLERANCE_MM`].
pub fn tessellate_arc(from: DVec3, arc: &Arc) -> Vec<DVec3> {
    let plane = arc.plane(from);
    let n = plane.chords(CHORD_TOLERANCE_MM);
    plane.points(from, arc.to, n).collect()
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]
    use super::*;
    use crate::xorshift;
    use swarf_interp::Axis;

    #[test]
    fn arc_tangents_follow_the_direction_of_travel() {
        let from = DVec3::new(10.0, 0.0, 0.0);
        let to = DVec3::new(0.0, 10.0, 0.0);
        let ccw = PlaneArc::new(from, to, DVec3::ZERO, Axis::Z, true, 0);
        let start = tangent(&ccw, from, to, 0.0).unwrap();
        let end = tangent(&ccw, from, to, 1.0).unwrap();
        assert!(start.abs_diff_eq(DVec3::Y, 1e-12), "{start}");
        assert!(end.abs_diff_eq(-DVec3::X, 1e-12), "{end}");
        let cw = PlaneArc::new(from, to, DVec3::ZERO, Axis::Z, false, 0);
        let start = tangent(&cw, from, to, 0.0).unwrap();
        assert!(start.abs_diff_eq(-DVec3::Y, 1e-12), "{start}");
    }

    #[test]
    fn sweeps_and_end_tangents_agree_with_the_angles_of_the_ends() {
        let mut seed = 0x007a_9ee7_d50f_u64;
        let mut next = move || (xorshift(&mut seed) >> 11) as f64 / (1u64 << 53) as f64 - 0.5;
        for case in 0..2000 {
            let point = |next: &mut dyn FnMut() -> f64| {
                DVec3::new(100.0 * next(), 100.0 * next(), 10.0 * next())
            };
            let (from, mut to, center) = (point(&mut next), point(&mut next), point(&mut next));
            // Some arcs end where they start, at the centre, or are helices or spirals.
            match case % 5 {
                0 => to = from,
                1 => to = center,
                _ => {}
            }
            let axis = [Axis::X, Axis::Y, Axis::Z][case % 3];
            let (ccw, turns) = (next() < 0.0, u32::from(case % 7 == 0));
            let arc = PlaneArc::new(from, to, center, axis, ccw, turns);
            // The sweep is the end's angle less the start's, brought round to the direction
            // (a full turn where the end is the start, and one more for each extra turn).
            let (iu, iv) = (arc.iu, arc.iv);
            let angle = |p: DVec3| (p[iv] - center[iv]).atan2(p[iu] - center[iu]);
            let tau = std::f64::consts::TAU;
            let raw = angle(to) - angle(from);
            let turn = (arc.sweep - raw) / tau;
            let most = tau * f64::from(turns + 1);
            assert!(
                (turn - turn.round()).abs() < 1e-9
                    && (arc.sweep > 0.0) == ccw
                    && arc.sweep.abs() <= most + 1e-9
                    && arc.sweep.abs() > most - tau,
                "case {case}: sweep {} against {raw}",
                arc.sweep
            );
            for (end, t) in [(false, 0.0), (true, 1.0)] {
                let (quick, plain) = (end_tangent(&arc, from, to, end), tangent(&arc, from, to, t));
                match (quick, plain) {
                    (Some(q), Some(p)) => assert!(q.abs_diff_eq(p, 1e-9), "case {case}: {q} {p}"),
                    _ => assert_eq!(quick, plain, "case {case}"),
                }
            }
        }
    }
}
