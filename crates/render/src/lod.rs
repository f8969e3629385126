//! Level of detail: runs of one kind within a tolerance of a chord are drawn as it, the tolerance
//! being [`LOD_TOLERANCE_PX`] in world units rounded down to a power of two, so it changes on a
//! zoom by two. Picking and segment numbers stay the full path's ([`PathLod::prepare`]).

use std::ops::Range;
use std::sync::Arc;

use glam::{Mat4, Vec2, Vec3, Vec3A};

use crate::camera::corners;
use crate::path::{Kind, PathPoint, PathRenderer, ViewParams};

/// Largest distance, in pixels, between the simplified path and the full path on screen.
pub const LOD_TOLERANCE_PX: f32 = 0.5;

/// Indices of the points kept when runs of one kind, colour and flags (solid, no pen up) become
/// chords within `tolerance` world units; keeps the ends, or all if `tolerance` is 0 or not finite.
#[must_use]
pub fn simplify(points: &[PathPoint], tolerance: f32) -> Vec<u32> {
    let Some(last) = points.len().checked_sub(1) else {
        return Vec::new();
    };
    let mut kept = vec![0];
    simplify_span(points, 0, last, tolerance, &mut kept);
    kept
}

/// Whether the segment ending at `p` may be merged with its neighbours of the same packed word:
/// drawn (no pen up), solid (a dashed line's pattern restarts at every segment) and finite.
fn mergeable(p: &PathPoint) -> bool {
    !p.is_pen_up()
        && !matches!(p.kind(), Some(Kind::Rapid | Kind::Programmed) | None)
        && p.position().is_finite()
}

/// Pushes the indices kept in `from + 1..=to` (`from` is already kept) onto `kept`.
fn simplify_span(points: &[PathPoint], from: usize, to: usize, tol: f32, kept: &mut Vec<u32>) {
    let to = to.min(points.len().saturating_sub(1));
    let merges = tol.is_finite() && tol > 0.0;
    let tol2 = if merges { tol * tol } else { 0.0 };
    let push = |kept: &mut Vec<u32>, i: usize| kept.push(u32::try_from(i).unwrap_or(u32::MAX));
    // The end of the run of mergeable points with one packed word that the anchor lies in.
    let mut run_end = from;
    let mut anchor = from;
    while anchor < to {
        let next = anchor + 1;
        if tol2 == 0.0 || !mergeable(&points[next]) {
            push(kept, next);
            anchor = next;
            continue;
        }
        if next > run_end {
            let packed = points[next].packed;
            run_end = next;
            while run_end < to
                && points[run_end + 1].packed == packed
                && mergeable(&points[run_end + 1])
            {
                run_end += 1;
            }
        }
        let end = farthest_chord(points, anchor, run_end, tol2);
        push(kept, end);
        anchor = end;
    }
}

/// The end of a chord from `anchor` (at most `limit`) within `sqrt(tol2)` of every point it
/// stands for, by doubling then bisecting (O(n log n)). Not inlined: a browser's wasm engine
/// optimises a function between calls, so this one runs optimised sooner (a third faster).
#[inline(never)]
fn farthest_chord(points: &[PathPoint], anchor: usize, limit: usize, tol2: f32) -> usize {
    let holds = |end: usize| chord_holds(points, anchor, end, tol2);
    // `bad` past `limit` until a chord fails; then `good` is `limit` unless one did.
    let (mut good, mut bad, mut step) = (anchor + 1, limit + 1, 2);
    while good < limit {
        let end = (anchor + step).min(limit);
        if !holds(end) {
            bad = end;
            break;
        }
        (good, step) = (end, step * 2);
    }
    while bad - good > 1 {
        let mid = good + (bad - good) / 2;
        *if holds(mid) { &mut good } else { &mut bad } = mid;
    }
    good
}

