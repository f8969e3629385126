//! Orbit camera for the backplot: Z-up, right-handed, wgpu depth range 0..1. It orbits `target` at
//! `distance`, `yaw` about +Z from +X, `pitch` above XY; Top looks down −Z with +Y up.

use glam::camera::rh::proj::directx;
use glam::camera::rh::view::look_to_mat4;
use glam::{BVec3, Mat4, Vec2, Vec3};

/// Smallest allowed orbit distance, so zooming in can never collapse the view to a point.
pub const MIN_DISTANCE: f32 = 1.0e-4;
/// Largest allowed orbit distance, so zooming out stays well inside f32 range.
pub const MAX_DISTANCE: f32 = 1.0e7;
/// Default orbit distance (and scene radius) used before anything has been fitted.
const DEFAULT_DISTANCE: f32 = 100.0;
/// Radians of orbit per pixel of mouse drag.
const ORBIT_RADIANS_PER_PX: f32 = 0.01;
/// Fraction of the view left free around a fitted box (1.1 = 10 % margin).
const FIT_MARGIN: f32 = 1.1;
/// Most steps back [`OrbitCamera::fit_in`] takes to fit a box in perspective.
const FIT_IN_STEPS: usize = 16;
/// Perspective near plane as a fraction of the orbit distance.
const NEAR_FRACTION: f32 = 1.0e-3;

/// Perspective or parallel projection.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Projection {
    /// Perspective projection with vertical field of view [`OrbitCamera::fov_y`].
    Perspective,
    /// Parallel projection; its scale matches the perspective view at the target's depth.
    #[default]
    Orthographic,
}

/// The standard machinist's views.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum StandardView {
    /// From front-right-above (eye towards +X, −Y, +Z): X runs right-down, Y right-up, Z up.
    Iso,
    /// Looking down −Z: +X right, +Y up.
    Top,
    /// Looking along +Y from the front: +X right, +Z up.
    Front,
    /// Looking along −X from the right: +Y right, +Z up.
    Right,
}

impl StandardView {
    /// `(yaw, pitch)` in radians for this view.
    #[must_use]
    pub fn angles(self) -> (f32, f32) {
        use std::f32::consts::{FRAC_PI_2, FRAC_PI_4};
        match self {
            // Elevation of the cube diagonal (1, -1, 1): atan(1 / sqrt 2).
            Self::Iso => (-FRAC_PI_4, std::f32::consts::FRAC_1_SQRT_2.atan()),
            Self::Top => (-FRAC_PI_2, FRAC_PI_2),
            Self::Front => (-FRAC_PI_2, 0.0),
            Self::Right => (0.0, 0.0),
        }
    }
}

/// An orbit camera (f32, Z up) producing wgpu-ready view-projection matrices. Fields are public for
/// persistence; every method sanitises them, so no value gives NaN matrices.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct OrbitCamera {
    /// Point orbited around and looked at.
    pub target: Vec3,
    /// Distance from the eye to `target`; also sets the orthographic scale.
    pub distance: f32,
    /// Azimuth of the eye around +Z, radians from +X (counter-clockwise seen from above).
    pub yaw: f32,
    /// Elevation of the eye above the XY plane, radians in `[-π/2, π/2]`.
    pub pitch: f32,
    /// Perspective or orthographic projection.
    pub projection: Projection,
    /// Vertical field of view in radians (for orthographic it sets the scale at `distance`).
    pub fov_y: f32,
    /// Radius of the last fitted scene, used to keep orthographic clipping planes generous.
    pub scene_radius: f32,
}

impl Default for OrbitCamera {
    fn default() -> Self {
        let (yaw, pitch) = StandardView::Iso.angles();
        Self {
            target: Vec3::ZERO,
            distance: DEFAULT_DISTANCE,
            yaw,
            pitch,
            projection: Projection::default(),
            fov_y: 30f32.to_radians(),
            scene_radius: DEFAULT_DISTANCE,
        }
    }
}

