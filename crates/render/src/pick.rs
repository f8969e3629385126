//! Picking on the CPU: the segment nearest to the cursor on screen, in one pass over the
//! points (or over the chords drawn, then the segments of those near the cursor), and the
//! bounds of a run of segments for "zoom to selection".

use std::ops::Range;

use glam::{Mat4, Vec2, Vec3, Vec4};

use crate::path::PathPoint;

/// The segment found by [`pick_segment`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Pick {
    /// Segment index: the segment from point `segment` to point `segment + 1`.
    pub segment: usize,
    /// Distance from the cursor to the segment on screen, in pixels.
    pub distance_px: f32,
    /// Where along the segment (0 at its start, 1 at its end, in world space) the point
    /// nearest to the cursor lies.
    pub t: f32,
    /// Normalised depth (0 near, 1 far) of that point.
    pub depth: f32,
}

impl Pick {
    /// The picked point in world space (relative to the scene origin).
    #[must_use]
    pub fn position(&self, points: &[PathPoint]) -> Option<Vec3> {
        let a = points.get(self.segment)?.position();
        let b = points.get(self.segment + 1)?.position();
        Some(a.lerp(b, self.t))
    }
}

/// Distances closer than this (pixels) count as a tie, broken by depth (the nearer wins).
const TIE_PX: f32 = 0.25;

/// The segment drawn nearest to `cursor_px` within `radius_px` (the unit of `viewport_px`, y down),
/// clipped at the near plane, `hidden_kinds` ([`crate::Kind::mask`]) skipped, ties to the nearer
/// then the later; `view_proj` is [`crate::OrbitCamera::view_proj`]'s.
#[must_use]
pub fn pick_segment(
    points: &[PathPoint],
    view_proj: Mat4,
    viewport_px: Vec2,
    cursor_px: Vec2,
    radius_px: f32,
    hidden_kinds: u32,
) -> Option<Pick> {
    let view = CursorView::new(view_proj, viewport_px, cursor_px, radius_px, hidden_kinds)?;
    let mut best = None;
    view.hits(points, 0, radius_px, |hit| keep_better(&mut best, hit));
    best
}

/// As [`pick_segment`], in time that follows what is drawn: the chords between `kept` points (see
/// [`crate::simplify`], within `slack_px`) first, then segments of those within
/// `radius_px + slack_px`.
#[must_use]
pub fn pick_kept_segment(
    points: &[PathPoint],
    kept: &[u32],
    (view_proj, viewport_px, cursor_px): (Mat4, Vec2, Vec2),
    radius_px: f32,
    hidden_kinds: u32,
    slack_px: f32,
) -> Option<Pick> {
    let view = CursorView::new(view_proj, viewport_px, cursor_px, radius_px, hidden_kinds)?;
    if !slack_px.is_finite() || slack_px < 0.0 {
        return None;
    }
    let chords: Vec<PathPoint> = kept
        .iter()
        .map_while(|&i| points.get(i as usize).copied())
        .collect();
    let mut near = Vec::new();
    view.hits(&chords, 0, radius_px + slack_px, |hit| {
        near.push(hit.segment);
    });
    let mut best = None;
    for chord in near {
        let (Some(&from), Some(&to)) = (kept.get(chord), kept.get(chord + 1)) else {
            continue;
        };
        let (from, to) = (from as usize, to as usize);
        if let Some(run) = points.get(from..=to) {
            view.hits(run, from, radius_px, |hit| keep_better(&mut best, hit));
        }
    }
    best
}

/// Makes `hit` the best unless `best` is nearer (ties within [`TIE_PX`]: the nearer to the
/// eye, then the later).
fn keep_better(best: &mut Option<Pick>, hit: Pick) {
    let better = |b: &Pick| {
        hit.distance_px < b.distance_px - TIE_PX
            || (hit.distance_px <= b.distance_px + TIE_PX && hit.depth <= b.depth)
    };
    if best.as_ref().is_none_or(better) {
        *best = Some(hit);
    }
}

/// A view and a cursor to measure segments against, in "cursor space".
struct CursorView {
    px: Vec4,
    py: Vec4,
    pz: Vec4,
    pw: Vec4,
    hidden_kinds: u32,
}