/// Whether every point strictly between `a` and `b` lies within `sqrt(tol2)` of the segment
/// from point `a` to point `b`.
fn chord_holds(points: &[PathPoint], a: usize, b: usize, tol2: f32) -> bool {
    let (Some(pa), Some(pb), Some(between)) = (points.get(a), points.get(b), points.get(a + 1..b))
    else {
        return false;
    };
    let (pa, pb) = (Vec3A::from(pa.position), Vec3A::from(pb.position));
    let d = pb - pa;
    let len2 = d.length_squared();
    let scale = if len2 > 0.0 { len2.recip() } else { 0.0 };
    let off = |p: &PathPoint| {
        let v = Vec3A::from(p.position) - pa;
        (v - d * (v.dot(d) * scale).clamp(0.0, 1.0)).length_squared() <= tol2
    };
    // A chord that does not hold is mostly furthest from its middle: look there first.
    between.get(between.len() / 2).is_none_or(off) && between.iter().all(off)
}

/// The most pixels one world unit spans on a `viewport` target through `view_proj` anywhere
/// in the box `bounds` (lines project to lines, so a chord within ε of a run is within ε times
/// this on screen); `None` when part of the box lies at or behind the eye.
#[must_use]
pub fn pixels_per_unit(view_proj: Mat4, viewport: Vec2, (min, max): (Vec3, Vec3)) -> Option<f32> {
    let half = viewport * 0.5;
    let row_x = view_proj.row(0).truncate() * half.x;
    let row_y = view_proj.row(1).truncate() * half.y;
    let row_w = view_proj.row(3);
    let w_min = corners(min, max)
        .map(|corner| row_w.dot(corner.extend(1.0)))
        .fold(f32::INFINITY, f32::min);
    // The largest singular value of the 2×3 screen Jacobian of an affine view, plus what the
    // perspective divide adds on screen (|ndc| ≤ 1), over the nearest depth.
    let (xx, xy, yy) = (row_x.dot(row_x), row_x.dot(row_y), row_y.dot(row_y));
    let affine = ((xx + yy) * 0.5 + (((xx - yy) * 0.5).powi(2) + xy * xy).sqrt()).sqrt();
    let divide = row_w.truncate().length() * half.length();
    let scale = (affine + divide) / w_min;
    (w_min > 0.0 && scale.is_finite()).then_some(scale)
}

/// The level (log2 of the tolerance in world units) at which `params` shows a path within
/// `bounds`, keeping `current` while it is between a quarter and all of the tolerance needed;
/// `None`: every point is drawn (part of the box lies at or behind the eye).
#[must_use]
pub fn lod_level(params: &ViewParams, bounds: (Vec3, Vec3), current: Option<i32>) -> Option<i32> {
    let scale = pixels_per_unit(params.view_proj, params.viewport_px, bounds)?;
    let needed = (LOD_TOLERANCE_PX / scale).log2();
    if !needed.is_finite() {
        return None;
    }
    let keeps = |l: i32| (l as f32) <= needed && needed < (l + 2) as f32;
    match current {
        Some(level) if keeps(level) => Some(level),
        _ => Some(needed.floor().clamp(-60.0, 60.0) as i32),
    }
}

/// The indices [`simplify`] keeps at `level` (log2 of the tolerance; `None`: every point).
#[must_use]
pub fn simplify_at(points: &[PathPoint], level: Option<i32>) -> Vec<u32> {
    match level {
        Some(level) => simplify(points, (level as f32).exp2()),
        None => (0..points.len())
            .map(|i| u32::try_from(i).unwrap_or(u32::MAX))
            .collect(),
    }
}

/// What the renderer holds of the path: made with a level, highlight breaks and flagged runs.
#[derive(Clone, Debug, PartialEq)]
struct Uploaded {
    level: Option<i32>,
    breaks: Vec<u32>,
    flagged: Vec<Range<usize>>,
}

/// A toolpath drawn at the level of detail its view needs (see the module's documentation).
#[derive(Debug, Default)]
pub struct PathLod {
    points: Arc<Vec<PathPoint>>,
    /// A box around the points, where the view's scale is taken.
    bounds: Option<(Vec3, Vec3)>,
    /// Tolerance of `base` as a power of two (world units); `None`: every point is kept.
    level: Option<i32>,
    /// Indices kept at `level`, before the highlight and playback breaks are added.
    base: Option<Arc<Vec<u32>>>,
    /// Whether `base` is given ([`PathLod::given`]) rather than made here for the view.
    given: bool,
    /// Indices of the points the renderer holds, ascending.
    drawn: Vec<u32>,
    uploaded: Option<Uploaded>,
}