/// The eight corners of the box `min..max`.
pub(crate) fn corners(min: Vec3, max: Vec3) -> impl Iterator<Item = Vec3> {
    (0..8).map(move |i| Vec3::select(BVec3::new(i & 1 != 0, i & 2 != 0, i & 4 != 0), max, min))
}

/// Returns `value` if finite, else `fallback`.
pub(crate) fn finite_or(value: f32, fallback: f32) -> f32 {
    if value.is_finite() { value } else { fallback }
}

/// Sanitises an aspect ratio (width / height): positive and finite, else 1.
fn sane_aspect(aspect: f32) -> f32 {
    if aspect.is_finite() && aspect > 1.0e-6 {
        aspect.min(1.0e6)
    } else {
        1.0
    }
}

impl OrbitCamera {
    /// A camera in the given standard view, orbiting the origin at the default distance.
    #[must_use]
    pub fn new(view: StandardView) -> Self {
        let mut camera = Self::default();
        camera.set_view(view);
        camera
    }

    /// Sanitised distance (finite, clamped).
    fn dist(&self) -> f32 {
        finite_or(self.distance, DEFAULT_DISTANCE).clamp(MIN_DISTANCE, MAX_DISTANCE)
    }

    /// Sanitised vertical field of view, between 1° and 120°.
    fn fov(&self) -> f32 {
        finite_or(self.fov_y, 30f32.to_radians()).clamp(1f32.to_radians(), 120f32.to_radians())
    }

    /// Sanitised target.
    fn tgt(&self) -> Vec3 {
        (Some(self.target).filter(|t| t.is_finite())).unwrap_or(Vec3::ZERO)
    }

    /// Camera basis `(right, up, back)`: `back` points from the target towards the eye.
    #[must_use]
    pub fn basis(&self) -> (Vec3, Vec3, Vec3) {
        let yaw = finite_or(self.yaw, 0.0);
        let pitch = finite_or(self.pitch, 0.0)
            .clamp(-std::f32::consts::FRAC_PI_2, std::f32::consts::FRAC_PI_2);
        let (sy, cy) = yaw.sin_cos();
        let (sp, cp) = pitch.sin_cos();
        let back = Vec3::new(cp * cy, cp * sy, sp);
        let right = Vec3::new(-sy, cy, 0.0);
        let up = back.cross(right);
        (right, up, back)
    }

    /// Unit vector the camera looks along (from the eye towards the target).
    #[must_use]
    pub fn forward(&self) -> Vec3 {
        -self.basis().2
    }

    /// Eye position in world space.
    #[must_use]
    pub fn eye(&self) -> Vec3 {
        self.tgt() + self.basis().2 * self.dist()
    }

    /// World units per screen pixel at the target's depth, for a viewport `height_px` tall.
    #[must_use]
    pub fn units_per_px(&self, height_px: f32) -> f32 {
        let height_px = finite_or(height_px, 1.0).max(1.0);
        2.0 * self.dist() * (self.fov() * 0.5).tan() / height_px
    }

    /// Jumps to one of the standard views, keeping target and distance.
    pub fn set_view(&mut self, view: StandardView) {
        (self.yaw, self.pitch) = view.angles();
    }

    /// Frames `min..max` with a margin for a viewport of `aspect` (width / height), keeping the
    /// view direction; an empty or non-finite box frames the origin, a zero-size one a small area.
    pub fn fit_aspect(&mut self, min: Vec3, max: Vec3, aspect: f32) {
        let tan_y = (self.fov() * 0.5).tan();
        self.fit_tangents(min, max, tan_y * sane_aspect(aspect), tan_y);
    }

