//! Reference geometry: a floor grid on the XY plane and the XYZ axis triad at the origin.

use glam::{Vec2, Vec3};

use crate::path::{Kind, PathPoint};

/// At most this many grid cells per side, whatever the bounds.
const MAX_CELLS: f32 = 200.0;

/// The X, Y and Z axes with the kind each is drawn as.
pub(crate) const AXES: [(Vec3, Kind); 3] = [
    (Vec3::X, Kind::AxisX),
    (Vec3::Y, Kind::AxisY),
    (Vec3::Z, Kind::AxisZ),
];

/// Smallest "nice" step (1, 2 or 5 × 10ⁿ) that is at least `raw`.
#[must_use]
pub fn nice_step(raw: f32) -> f32 {
    if !raw.is_finite() || raw <= 0.0 {
        return 1.0;
    }
    let raw = raw.clamp(1.0e-6, 1.0e30);
    let magnitude = 10f32.powf(raw.log10().floor());
    let steps = [1.0, 2.0, 5.0, 10.0].map(|mantissa| mantissa * magnitude);
    // Tolerate rounding in powf/log10 (e.g. raw = 1000 giving 999.99994).
    let step = steps.into_iter().find(|&step| step >= raw * (1.0 - 1.0e-5));
    step.unwrap_or(10.0 * magnitude)
}

/// Polylines for a grid at z = 0 over `min..max` and the origin (1/2/5×10ⁿ step, about ten cells),
/// then the axes ([`Kind::AxisX`], …); invalid or empty bounds give a 100-unit grid.
#[must_use]
pub fn grid_points(min: Vec3, max: Vec3) -> Vec<PathPoint> {
    let (lo, hi) = if min.is_finite() && max.is_finite() && min.cmple(max).all() {
        (
            min.truncate().min(Vec2::ZERO),
            max.truncate().max(Vec2::ZERO),
        )
    } else {
        (Vec2::splat(-50.0), Vec2::splat(50.0))
    };
    let size = (hi - lo).max_element();
    let size = if size > 1.0e-6 { size } else { 10.0 };
    let mut step = nice_step(size / 10.0);
    // One cell of margin all round, snapped to the step.
    let mut start = (lo / step).floor() - Vec2::ONE;
    let mut end = (hi / step).ceil() + Vec2::ONE;
    // Bounded: a step that no longer grows (at the clamp of `nice_step`) ends the search too.
    for _ in 0..128 {
        if (end - start).max_element() <= MAX_CELLS {
            break;
        }
        step = nice_step(step * 1.5);
        start = (lo / step).floor() - Vec2::ONE;
        end = (hi / step).ceil() + Vec2::ONE;
    }

    let mut out = Vec::new();
    let (x0, x1) = (start.x * step, end.x * step);
    let (y0, y1) = (start.y * step, end.y * step);
    // Lines are integer multiples of the step (so major lines line up), counted in integers:
    // far from the origin `i + 1.0` can equal `i` in f32, and a float loop would never end.
    let lines = |from: f32, to: f32| {
        let count = ((to - from).max(0.0) as u32).min(MAX_CELLS as u32 + 2);
        (0..=count).map(move |k| from + k as f32)
    };
    for i in lines(start.x, end.x) {
        out.push(PathPoint::pen_up(Vec3::new(i * step, y0, 0.0)));
        out.push(PathPoint::new(Vec3::new(i * step, y1, 0.0), grid_kind(i)));
    }
    for j in lines(start.y, end.y) {
        out.push(PathPoint::pen_up(Vec3::new(x0, j * step, 0.0)));
        out.push(PathPoint::new(Vec3::new(x1, j * step, 0.0), grid_kind(j)));
    }

    let axis = (size * 0.15).max(step * 2.0);
    for (dir, kind) in AXES {
        out.push(PathPoint::pen_up(Vec3::ZERO));
        out.push(PathPoint::new(dir * axis, kind));
    }
    out
}