impl PathLod {
    /// The toolpath's points (as [`PathRenderer::set_path`] takes them), not yet simplified,
    /// and a box around them (see [`crate::segment_bounds`]; `None`: never simplified).
    #[must_use]
    pub fn new(points: Arc<Vec<PathPoint>>, bounds: Option<(Vec3, Vec3)>) -> Self {
        Self {
            points,
            bounds,
            ..Self::default()
        }
    }

    /// The toolpath's points, simplified elsewhere (by the analysis, beside the frames) and
    /// given with [`Self::set_base`]: [`Self::prepare`] then never simplifies, and draws
    /// nothing of the path until a base is given.
    #[must_use]
    pub fn given(points: Arc<Vec<PathPoint>>, bounds: Option<(Vec3, Vec3)>) -> Self {
        Self {
            given: true,
            ..Self::new(points, bounds)
        }
    }

    /// Gives the indices [`simplify_at`] keeps of the points at `level` (see [`Self::given`]);
    /// whether they are other than those it holds (the same `Arc` changes nothing).
    pub fn set_base(&mut self, level: Option<i32>, base: &Arc<Vec<u32>>) -> bool {
        if self.base.as_ref().is_some_and(|b| Arc::ptr_eq(b, base)) {
            return false;
        }
        self.level = level;
        self.base = Some(Arc::clone(base));
        self.uploaded = None;
        true
    }

    /// Segments the renderer draws of the path (one fewer than the points it holds).
    #[must_use]
    pub fn drawn_segments(&self) -> usize {
        self.drawn.len().saturating_sub(1)
    }

    /// Puts the path as `params` shows it, `flagged` highlighted, into `renderer` (simplified again
    /// only at a new zoom level, uploaded only on change); returns `params` renumbered to match.
    pub fn prepare(
        &mut self,
        renderer: &mut PathRenderer,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        params: &ViewParams,
        flagged: &[Range<usize>],
    ) -> ViewParams {
        if !self.given {
            let current = self.base.as_ref().and(self.level);
            let level = self.bounds.and_then(|b| lod_level(params, b, current));
            if self.base.is_none() || level != self.level {
                self.level = level;
                self.base = Some(Arc::new(simplify_at(&self.points, level)));
            }
        }
        let level = self.level;
        let last = u32::try_from(self.points.len().saturating_sub(1)).unwrap_or(u32::MAX);
        let point = |i: usize| u32::try_from(i).unwrap_or(u32::MAX).min(last);
        let mut breaks: Vec<u32> = flagged
            .iter()
            .flat_map(|run| [point(run.start), point(run.end)])
            .chain([params.highlight.start, params.highlight.end].map(|i| i.min(last)))
            .chain(params.executed_segments.map(|e| e.min(last)))
            .collect();
        breaks.sort_unstable();
        breaks.dedup();
        let wanted = Uploaded {
            level,
            breaks,
            flagged: flagged.to_vec(),
        };
        if self.uploaded.as_ref() != Some(&wanted) {
            let tolerance = level.map_or(0.0, |l| (l as f32).exp2());
            let base = self.base.as_deref().map_or(&[][..], Vec::as_slice);
            let drawn = with_breaks(&self.points, base, &wanted.breaks, tolerance);
            // A highlight moved to points already kept changes no point.
            let same_flags = (self.uploaded.as_ref()).is_some_and(|u| u.flagged == wanted.flagged);
            // Every point drawn (`drawn` ascends) and none highlighted: the points as they are,
            // not a copy (a path that does not simplify may be tens of millions of points).
            let changed = drawn != self.drawn || !same_flags;
            if changed && flagged.is_empty() && drawn.len() == self.points.len() {
                renderer.set_path(device, queue, &self.points);
            } else if changed {
                let mut points: Vec<PathPoint> = drawn
                    .iter()
                    .filter_map(|&i| self.points.get(i as usize).copied())
                    .collect();
                for run in flagged {
                    let from = position(&drawn, point(run.start));
                    let to = position(&drawn, point(run.end));
                    for p in points.get_mut(from + 1..=to).into_iter().flatten() {
                        *p = p.with_highlight(true);
                    }
                }
                renderer.set_path(device, queue, &points);
            }
            self.drawn = drawn;
            self.uploaded = Some(wanted);
        }
        let renumber =
            |i: u32| u32::try_from(position(&self.drawn, i.min(last))).unwrap_or(u32::MAX);
        ViewParams {
            highlight: renumber(params.highlight.start)..renumber(params.highlight.end),
            executed_segments: params.executed_segments.map(renumber),
            ..params.clone()
        }
    }
}