impl CursorView {
    /// `None` for a view, cursor or radius that is not finite (or an empty viewport).
    fn new(
        view_proj: Mat4,
        viewport_px: Vec2,
        cursor_px: Vec2,
        radius_px: f32,
        hidden_kinds: u32,
    ) -> Option<Self> {
        let valid = view_proj.is_finite()
            && viewport_px.is_finite()
            && viewport_px.min_element() > 0.0
            && cursor_px.is_finite()
            && radius_px.is_finite()
            && radius_px >= 0.0;
        if !valid {
            return None;
        }
        // Rows of the matrix taking a world point to (pixel offset from the cursor) × w:
        // px = (ndc.x + 1) / 2 · W − cx  and  py = (1 − ndc.y) / 2 · H − cy.
        let m = view_proj.transpose();
        let (row_x, row_y, row_z, row_w) = (m.x_axis, m.y_axis, m.z_axis, m.w_axis);
        let half = viewport_px * 0.5;
        Some(CursorView {
            px: row_x * half.x + row_w * (half.x - cursor_px.x),
            py: row_y * (-half.y) + row_w * (half.y - cursor_px.y),
            pz: row_z,
            pw: row_w,
            hidden_kinds,
        })
    }

    /// Calls `hit` with each segment of `points` drawn within `radius_px` of the cursor, in
    /// order, numbered from `first` (the index in the whole path of `points[0]`).
    fn hits(&self, points: &[PathPoint], first: usize, radius_px: f32, mut hit: impl FnMut(Pick)) {
        // A point in "cursor space": homogeneous coordinates whose `x / w`, `y / w` are pixel
        // offsets from the cursor (y down) and `z / w` the depth, and those offsets when the
        // point is in front of the near plane.
        let project = |p: &PathPoint| {
            let v = Vec4::new(p.position[0], p.position[1], p.position[2], 1.0);
            let clip = Vec4::new(
                self.px.dot(v),
                self.py.dot(v),
                self.pz.dot(v),
                self.pw.dot(v),
            );
            let in_front = clip.z >= 0.0 && clip.w > 0.0;
            (clip, in_front.then(|| Vec2::new(clip.x, clip.y) / clip.w))
        };
        let Some(start) = points.first() else {
            return;
        };
        let mut prev = project(start);
        for (i, point) in points.iter().enumerate().skip(1) {
            let cur = project(point);
            let skip = point.is_pen_up() || (self.hidden_kinds >> (point.packed & 0xff)) & 1 != 0;
            if !skip {
                let ((a, on_a), (b, on_b)) = (prev, cur);
                let found = if let (Some(on_a), Some(on_b)) = (on_a, on_b) {
                    nearest_on_screen(on_a, on_b, radius_px).map(|(t, d)| {
                        // Screen-space t to the world-space parameter (perspective divide).
                        let s = world_t(t, a.w, b.w);
                        let clip = a.lerp(b, s);
                        (s, d, clip.z / clip.w)
                    })
                } else {
                    clipped_hit(a, b, radius_px)
                };
                if let Some((t, distance_px, depth)) = found {
                    hit(Pick {
                        segment: first + i - 1,
                        distance_px,
                        t,
                        depth,
                    });
                }
            }
            prev = cur;
        }
    }
}