    /// Like [`Self::fit_aspect`], but framing in `free_min..free_max` (pixels from the top-left) of
    /// the `viewport_px` viewport, e.g. below overlaid buttons; an invalid part means all of it.
    pub fn fit_in(
        &mut self,
        min: Vec3,
        max: Vec3,
        viewport_px: Vec2,
        free_min: Vec2,
        free_max: Vec2,
    ) {
        let valid = viewport_px.is_finite()
            && viewport_px.cmpge(Vec2::ONE).all()
            && free_min.is_finite()
            && free_max.is_finite()
            && (free_max - free_min).cmpge(Vec2::ONE).all();
        if !valid {
            self.fit_aspect(min, max, viewport_px.x / viewport_px.y);
            return;
        }
        let (free_min, free_max) = (free_min.max(Vec2::ZERO), free_max.min(viewport_px));
        let free = (free_max - free_min).max(Vec2::ONE);
        // The frustum through the free part: its share of the viewport's field of view.
        let tan = free * (self.fov() * 0.5).tan() / viewport_px.y;
        self.fit_tangents(min, max, tan.x, tan.y);
        if !min.is_finite() || !max.is_finite() || min.cmpgt(max).any() {
            return;
        }
        // Then move the box's centre from the viewport's centre to the free part's. In
        // perspective the box's depth makes that shift inexact: step back until it fits.
        let center = (min + max) * 0.5;
        let shift = (free_min + free_max) * 0.5 - viewport_px * 0.5;
        let (right, up, _) = self.basis();
        for _ in 0..FIT_IN_STEPS {
            let upp = self.units_per_px(viewport_px.y);
            let target = center - right * (shift.x * upp) + up * (shift.y * upp);
            if !target.is_finite() {
                return;
            }
            self.target = target;
            if self.projection == Projection::Orthographic
                || self.frames_in(min, max, viewport_px, free_min, free_max)
            {
                return;
            }
            self.distance = (self.dist() * 1.1).clamp(MIN_DISTANCE, MAX_DISTANCE);
        }
    }

    /// Whether every corner of the box `min..max` is seen inside the pixels `lo..hi` of a
    /// viewport `view` pixels wide and high (half a pixel of slack).
    fn frames_in(&self, min: Vec3, max: Vec3, view: Vec2, lo: Vec2, hi: Vec2) -> bool {
        let view_proj = self.view_proj(view.x / view.y);
        corners(min, max).all(|corner| {
            let clip = view_proj * corner.extend(1.0);
            if clip.w <= 0.0 {
                return false;
            }
            let px = Vec2::new(
                (clip.x / clip.w + 1.0) * 0.5 * view.x,
                (1.0 - clip.y / clip.w) * 0.5 * view.y,
            );
            px.cmpge(lo - 0.5).all() && px.cmple(hi + 0.5).all()
        })
    }

    /// Frames the box `min..max` so that it fits a frustum of half-angle tangents `tan_x`,
    /// `tan_y` about the view axis, with a margin (see [`Self::fit_aspect`]).
    fn fit_tangents(&mut self, min: Vec3, max: Vec3, tan_x: f32, tan_y: f32) {
        if !min.is_finite() || !max.is_finite() || min.cmpgt(max).any() {
            self.target = Vec3::ZERO;
            self.distance = DEFAULT_DISTANCE;
            self.scene_radius = DEFAULT_DISTANCE;
            return;
        }
        let tan_x = finite_or(tan_x, 1.0).max(1.0e-6);
        let tan_y = finite_or(tan_y, 1.0).max(1.0e-6);
        let center = (min + max) * 0.5;
        let radius = (max - min).length() * 0.5;
        let radius = if radius > 1.0e-6 { radius } else { 1.0 };
        // Never frame less than a twentieth of the scene, so flat or end-on boxes stay sane.
        let floor = radius * 0.05;
        let (right, up, back) = self.basis();
        let mut needed: f32 = 0.0;
        for corner in corners(min, max) {
            let offset = corner - center;
            let x = offset.dot(right).abs().max(floor) * FIT_MARGIN;
            let y = offset.dot(up).abs().max(floor) * FIT_MARGIN;
            let d = match self.projection {
                // The corner is `offset·back` nearer to the eye than the target is.
                Projection::Perspective => offset.dot(back) + (x / tan_x).max(y / tan_y),
                Projection::Orthographic => (x / tan_x).max(y / tan_y),
            };
            needed = needed.max(d);
        }
        self.target = center;
        self.distance = finite_or(needed, DEFAULT_DISTANCE).clamp(MIN_DISTANCE, MAX_DISTANCE);
        self.scene_radius = radius;
    }