/// [`grid_points`] for a scene whose machine zero lies at `zero` (scene frame): the grid
/// covers `min..max` and machine zero, and the axes start at `zero`.
#[must_use]
pub fn grid_points_at(zero: Vec3, min: Vec3, max: Vec3) -> Vec<PathPoint> {
    let mut points = grid_points(min - zero, max - zero);
    for p in &mut points {
        p.position = (p.position() + zero).to_array();
    }
    points
}

/// Every tenth grid line (counted from the origin) is a major one.
fn grid_kind(index: f32) -> Kind {
    if (index % 10.0) == 0.0 {
        Kind::GridMajor
    } else {
        Kind::Grid
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn nice_steps() {
        assert_eq!(nice_step(1.0), 1.0);
        assert_eq!(nice_step(1.2), 2.0);
        assert_eq!(nice_step(3.0), 5.0);
        assert_eq!(nice_step(7.0), 10.0);
        assert_eq!(nice_step(1000.0), 1000.0);
        assert!((nice_step(0.03) - 0.05).abs() < 1e-7);
        assert_eq!(nice_step(0.0), 1.0);
        assert_eq!(nice_step(f32::NAN), 1.0);
    }

    /// Far from the origin a float counter stops moving: the grid is still finite and small.
    #[test]
    fn a_grid_far_from_the_origin_ends() {
        for far in [1.0e12_f32, 3.0e20, -1.0e15] {
            let v = grid_points(Vec3::splat(far), Vec3::splat(far) + Vec3::ONE);
            assert!(v.len() < 2000, "{far}: {}", v.len());
        }
    }

    #[test]
    fn grid_covers_bounds_and_origin() {
        let min = Vec3::new(20.0, 30.0, -5.0);
        let max = Vec3::new(120.0, 80.0, 10.0);
        let v = grid_points(min, max);
        assert_eq!(v.len() % 2, 0);
        // Pairs: a pen-up start, then a drawn end.
        assert!(
            v.chunks_exact(2)
                .all(|p| p[0].is_pen_up() && !p[1].is_pen_up())
        );
        let grid = &v[..v.len() - 6];
        assert!(
            grid.iter()
                .skip(1)
                .step_by(2)
                .all(|p| matches!(p.kind(), Some(Kind::Grid | Kind::GridMajor)))
        );
        assert!(grid.iter().all(|v| v.position[2] == 0.0));
        let gx0 = grid.iter().map(|v| v.position[0]).fold(f32::MAX, f32::min);
        let gx1 = grid.iter().map(|v| v.position[0]).fold(f32::MIN, f32::max);
        let gy0 = grid.iter().map(|v| v.position[1]).fold(f32::MAX, f32::min);
        let gy1 = grid.iter().map(|v| v.position[1]).fold(f32::MIN, f32::max);
        assert!(gx0 <= 0.0 && gx1 >= 120.0 && gy0 <= 0.0 && gy1 >= 80.0);
        // Step 10 for a 120-unit part: 14 + 11 lines (with margins), not thousands.
        assert!(grid.len() < 2 * 60, "{} grid vertices", grid.len());
        // Axes last: red X, green Y, blue Z from the origin.
        let axes = &v[v.len() - 6..];
        assert_eq!(axes[1].kind(), Some(Kind::AxisX));
        assert_eq!(axes[3].kind(), Some(Kind::AxisY));
        assert_eq!(axes[5].kind(), Some(Kind::AxisZ));
        assert_eq!(axes[0].position, [0.0; 3]);
        assert!(axes[5].position[2] > 0.0);
    }

    #[test]
    fn grid_handles_degenerate_bounds() {
        for (min, max) in [
            (Vec3::ZERO, Vec3::ZERO),
            (Vec3::ONE, Vec3::ZERO),
            (Vec3::splat(f32::NAN), Vec3::ONE),
            (Vec3::splat(-1.0e9), Vec3::splat(1.0e9)),
            (Vec3::splat(0.001), Vec3::splat(0.002)),
        ] {
            let v = grid_points(min, max);
            assert!(!v.is_empty());
            assert!(v.len() < 2 * 2 * 210);
            assert!(v.iter().all(|v| v.position.iter().all(|c| c.is_finite())));
        }
    }
}
