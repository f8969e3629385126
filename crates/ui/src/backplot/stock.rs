//! The cut stock in the view: which cut to ask the analysis for, where the pointer meets the
//! stock's surface, and the rapids into it marked over the view.

use std::sync::Arc;

use glam::{DVec3, Vec3};
use swarf_analysis::{Request, StockCut, StockField};
use swarf_render::Kind;

use super::{Backplot, Scene};

/// Colour of the marks of rapids into the stock.
pub const RAPID_INTO_STOCK_COLOR: egui::Color32 = egui::Color32::from_rgb(240, 40, 40);

/// Rapids into the stock marked at most (each a line and a dot painted over the view).
const MAX_RAPID_MARKS: usize = 1000;

/// Most samples along the pointer's ray looking for the stock's surface.
const MAX_RAY_SAMPLES: f64 = 8192.0;

impl Backplot {
    /// Where the view's Stock button was drawn at the last frame.
    pub fn stock_button_rect(&self) -> Option<egui::Rect> {
        self.stock_button
    }

    /// The cut of the stock to ask the analysis for after [`Self::show`], while it is drawn: the
    /// whole toolpath's, or up to playback's position. A later position waits for the answer
    /// to the cut asked; an earlier one or a new analysis does not.
    pub fn stock_request(&mut self, scene: &Scene) -> Option<Request> {
        if !self.stock_on {
            self.stock_asked = None;
            return None;
        }
        let upto = self.playback.executed(scene);
        let upto = upto.unwrap_or_else(|| scene.segment_count());
        let generation = scene.generation;
        let want = (generation, upto);
        let cut = scene.stock.as_ref();
        let answered = |asked| cut.is_some_and(|c| (c.generation, c.upto) == asked);
        let waits = |asked: (u64, usize)| {
            asked == want || (asked.0 == want.0 && asked.1 < want.1 && !answered(asked))
        };
        if answered(want) || self.stock_asked.is_some_and(waits) {
            return None;
        }
        self.stock_asked = Some(want);
        Some(Request::Stock { generation, upto })
    }

    /// Kinds not drawn: those hidden, and every move when the stock is drawn alone.
    pub(super) fn hidden(&self) -> u32 {
        let alone = self.stock_on && self.stock_alone;
        let hide = Kind::ALL.iter().filter(|k| alone && k.is_motion());
        hide.fold(self.hidden_kinds, |m, k| m | k.mask())
    }

    /// The stock to draw: the scene's cut, or until it comes the last one; `None` when off.
    pub(super) fn drawn_stock(&mut self, scene: &Scene) -> Option<Arc<StockCut>> {
        if let Some(cut) = &scene.stock
            && (cut.field.is_some() || cut.error.is_some())
        {
            self.shown_stock = Some(Arc::clone(cut));
        }
        self.stock_on.then(|| self.shown_stock.clone()).flatten()
    }

    /// The heights of the cut drawn, while the stock is drawn.
    pub(super) fn shown_field(&self) -> Option<&StockField> {
        let cut = self.shown_stock.as_ref().filter(|_| self.stock_on)?;
        cut.field.as_ref()
    }

    /// Where the ray under `pointer` first meets the drawn stock's surface, machine mm.
    pub(super) fn stock_point(
        &self,
        scene: &Scene,
        rect: egui::Rect,
        pointer: egui::Pos2,
    ) -> Option<DVec3> {
        let field = self.shown_field()?;
        let aspect = rect.width() / rect.height();
        let inverse = self.camera.view_proj(aspect).inverse();
        let x = (pointer.x - rect.min.x) / rect.width() * 2.0 - 1.0;
        let y = 1.0 - (pointer.y - rect.min.y) / rect.height() * 2.0;
        let at = |depth| scene.origin + inverse.project_point3(Vec3::new(x, y, depth)).as_dvec3();
        surface_hit(field, at(0.0), at(0.5))
    }

    /// Each rapid into the stock the cut found, in their colour, a dot where it meets material.
    pub(super) fn paint_rapids_into_stock(&self, ui: &egui::Ui, rect: egui::Rect, scene: &Scene) {
        let Some(cut) = scene.stock.as_ref().filter(|_| self.stock_on) else {
            return;
        };
        let painter = ui.painter_at(rect);
        let stroke = egui::Stroke::new(2.5, RAPID_INTO_STOCK_COLOR);
        for &(segment, [x, y]) in cut.rapids.iter().take(MAX_RAPID_MARKS) {
            let (Some(a), Some(b)) = (scene.points.get(segment), scene.points.get(segment + 1))
            else {
                continue;
            };
            let (a, b) = (a.position(), b.position());
            if let (Some(p), Some(q)) = (self.screen_pos(a), self.screen_pos(b)) {
                painter.line_segment([p, q], stroke);
            }
            // The point of the move over where it meets material.
            let at = (DVec3::new(x, y, 0.0) - scene.origin).as_vec3();
            let along = (b - a).truncate();
            let t = if along.length_squared() > 0.0 {
                ((at - a).truncate().dot(along) / along.length_squared()).clamp(0.0, 1.0)
            } else {
                1.0
            };
            if let Some(p) = self.screen_pos(a.lerp(b, t)) {
                painter.circle_filled(p, 4.0, RAPID_INTO_STOCK_COLOR);
            }
        }
    }
}