/// Where point `i` is in the ascending `drawn` (the first index at or after it).
fn position(drawn: &[u32], i: u32) -> usize {
    drawn.partition_point(|&k| k < i)
}

/// `base` with every point of `breaks` (ascending) kept too: each chord of `base` with breaks
/// inside is simplified again between them, with the same tolerance.
fn with_breaks(points: &[PathPoint], base: &[u32], breaks: &[u32], tolerance: f32) -> Vec<u32> {
    let mut out = Vec::with_capacity(base.len() + breaks.len());
    let mut pending = breaks.iter().copied().peekable();
    let mut chords = base.iter().copied();
    let Some(first) = chords.next() else {
        return out;
    };
    out.push(first);
    let mut from = first;
    for to in chords {
        let split = from;
        while let Some(b) = pending.next_if(|&b| b < to) {
            if b > from {
                simplify_span(points, from as usize, b as usize, tolerance, &mut out);
                from = b;
            }
        }
        if from == split {
            out.push(to);
        } else {
            simplify_span(points, from as usize, to as usize, tolerance, &mut out);
        }
        from = to;
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{OrbitCamera, StandardView};

    /// The surfacing program of the web benchmark: `rows` rows of 400 feeds of 0.25 mm along X,
    /// 0.5 mm apart in Y, Z a smooth sine, after a rapid down to the start.
    fn surfacing(rows: usize) -> Vec<PathPoint> {
        let mut points = vec![
            PathPoint::pen_up(Vec3::new(0.0, 0.0, 5.0)),
            PathPoint::new(Vec3::ZERO, Kind::Feed),
        ];
        for n in 0..rows * 400 {
            let x = (n % 400) as f32 * 0.25;
            let y = (n / 400) as f32 * 0.5;
            let z = -((x * 0.07).sin() * (y * 0.05).cos()).abs() * 3.0;
            points.push(PathPoint::new(Vec3::new(x, y, z), Kind::Feed));
        }
        points
    }

    /// Deterministic noise in -1..1.
    fn noise(i: usize) -> f32 {
        let h = (i as u32).wrapping_mul(2_654_435_761).rotate_left(13) ^ 0x9e37_79b9;
        (h % 20_001) as f32 / 10_000.0 - 1.0
    }

    /// A wandering path of every kind, with pen ups, a non-finite point and a part that goes
    /// back over itself.
    fn mixed(n: usize) -> Vec<PathPoint> {
        let kinds = [
            Kind::Feed,
            Kind::Arc,
            Kind::Rapid,
            Kind::Plunge,
            Kind::Compensated,
        ];
        (0..n)
            .map(|i| {
                let t = i as f32 * 0.02;
                let p = Vec3::new(t.cos() * 10.0, (t * 0.7).sin() * 10.0, noise(i) * 0.05);
                let p = if (300..340).contains(&i) {
                    Vec3::new(20.0 - (i as f32 - 320.0).abs() * 0.1, 0.0, 0.0)
                } else {
                    p
                };
                match i {
                    _ if i % 211 == 0 => PathPoint::pen_up(p),
                    777 => PathPoint::new(Vec3::NAN, Kind::Feed),
                    _ => PathPoint::new(p, kinds[(i / 60) % kinds.len()])
                        .with_color_index(u16::from(i > n / 2)),
                }
            })
            .collect()
    }

    fn distance_to_segment(p: Vec3, a: Vec3, b: Vec3) -> f32 {
        let d = b - a;
        let t = if d.length_squared() > 0.0 {
            ((p - a).dot(d) / d.length_squared()).clamp(0.0, 1.0)
        } else {
            0.0
        };
        (p - (a + d * t)).length()
    }

    /// Every point is within `tolerance` of the chord standing for it, and a chord stands only
    /// for segments that may be merged, all alike: kind, colour and pen-up boundaries are kept.
    fn assert_keeps_the_picture(points: &[PathPoint], kept: &[u32], tolerance: f32) {
        assert_eq!(kept.first(), Some(&0));
        assert_eq!(kept.last().map(|&k| k as usize), Some(points.len() - 1));
        for chord in kept.windows(2) {
            let (a, b) = (chord[0] as usize, chord[1] as usize);
            assert!(a < b, "indices ascend: {a}, {b}");
            if b == a + 1 {
                continue;
            }
            let (pa, pb) = (points[a].position(), points[b].position());
            for (i, p) in points.iter().enumerate().take(b + 1).skip(a + 1) {
                assert!(
                    mergeable(p),
                    "point {i} may not be merged, yet {a}..{b} stand for it"
                );
                assert_eq!(
                    p.packed, points[b].packed,
                    "point {i} differs from the chord {a}..{b}"
                );
                let off = distance_to_segment(p.position(), pa, pb);
                assert!(
                    off <= tolerance * 1.001,
                    "point {i} is {off} off {a}..{b} (tolerance {tolerance})"
                );
            }
        }
    }

    #[test]
    fn simplification_stays_within_the_tolerance_and_keeps_every_boundary() {
        let points = mixed(3000);
        for tolerance in [0.0, 0.01, 0.1, 0.5, 2.0, 50.0] {
            let kept = simplify(&points, tolerance);
            assert_keeps_the_picture(&points, &kept, tolerance);
            if tolerance == 0.0 {
                assert_eq!(kept.len(), points.len());
            }
        }
        // Rapids (dashed) and the segment into a non-finite point are never merged.
        let kept = simplify(&points, 50.0);
        for (i, p) in points.iter().enumerate().skip(1) {
            if !mergeable(p) {
                assert!(
                    kept.contains(&(i as u32)) && kept.contains(&(i as u32 - 1)),
                    "point {i}"
                );
            }
        }
        assert!(
            kept.len() < points.len() / 2,
            "{} of {} kept",
            kept.len(),
            points.len()
        );
        // A line that turns back on itself keeps its far end.
        let back: Vec<PathPoint> = [0.0, 1.0, 2.0, 3.0, 2.5, 2.0]
            .iter()
            .map(|&x| PathPoint::new(Vec3::new(x, 0.0, 0.0), Kind::Feed))
            .collect();
        assert_eq!(simplify(&back, 0.1), [0, 3, 5]);
        assert!(simplify(&[], 1.0).is_empty());
        assert_eq!(simplify(&back[..1], 1.0), [0]);
    }

    #[test]
    fn breaks_are_kept_and_chords_between_them_stay_within_the_tolerance() {
        let points = mixed(3000);
        let base = simplify(&points, 0.5);
        let breaks = [5, 6, 1234, 2000, 2999];
        let drawn = with_breaks(&points, &base, &breaks, 0.5);
        assert_keeps_the_picture(&points, &drawn, 0.5);
        for b in breaks {
            assert!(drawn.contains(&b), "break {b}");
        }
        assert!(drawn.len() <= base.len() + 2 * breaks.len());
        assert_eq!(with_breaks(&points, &base, &[], 0.5), base);
    }

    #[test]
    fn the_surfacing_program_at_fit_all_draws_a_few_percent_of_its_segments() {
        let points = surfacing(2500);
        let (min, max) = crate::segment_bounds(&points, 0..points.len()).unwrap();
        // The backplot of the web page at 1280×800.
        let viewport = Vec2::new(540.0, 682.0);
        let mut camera = OrbitCamera::new(StandardView::Iso);
        camera.fit_aspect(min, max, viewport.x / viewport.y);
        let view_proj = camera.view_proj(viewport.x / viewport.y);
        let scale = pixels_per_unit(view_proj, viewport, (min, max)).unwrap();
        let tolerance = LOD_TOLERANCE_PX / scale;
        let kept = simplify(&points, tolerance);
        assert_keeps_the_picture(&points, &kept, tolerance);
        assert!(
            kept.len() * 20 < points.len(),
            "{} of {} points kept at {tolerance} mm",
            kept.len(),
            points.len()
        );
        // On screen, no point is more than half a pixel off what is drawn.
        let screen = |p: Vec3| {
            let c = view_proj * p.extend(1.0);
            Vec3::new(
                c.x / c.w * viewport.x * 0.5,
                c.y / c.w * viewport.y * 0.5,
                0.0,
            )
        };
        for chord in kept.windows(2).step_by(7) {
            let (a, b) = (chord[0] as usize, chord[1] as usize);
            let (sa, sb) = (screen(points[a].position()), screen(points[b].position()));
            for p in &points[a + 1..b] {
                let off = distance_to_segment(screen(p.position()), sa, sb);
                assert!(off <= LOD_TOLERANCE_PX, "{off} px off the chord {a}..{b}");
            }
        }
    }

    #[test]
    fn the_scale_is_exact_for_a_parallel_view_and_none_behind_the_eye() {
        let bounds = (Vec3::splat(-1.0), Vec3::splat(1.0));
        let view_proj = Mat4::from_scale(Vec3::new(0.1, 0.1, 0.01));
        let scale = pixels_per_unit(view_proj, Vec2::new(200.0, 200.0), bounds).unwrap();
        assert!((scale - 10.0).abs() < 1e-4, "{scale}");
        let mut camera = OrbitCamera::new(StandardView::Top);
        camera.projection = crate::Projection::Perspective;
        camera.fit_aspect(Vec3::splat(-1.0), Vec3::splat(1.0), 1.0);
        let perspective = camera.view_proj(1.0);
        assert!(pixels_per_unit(perspective, Vec2::splat(100.0), bounds).is_some());
        assert_eq!(
            pixels_per_unit(
                perspective,
                Vec2::splat(100.0),
                (Vec3::splat(-1e6), Vec3::splat(1e6))
            ),
            None
        );
    }

    #[test]
    fn picking_over_the_chords_drawn_finds_what_picking_every_segment_finds() {
        use crate::{Projection, pick_kept_segment, pick_segment};
        let viewport = Vec2::new(800.0, 600.0);
        let cases = [
            (surfacing(60), Projection::Orthographic, 1.0),
            (surfacing(60), Projection::Orthographic, 3.0),
            (mixed(2000), Projection::Perspective, 1.0),
            (mixed(2000), Projection::Orthographic, 2.5),
        ];
        for (points, projection, zoom) in cases {
            let finite = points
                .iter()
                .map(PathPoint::position)
                .filter(|p| p.is_finite());
            let (min, max) = finite.fold((Vec3::INFINITY, Vec3::NEG_INFINITY), |(lo, hi), p| {
                (lo.min(p), hi.max(p))
            });
            let mut camera = OrbitCamera::new(StandardView::Iso);
            camera.projection = projection;
            camera.fit_aspect(min, max, viewport.x / viewport.y);
            let fitted = ViewParams {
                view_proj: camera.view_proj(viewport.x / viewport.y),
                viewport_px: viewport,
                ..ViewParams::default()
            };
            let level = lod_level(&fitted, (min, max), None);
            let kept = simplify_at(&points, level);
            assert!(
                kept.len() < points.len(),
                "{} of {}",
                kept.len(),
                points.len()
            );
            // Zoomed in since that level was made (as while the next one is on its way).
            camera.zoom(zoom);
            let view_proj = camera.view_proj(viewport.x / viewport.y);
            let scale = pixels_per_unit(view_proj, viewport, (min, max)).unwrap();
            let slack = (level.unwrap() as f32).exp2() * scale + 0.01;
            let mut hits = 0;
            for (x, y) in (0..48).flat_map(|x| (0..36).map(move |y| (x, y))) {
                let cursor = Vec2::new(x as f32 + 0.37, y as f32 + 0.61) * 16.7;
                for hidden in [0, Kind::Feed.mask()] {
                    let all = pick_segment(&points, view_proj, viewport, cursor, 6.0, hidden);
                    let drawn = (view_proj, viewport, cursor);
                    let over = pick_kept_segment(&points, &kept, drawn, 6.0, hidden, slack);
                    assert_eq!(over, all, "{cursor} zoom {zoom} hidden {hidden}");
                    hits += usize::from(all.is_some());
                }
            }
            assert!(hits > 50, "{hits} hits");
        }
    }
}