    /// Frames the box `min..max` (e.g. [`crate::segment_bounds`]) like [`Self::fit_aspect`], not
    /// shrinking [`Self::scene_radius`] so the scene stays in the orthographic depth range.
    /// Invalid boxes leave the camera unchanged.
    pub fn zoom_to_selection(&mut self, min: Vec3, max: Vec3, aspect: f32) {
        if !min.is_finite() || !max.is_finite() || min.cmpgt(max).any() {
            return;
        }
        let scene_radius = finite_or(self.scene_radius, DEFAULT_DISTANCE).abs();
        self.fit_aspect(min, max, aspect);
        self.scene_radius = self.scene_radius.max(scene_radius);
    }

    /// Orbits by a mouse drag: horizontal spins around Z, vertical tilts (drag down = look
    /// more from above, as if grabbing the model's front face).
    pub fn orbit(&mut self, delta_px: Vec2) {
        if !delta_px.is_finite() {
            return;
        }
        let yaw = finite_or(self.yaw, 0.0) - delta_px.x * ORBIT_RADIANS_PER_PX;
        self.yaw = yaw.rem_euclid(std::f32::consts::TAU);
        self.pitch = (finite_or(self.pitch, 0.0) + delta_px.y * ORBIT_RADIANS_PER_PX)
            .clamp(-std::f32::consts::FRAC_PI_2, std::f32::consts::FRAC_PI_2);
    }

    /// Pans by a mouse drag of `delta_px` (screen pixels, y down) in a viewport of
    /// `viewport_px`, so that the point under the cursor (at the target's depth) follows it.
    pub fn pan(&mut self, delta_px: Vec2, viewport_px: Vec2) {
        if !delta_px.is_finite() || !viewport_px.is_finite() || viewport_px.y < 1.0 {
            return;
        }
        let upp = self.units_per_px(viewport_px.y);
        let (right, up, _) = self.basis();
        let target = self.tgt() - right * (delta_px.x * upp) + up * (delta_px.y * upp);
        if target.is_finite() {
            self.target = target;
        }
    }

    /// Zooms by `factor` (> 1 zooms in), keeping the distance within limits.
    pub fn zoom(&mut self, factor: f32) {
        if factor.is_finite() && factor > 0.0 {
            self.distance = (self.dist() / factor).clamp(MIN_DISTANCE, MAX_DISTANCE);
        }
    }

    /// Zooms by `factor` (> 1 zooms in) keeping the point under `cursor_px` (relative to the
    /// viewport's top-left corner, at the target's depth) fixed on screen.
    pub fn zoom_at(&mut self, factor: f32, cursor_px: Vec2, viewport_px: Vec2) {
        let valid = factor.is_finite()
            && factor > 0.0
            && cursor_px.is_finite()
            && viewport_px.is_finite()
            && viewport_px.y >= 1.0;
        if !valid {
            return;
        }
        let upp = self.units_per_px(viewport_px.y);
        let (right, up, _) = self.basis();
        let from_center = cursor_px - viewport_px * 0.5;
        let offset = right * (from_center.x * upp) - up * (from_center.y * upp);
        let before = self.dist();
        let after = (before / factor).clamp(MIN_DISTANCE, MAX_DISTANCE);
        let target = self.tgt() + offset * (1.0 - after / before);
        if target.is_finite() {
            self.target = target;
        }
        self.distance = after;
    }