/// The box of the stock `field` covers, its lowest and highest corners (machine mm).
pub(super) fn stock_box(field: &StockField) -> (DVec3, DVec3) {
    let (nx, ny) = field.size;
    let far = DVec3::new(nx as f64, ny as f64, 0.0) * field.cell_mm;
    (field.min, (field.min + far).with_z(field.top))
}

/// The first point of the line from `a` through `b` (machine mm, from `a` on) at or below
/// `field`'s surface, on its surface.
fn surface_hit(field: &StockField, a: DVec3, b: DVec3) -> Option<DVec3> {
    let (lo, hi) = stock_box(field);
    // Where the line is inside the stock's box (slabs).
    let d = b - a;
    let (mut t0, mut t1) = (0.0f64, f64::INFINITY);
    for axis in 0..3 {
        let (o, v) = (a[axis], d[axis]);
        if v.abs() < 1e-12 {
            if o < lo[axis] || o > hi[axis] {
                return None;
            }
            continue;
        }
        let (p, q) = ((lo[axis] - o) / v, (hi[axis] - o) / v);
        t0 = t0.max(p.min(q));
        t1 = t1.min(p.max(q));
    }
    if !(t0 <= t1 && t1.is_finite()) {
        return None;
    }
    let below = |t: f64| {
        let p = a + d * t;
        field.height_at(p.x, p.y).is_some_and(|h| p.z <= h)
    };
    // Half a cell apart across the grid, then bisection between the last above and first below.
    let across = (d.truncate() * (t1 - t0)).length() / (field.cell_mm * 0.5);
    let samples = across.ceil().clamp(1.0, MAX_RAY_SAMPLES) as usize;
    let mut above = t0;
    for k in 0..=samples {
        let t = t0 + (t1 - t0) * k as f64 / samples as f64;
        if !below(t) {
            above = t;
            continue;
        }
        let mut hit = t;
        if k > 0 {
            for _ in 0..32 {
                let mid = f64::midpoint(above, hit);
                *if below(mid) { &mut hit } else { &mut above } = mid;
            }
        }
        let p = a + d * hit;
        return Some(DVec3::new(p.x, p.y, field.height_at(p.x, p.y)?));
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;

    /// 10 × 10 cells of 1 mm from (0, 0), top at 0, bottom at −10, with a 4 mm deep pocket
    /// over X 4..6.
    fn field() -> StockField {
        let mut heights = vec![0.0f32; 100];
        for j in 0..10 {
            for i in 4..6 {
                heights[j * 10 + i] = -4.0;
            }
        }
        StockField {
            heights,
            size: (10, 10),
            cell_mm: 1.0,
            min: DVec3::new(0.0, 0.0, -10.0),
            top: 0.0,
        }
    }

    #[test]
    fn a_ray_meets_the_top_or_the_pocket_floor_or_misses() {
        let field = field();
        let down = |x: f64| surface_hit(&field, DVec3::new(x, 5.0, 50.0), DVec3::new(x, 5.0, 0.0));
        assert_eq!(down(2.5), Some(DVec3::new(2.5, 5.0, 0.0)));
        assert_eq!(down(4.5), Some(DVec3::new(4.5, 5.0, -4.0)));
        assert_eq!(down(20.0), None);
        // Slanting down across the pocket, from above X 0: it meets the far wall's top edge
        // region or the floor, never a point above the surface.
        let hit = surface_hit(&field, DVec3::new(0.0, 5.0, 3.0), DVec3::new(1.0, 5.0, 2.0));
        let hit = hit.unwrap_or_default();
        assert!((hit.x - 3.0).abs() < 1e-6 && hit.z == 0.0, "{hit}");
        let steep = surface_hit(&field, DVec3::new(4.2, 5.0, 1.0), DVec3::new(4.3, 5.0, 0.0));
        let steep = steep.unwrap_or_default();
        assert!(steep.z == -4.0 && (4.0..6.0).contains(&steep.x), "{steep}");
        // Pointing away from the stock.
        assert_eq!(
            surface_hit(&field, DVec3::new(5.0, 5.0, 5.0), DVec3::new(5.0, 5.0, 6.0)),
            None
        );
    }
}