/// `(t, distance)` of the point of screen segment `a..b` nearest to the origin (the cursor),
/// if within `radius`.
#[inline]
fn nearest_on_screen(a: Vec2, b: Vec2, radius: f32) -> Option<(f32, f32)> {
    // Cheap rejection: the segment's box must come within `radius` of the cursor.
    if a.x.min(b.x) > radius
        || a.x.max(b.x) < -radius
        || a.y.min(b.y) > radius
        || a.y.max(b.y) < -radius
    {
        return None;
    }
    let ab = b - a;
    let len2 = ab.length_squared();
    let t = if len2 > 1.0e-12 {
        (-a.dot(ab) / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    let d = (a + ab * t).length();
    (d <= radius).then_some((t, d))
}

/// Maps parameter `t` along a projected segment to the parameter along the original one,
/// given the endpoints' clip `w`.
#[inline]
fn world_t(t: f32, wa: f32, wb: f32) -> f32 {
    let denom = t * wa + (1.0 - t) * wb;
    if denom.abs() > 1.0e-30 {
        (t * wa / denom).clamp(0.0, 1.0)
    } else {
        t
    }
}

/// A hit on a segment crossing the near plane (or entirely behind it): clip, then measure.
#[cold]
fn clipped_hit(a: Vec4, b: Vec4, radius: f32) -> Option<(f32, f32, f32)> {
    if a.z < 0.0 && b.z < 0.0 {
        return None;
    }
    let cross = a.z / (a.z - b.z);
    let s0 = if a.z < 0.0 { cross } else { 0.0 };
    let s1 = if b.z < 0.0 { cross } else { 1.0 };
    let ca = a.lerp(b, s0);
    let cb = a.lerp(b, s1);
    if ca.w <= 0.0 || cb.w <= 0.0 {
        return None;
    }
    let sa = Vec2::new(ca.x, ca.y) / ca.w;
    let sb = Vec2::new(cb.x, cb.y) / cb.w;
    let (t, d) = nearest_on_screen(sa, sb, radius)?;
    let s = world_t(t, ca.w, cb.w);
    let clip = ca.lerp(cb, s);
    Some((s0 + (s1 - s0) * s, d, clip.z / clip.w))
}

/// Bounds of the points of `segments` (segment `i` runs from point `i` to point `i + 1`),
/// e.g. to zoom to a selected block; `None` for an empty or out-of-range selection.
#[must_use]
pub fn segment_bounds(points: &[PathPoint], segments: Range<usize>) -> Option<(Vec3, Vec3)> {
    let end = segments.end.saturating_add(1).min(points.len());
    let selected = points.get(segments.start..end).filter(|s| s.len() >= 2)?;
    let (mut min, mut max) = (Vec3::INFINITY, Vec3::NEG_INFINITY);
    for p in selected {
        let v = p.position();
        min = min.min(v);
        max = max.max(v);
    }
    (min.is_finite() && max.is_finite()).then_some((min, max))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{Kind, OrbitCamera, Projection, StandardView};

    const VIEWPORT: Vec2 = Vec2::new(800.0, 600.0);

    fn top_camera(projection: Projection) -> OrbitCamera {
        let mut camera = OrbitCamera::new(StandardView::Top);
        camera.projection = projection;
        camera.fit_aspect(
            Vec3::new(-50.0, -50.0, 0.0),
            Vec3::new(50.0, 50.0, 0.0),
            VIEWPORT.x / VIEWPORT.y,
        );
        camera
    }

    /// Where `p` lands on screen (pixels from the top-left, y down).
    fn screen(camera: &OrbitCamera, p: Vec3) -> Vec2 {
        let ndc = camera.view_proj(VIEWPORT.x / VIEWPORT.y).project_point3(p);
        Vec2::new(
            (ndc.x + 1.0) * 0.5 * VIEWPORT.x,
            (1.0 - ndc.y) * 0.5 * VIEWPORT.y,
        )
    }

    fn square() -> Vec<PathPoint> {
        vec![
            PathPoint::pen_up(Vec3::new(-40.0, -40.0, 0.0)),
            PathPoint::new(Vec3::new(40.0, -40.0, 0.0), Kind::Feed),
            PathPoint::new(Vec3::new(40.0, 40.0, 0.0), Kind::Feed),
            PathPoint::new(Vec3::new(-40.0, 40.0, 0.0), Kind::Rapid),
            PathPoint::pen_up(Vec3::new(-40.0, -40.0, 0.0)),
            PathPoint::new(Vec3::new(0.0, 0.0, 0.0), Kind::Arc),
        ]
    }

    fn pick(camera: &OrbitCamera, points: &[PathPoint], cursor: Vec2) -> Option<Pick> {
        let vp = camera.view_proj(VIEWPORT.x / VIEWPORT.y);
        pick_segment(points, vp, VIEWPORT, cursor, 5.0, 0)
    }

    #[test]
    fn picks_the_segment_under_the_cursor() {
        for projection in [Projection::Orthographic, Projection::Perspective] {
            let camera = top_camera(projection);
            let points = square();
            // Middle of the right edge (segment 1, from point 1 to 2).
            let mid = screen(&camera, Vec3::new(40.0, 0.0, 0.0));
            let hit = pick(&camera, &points, mid + Vec2::new(2.0, 0.0));
            let hit = hit.unwrap_or_else(|| panic!("{projection:?}: nothing picked"));
            assert_eq!(hit.segment, 1);
            assert!((hit.distance_px - 2.0).abs() < 0.05, "{hit:?}");
            assert!((hit.t - 0.5).abs() < 1e-3, "{hit:?}");
            let at = hit.position(&points).unwrap_or(Vec3::NAN);
            assert!(at.abs_diff_eq(Vec3::new(40.0, 0.0, 0.0), 0.05), "{at}");
            // Outside the radius: nothing.
            assert!(pick(&camera, &points, mid + Vec2::new(8.0, 0.0)).is_none());
            // The pen-up gap between points 3 and 4 (left edge) is not a segment.
            let left = screen(&camera, Vec3::new(-40.0, 0.0, 0.0));
            assert!(pick(&camera, &points, left).is_none());
            // The diagonal after the pen-up is segment 4.
            let diag = screen(&camera, Vec3::new(-20.0, -20.0, 0.0));
            assert_eq!(pick(&camera, &points, diag).map(|p| p.segment), Some(4));
        }
    }

    #[test]
    fn hidden_kinds_and_bad_input_pick_nothing() {
        let camera = top_camera(Projection::Orthographic);
        let points = square();
        let vp = camera.view_proj(VIEWPORT.x / VIEWPORT.y);
        let top = screen(&camera, Vec3::new(0.0, 40.0, 0.0));
        assert_eq!(
            pick_segment(&points, vp, VIEWPORT, top, 5.0, 0).map(|p| p.segment),
            Some(2)
        );
        assert!(pick_segment(&points, vp, VIEWPORT, top, 5.0, Kind::Rapid.mask()).is_none());
        assert!(pick_segment(&points, vp, VIEWPORT, Vec2::NAN, 5.0, 0).is_none());
        assert!(pick_segment(&points, vp, Vec2::ZERO, top, 5.0, 0).is_none());
        assert!(pick_segment(&points[..1], vp, VIEWPORT, top, 5.0, 0).is_none());
        assert!(pick_segment(&[], vp, VIEWPORT, top, 5.0, 0).is_none());
    }

    #[test]
    fn ties_go_to_the_segment_nearer_the_eye() {
        // Two identical squares at z = 0 and z = -10 seen from the top: same on screen.
        let camera = top_camera(Projection::Orthographic);
        let mut points = Vec::new();
        for z in [-10.0, 0.0, -20.0] {
            points.push(PathPoint::pen_up(Vec3::new(-40.0, 0.0, z)));
            points.push(PathPoint::new(Vec3::new(40.0, 0.0, z), Kind::Feed));
        }
        let cursor = screen(&camera, Vec3::new(10.0, 0.0, 0.0));
        let hit = pick(&camera, &points, cursor).map(|p| p.segment);
        assert_eq!(hit, Some(2), "the z = 0 segment (index 2) is on top");
    }

    #[test]
    fn segments_crossing_the_near_plane_are_clipped() {
        // Perspective camera close to a long line that passes behind the eye.
        let mut camera = OrbitCamera::new(StandardView::Front);
        camera.projection = Projection::Perspective;
        camera.target = Vec3::ZERO;
        camera.distance = 10.0;
        let eye = camera.eye();
        let points = [
            PathPoint::pen_up(Vec3::new(1.0, 0.0, 0.0)),
            // Far behind the eye along the view axis.
            PathPoint::new(eye - camera.forward() * 1000.0 + Vec3::X, Kind::Feed),
        ];
        let on_screen = screen(&camera, Vec3::new(1.0, 0.0, 0.0));
        let hit = pick(&camera, &points, on_screen);
        let hit = hit.unwrap_or_else(|| panic!("clipped segment not picked"));
        assert_eq!(hit.segment, 0);
        assert!(hit.t < 0.01 && hit.distance_px < 0.5, "{hit:?}");
        // A segment entirely behind the eye is never picked.
        let behind = [
            PathPoint::pen_up(eye - camera.forward() * 5.0),
            PathPoint::new(eye - camera.forward() * 6.0 + Vec3::X, Kind::Feed),
        ];
        let centre = VIEWPORT * 0.5;
        let vp = camera.view_proj(VIEWPORT.x / VIEWPORT.y);
        assert!(pick_segment(&behind, vp, VIEWPORT, centre, 1.0e6, 0).is_none());
    }

    #[test]
    fn perspective_t_is_in_world_space() {
        // A line receding from the eye: its world midpoint is not the screen midpoint.
        let mut camera = OrbitCamera::new(StandardView::Iso);
        camera.projection = Projection::Perspective;
        camera.fit_aspect(
            Vec3::splat(-50.0),
            Vec3::splat(50.0),
            VIEWPORT.x / VIEWPORT.y,
        );
        let a = Vec3::new(-50.0, 50.0, 0.0);
        let b = Vec3::new(50.0, -50.0, 0.0);
        let points = [PathPoint::pen_up(a), PathPoint::new(b, Kind::Feed)];
        let target = a.lerp(b, 0.3);
        let hit = pick(&camera, &points, screen(&camera, target));
        let hit = hit.unwrap_or_else(|| panic!("nothing picked"));
        assert!((hit.t - 0.3).abs() < 1e-3, "{hit:?}");
    }

    #[test]
    fn bounds_of_a_selection() {
        let points = square();
        let (min, max) = segment_bounds(&points, 1..3).unwrap_or((Vec3::NAN, Vec3::NAN));
        assert_eq!(min, Vec3::new(-40.0, -40.0, 0.0));
        assert_eq!(max, Vec3::new(40.0, 40.0, 0.0));
        let (min, max) = segment_bounds(&points, 4..5).unwrap_or((Vec3::NAN, Vec3::NAN));
        assert_eq!((min, max), (Vec3::new(-40.0, -40.0, 0.0), Vec3::ZERO));
        assert!(segment_bounds(&points, 5..6).is_none());
        assert!(segment_bounds(&points, 3..3).is_none());
        assert!(segment_bounds(&points, 10..20).is_none());
    }
}