    /// Combined view-projection matrix (right-handed, Z up, depth 0..1) for a viewport of the
    /// given aspect (width / height), for wgpu.
    #[must_use]
    pub fn view_proj(&self, aspect: f32) -> Mat4 {
        let aspect = sane_aspect(aspect);
        let distance = self.dist();
        let projection = match self.projection {
            Projection::Perspective => {
                directx::perspective_infinite(self.fov(), aspect, distance * NEAR_FRACTION)
            }
            Projection::Orthographic => {
                let h = distance * (self.fov() * 0.5).tan();
                let w = h * aspect;
                // A generous slab so nothing is clipped; Depth32Float keeps enough precision.
                let radius = finite_or(self.scene_radius, DEFAULT_DISTANCE).abs();
                let d = 10.0 * (radius + distance) + 1.0;
                directx::orthographic(-w, w, -h, h, distance - d, distance + d)
            }
        };
        let (_, up, back) = self.basis();
        projection * look_to_mat4(self.eye(), -back, up)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const VIEWS: [StandardView; 4] = [
        StandardView::Iso,
        StandardView::Top,
        StandardView::Front,
        StandardView::Right,
    ];
    const PROJECTIONS: [Projection; 2] = [Projection::Perspective, Projection::Orthographic];

    fn corners(min: Vec3, max: Vec3) -> impl Iterator<Item = Vec3> {
        (0..8).map(move |i| {
            Vec3::new(
                if i & 1 == 0 { min.x } else { max.x },
                if i & 2 == 0 { min.y } else { max.y },
                if i & 4 == 0 { min.z } else { max.z },
            )
        })
    }

    fn assert_finite(m: Mat4) {
        assert!(m.is_finite(), "matrix has NaN/inf: {m:?}");
    }

    fn assert_inside_ndc(camera: &OrbitCamera, min: Vec3, max: Vec3, aspect: f32) {
        let vp = camera.view_proj(aspect);
        assert_finite(vp);
        for p in corners(min, max) {
            let clip = vp * p.extend(1.0);
            assert!(clip.w > 0.0, "corner {p} behind camera {camera:?}");
            let ndc = clip.truncate() / clip.w;
            assert!(
                ndc.x.abs() <= 1.0 && ndc.y.abs() <= 1.0 && (0.0..=1.0).contains(&ndc.z),
                "corner {p} -> {ndc} outside NDC; camera {camera:?} aspect {aspect}"
            );
        }
    }

    #[test]
    fn fit_in_frames_every_corner_inside_the_free_part() {
        let boxes = [
            (Vec3::new(-10.0, -20.0, -5.0), Vec3::new(110.0, 40.0, 3.0)),
            (Vec3::new(0.0, 0.0, 0.0), Vec3::new(100.0, 100.0, 0.0)),
            (Vec3::new(5.0, 5.0, -50.0), Vec3::new(5.0, 5.0, 0.0)),
            (Vec3::new(-3.0, -3.0, -3.0), Vec3::new(3.0, 3.0, 30.0)),
        ];
        let viewport = Vec2::new(800.0, 600.0);
        // Below a 30-pixel row of buttons, and a part off to one side.
        let parts = [
            (Vec2::new(0.0, 30.0), viewport),
            (Vec2::new(200.0, 100.0), Vec2::new(700.0, 400.0)),
        ];
        for (min, max) in boxes {
            for view in VIEWS {
                for projection in PROJECTIONS {
                    for (free_min, free_max) in parts {
                        let mut camera = OrbitCamera::new(view);
                        camera.projection = projection;
                        camera.fit_in(min, max, viewport, free_min, free_max);
                        assert!(
                            camera.frames_in(min, max, viewport, free_min, free_max),
                            "{min}..{max} not inside {free_min}..{free_max}: {camera:?}"
                        );
                        // Framed, not lost in a corner: it spans much of the free part.
                        let vp = camera.view_proj(viewport.x / viewport.y);
                        let xs: Vec<f32> =
                            corners(min, max).map(|p| vp.project_point3(p).x).collect();
                        let ys: Vec<f32> =
                            corners(min, max).map(|p| vp.project_point3(p).y).collect();
                        let span = |v: &[f32]| {
                            v.iter().copied().fold(f32::MIN, f32::max)
                                - v.iter().copied().fold(f32::MAX, f32::min)
                        };
                        let wide = span(&xs) * 0.5 * viewport.x / (free_max.x - free_min.x);
                        let high = span(&ys) * 0.5 * viewport.y / (free_max.y - free_min.y);
                        // (A line seen end-on, the third box from above, fills nothing.)
                        let end_on = min.x == max.x && view == StandardView::Top;
                        assert!(
                            end_on || wide.max(high) > 0.5,
                            "{min}..{max} fills {wide}×{high} of the part ({view:?})"
                        );
                    }
                }
            }
        }
        // An empty part frames in the whole viewport.
        let mut camera = OrbitCamera::new(StandardView::Iso);
        let (min, max) = boxes[0];
        camera.fit_in(min, max, viewport, Vec2::ZERO, Vec2::ZERO);
        assert_inside_ndc(&camera, min, max, viewport.x / viewport.y);
    }

    #[test]
    fn fit_frames_every_corner() {
        let boxes = [
            (Vec3::new(-10.0, -20.0, -5.0), Vec3::new(110.0, 40.0, 3.0)),
            (Vec3::new(0.0, 0.0, 0.0), Vec3::new(100.0, 100.0, 0.0)),
            (Vec3::new(5.0, 5.0, -50.0), Vec3::new(5.0, 5.0, 0.0)),
            (
                Vec3::new(1000.0, 2000.0, 3000.0),
                Vec3::new(1000.5, 2000.1, 3000.0),
            ),
            (Vec3::splat(-0.01), Vec3::splat(0.01)),
        ];
        for (min, max) in boxes {
            for view in VIEWS {
                for projection in PROJECTIONS {
                    for aspect in [0.3, 1.0, 2.5] {
                        let mut camera = OrbitCamera::new(view);
                        camera.projection = projection;
                        camera.fit_aspect(min, max, aspect);
                        assert_inside_ndc(&camera, min, max, aspect);
                    }
                }
            }
        }
    }

    #[test]
    fn zoom_to_selection_frames_it_and_keeps_the_scene_depth() {
        for projection in PROJECTIONS {
            let mut camera = OrbitCamera::new(StandardView::Iso);
            camera.projection = projection;
            camera.fit_aspect(Vec3::splat(-500.0), Vec3::splat(500.0), 1.5);
            let radius = camera.scene_radius;
            let (min, max) = (Vec3::new(10.0, 10.0, -1.0), Vec3::new(12.0, 11.0, 0.0));
            camera.zoom_to_selection(min, max, 1.5);
            assert_inside_ndc(&camera, min, max, 1.5);
            assert!(camera.distance < 50.0, "{camera:?}");
            assert_eq!(camera.scene_radius, radius);
            let before = camera;
            camera.zoom_to_selection(Vec3::ONE, Vec3::ZERO, 1.5);
            camera.zoom_to_selection(Vec3::NAN, Vec3::ONE, 1.5);
            assert_eq!(camera, before);
            if projection == Projection::Orthographic {
                // The far corner of the whole scene is still inside the depth range.
                let vp = camera.view_proj(1.5);
                for p in [Vec3::splat(-500.0), Vec3::splat(500.0)] {
                    let z = vp.project_point3(p).z;
                    assert!((0.0..=1.0).contains(&z), "{p} depth {z}");
                }
            }
        }
    }

    #[test]
    fn fit_uses_the_space() {
        // A fitted box should fill a good part of the view, not be a speck.
        let (min, max) = (Vec3::ZERO, Vec3::new(100.0, 50.0, 0.0));
        let mut camera = OrbitCamera::new(StandardView::Top);
        camera.fit_aspect(min, max, 2.0);
        let vp = camera.view_proj(2.0);
        let extent = corners(min, max)
            .map(|p| vp.project_point3(p).x.abs())
            .fold(0.0f32, f32::max);
        assert!(extent > 0.8, "box only spans {extent} of the half-width");
    }

    #[test]
    fn degenerate_boxes_never_nan() {
        let cases = [
            (Vec3::ZERO, Vec3::ZERO),
            (Vec3::splat(7.0), Vec3::splat(7.0)),
            (Vec3::ONE, Vec3::ZERO), // empty (min > max)
            (Vec3::splat(f32::NAN), Vec3::ONE),
            (Vec3::splat(f32::NEG_INFINITY), Vec3::splat(f32::INFINITY)),
        ];
        for (min, max) in cases {
            for view in VIEWS {
                for projection in PROJECTIONS {
                    let mut camera = OrbitCamera::new(view);
                    camera.projection = projection;
                    camera.fit_aspect(min, max, 1.0);
                    assert_finite(camera.view_proj(1.5));
                    assert!(camera.distance >= MIN_DISTANCE);
                    if min.is_finite() && max.is_finite() && min.cmple(max).all() {
                        assert_inside_ndc(&camera, min, max, 1.0);
                    }
                    camera.orbit(Vec2::new(13.0, -7.0));
                    camera.pan(Vec2::new(3.0, 4.0), Vec2::new(800.0, 600.0));
                    camera.zoom(1.5);
                    camera.zoom_at(0.5, Vec2::new(10.0, 10.0), Vec2::new(800.0, 600.0));
                    assert_finite(camera.view_proj(1.5));
                }
            }
        }
    }

    #[test]
    fn top_view_looks_down_negative_z() {
        let camera = OrbitCamera::new(StandardView::Top);
        assert!(camera.forward().abs_diff_eq(Vec3::NEG_Z, 1e-6));
        let vp = camera.view_proj(1.0);
        // +X is right and +Y is up on screen.
        let x = vp.project_point3(Vec3::X * 10.0);
        let y = vp.project_point3(Vec3::Y * 10.0);
        assert!(x.x > 0.0 && x.y.abs() < 1e-5);
        assert!(y.y > 0.0 && y.x.abs() < 1e-5);
        // Higher Z is nearer the eye, so smaller depth.
        let high = vp.project_point3(Vec3::Z * 5.0);
        let low = vp.project_point3(Vec3::Z * -5.0);
        assert!(high.z < low.z);
    }

    #[test]
    fn standard_views_put_z_up() {
        for view in [StandardView::Iso, StandardView::Front, StandardView::Right] {
            for projection in PROJECTIONS {
                let mut camera = OrbitCamera::new(view);
                camera.projection = projection;
                let vp = camera.view_proj(1.0);
                let z = vp.project_point3(Vec3::Z * 10.0);
                let o = vp.project_point3(Vec3::ZERO);
                assert!(z.y > o.y, "{view:?}: +Z not up on screen");
                assert!((z.x - o.x).abs() < 1e-5, "{view:?}: Z axis not vertical");
            }
        }
        let front = OrbitCamera::new(StandardView::Front);
        assert!(front.forward().abs_diff_eq(Vec3::Y, 1e-6));
        let right = OrbitCamera::new(StandardView::Right);
        assert!(right.forward().abs_diff_eq(Vec3::NEG_X, 1e-6));
        // Iso: X goes right-down, Y goes right-up.
        let iso = OrbitCamera::new(StandardView::Iso).view_proj(1.0);
        let o = iso.project_point3(Vec3::ZERO);
        let x = iso.project_point3(Vec3::X) - o;
        let y = iso.project_point3(Vec3::Y) - o;
        assert!(x.x > 0.0 && x.y < 0.0);
        assert!(y.x > 0.0 && y.y > 0.0);
    }

    #[test]
    fn pan_follows_the_cursor() {
        for view in VIEWS {
            for projection in PROJECTIONS {
                let mut camera = OrbitCamera::new(view);
                camera.projection = projection;
                let viewport = Vec2::new(800.0, 600.0);
                let aspect = viewport.x / viewport.y;
                let point = camera.target;
                let before = camera.view_proj(aspect).project_point3(point);
                let delta = Vec2::new(40.0, -25.0);
                camera.pan(delta, viewport);
                let after = camera.view_proj(aspect).project_point3(point);
                // NDC spans 2 units over the viewport; screen y is down, NDC y is up.
                let moved_px = Vec2::new(
                    (after.x - before.x) * viewport.x / 2.0,
                    -(after.y - before.y) * viewport.y / 2.0,
                );
                assert!(
                    moved_px.abs_diff_eq(delta, 1e-2),
                    "{view:?} {projection:?}: moved {moved_px}, want {delta}"
                );
            }
        }
    }

    #[test]
    fn zoom_is_clamped_and_monotonic() {
        let mut camera = OrbitCamera::default();
        let d0 = camera.distance;
        camera.zoom(2.0);
        assert!((camera.distance - d0 / 2.0).abs() < 1e-3);
        camera.zoom(0.5);
        assert!((camera.distance - d0).abs() < 1e-3);
        for _ in 0..200 {
            camera.zoom(10.0);
        }
        assert_eq!(camera.distance, MIN_DISTANCE);
        assert_finite(camera.view_proj(1.0));
        for _ in 0..200 {
            camera.zoom(0.1);
        }
        assert_eq!(camera.distance, MAX_DISTANCE);
        assert_finite(camera.view_proj(1.0));
        for bad in [0.0, -1.0, f32::NAN, f32::INFINITY] {
            camera.zoom(bad);
            assert_eq!(camera.distance, MAX_DISTANCE);
        }
    }

    #[test]
    fn zoom_at_keeps_the_cursor_point_fixed() {
        for projection in PROJECTIONS {
            let mut camera = OrbitCamera::new(StandardView::Iso);
            camera.projection = projection;
            let viewport = Vec2::new(640.0, 480.0);
            let cursor = Vec2::new(500.0, 100.0);
            let upp = camera.units_per_px(viewport.y);
            let (right, up, _) = camera.basis();
            let from_center = cursor - viewport * 0.5;
            let point = camera.target + right * from_center.x * upp - up * from_center.y * upp;
            let aspect = viewport.x / viewport.y;
            let before = camera.view_proj(aspect).project_point3(point);
            camera.zoom_at(3.0, cursor, viewport);
            let after = camera.view_proj(aspect).project_point3(point);
            assert!(before.truncate().abs_diff_eq(after.truncate(), 1e-4));
        }
    }

    #[test]
    fn orbit_clamps_pitch() {
        let mut camera = OrbitCamera::default();
        camera.orbit(Vec2::new(0.0, 1.0e6));
        assert!((camera.pitch - std::f32::consts::FRAC_PI_2).abs() < 1e-6);
        assert_finite(camera.view_proj(1.0));
        camera.orbit(Vec2::new(123.0, -1.0e6));
        assert!((camera.pitch + std::f32::consts::FRAC_PI_2).abs() < 1e-6);
        assert_finite(camera.view_proj(1.0));
        let before = camera;
        camera.orbit(Vec2::new(f32::NAN, 1.0));
        assert_eq!(camera, before);
        // Dragging right spins the camera clockwise seen from above (yaw decreases).
        let mut camera = OrbitCamera::new(StandardView::Front);
        let yaw = camera.yaw;
        camera.orbit(Vec2::new(10.0, 0.0));
        let turned = (camera.yaw - yaw).rem_euclid(std::f32::consts::TAU);
        assert!((turned - (std::f32::consts::TAU - 0.1)).abs() < 1e-4);
    }

    #[test]
    fn garbage_fields_never_nan() {
        let camera = OrbitCamera {
            target: Vec3::splat(f32::NAN),
            distance: f32::NAN,
            yaw: f32::INFINITY,
            pitch: f32::NAN,
            projection: Projection::Perspective,
            fov_y: -3.0,
            scene_radius: f32::NAN,
        };
        assert_finite(camera.view_proj(f32::NAN));
        let ortho = OrbitCamera {
            projection: Projection::Orthographic,
            ..camera
        };
        assert_finite(ortho.view_proj(0.0));
    }
}
