//! A toolpath as the backplot draws it: the path with its kinds of move, and the reference
//! marks beside it (hole rings, pecks, the programmed contour, program zeros, G22 zones, the
//! travel box). The app's view and `swarf render` both draw this, so they show the same.

use std::sync::Arc;

use glam::{DVec3, Vec3};
use swarf_toolpath::{CycleMove, SegmentKind, Toolpath, box_edges};

use crate::grid::{AXES, grid_points_at};
use crate::path::{Kind, PathPoint};

/// What is drawn of a toolpath, in f32 relative to `origin` (the centre of its bounds). Its
/// serialized form leaves out the points and marks, which a web worker sends beside it.
#[derive(Clone, Debug, Default, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Drawing {
    /// The start point (pen up), then one point per segment end with the segment's kind and
    /// its tool's number in order of first use as colour index.
    /// Shared: the analysis keeps them to simplify for the view (see [`crate::simplify`]).
    #[serde(skip)]
    pub points: Arc<Vec<PathPoint>>,
    /// Reference marks drawn with the grid (not picked, not played back); pen-up points
    /// separate them.
    #[serde(skip)]
    pub marks: Vec<PathPoint>,
    /// Bounds of the path, `None` when it has no segment.
    pub bounds: Option<(Vec3, Vec3)>,
    /// Where machine zero lies in the drawing's frame (the grid and axes are drawn there).
    pub zero: Vec3,
    /// Machine coordinates (mm) of the drawing's origin.
    pub origin: DVec3,
}

impl Drawing {
    /// The drawing of `path`, with the machine's travel box `travel` (machine mm, from the
    /// setup) outlined. A path without segments draws only the travel box.
    #[must_use]
    pub fn of(path: &Toolpath, travel: Option<[[f64; 3]; 2]>) -> Self {
        let origin = path.bounds().map_or(DVec3::ZERO, |b| b.center());
        let rel = |p: DVec3| (p - origin).as_vec3();
        let travel = travel.map_or_else(Vec::new, |[lo, hi]| {
            let edges = box_edges(DVec3::from_array(lo), DVec3::from_array(hi));
            edge_marks(&edges, rel, Kind::Boundary)
        });
        let Some(bounds) = path.bounds() else {
            return Self {
                marks: travel,
                ..Self::default()
            };
        };
        let mut points = Vec::with_capacity(path.len() + 1);
        points.push(PathPoint::pen_up(rel(path.start())));
        let tools = path.tools();
        points.extend(
            path.ends()
                .iter()
                .zip(path.kinds())
                .zip(path.segment_tools())
                .map(|((end, kind), tool)| {
                    let kind = match kind {
                        SegmentKind::Rapid => Kind::Rapid,
                        SegmentKind::Feed => Kind::Feed,
                        SegmentKind::Arc => Kind::Arc,
                    };
                    let index = tools.iter().position(|t| *t == tool).unwrap_or(0);
                    PathPoint::new(rel(*end), kind)
                        .with_color_index(u16::try_from(index).unwrap_or(u16::MAX))
                }),
        );
        let cycle_moves = path.cycle_moves();
        for &(segment, role) in &cycle_moves {
            if let Some(p) = points.get_mut(segment + 1) {
                let kind = match role {
                    CycleMove::Plunge => Kind::Plunge,
                    CycleMove::Retract => Kind::Retract,
                    CycleMove::Other => Kind::Cycle,
                };
                *p = PathPoint::new(p.position(), kind).with_color_index(p.color_index());
            }
        }
        mark_compensated(path, &mut points);
        let diagonal = (bounds.max - bounds.min).length();
        let pecks = peck_marks(path, &cycle_moves, rel, diagonal);
        drop(cycle_moves);
        let zones = path.zone_boxes().into_iter();
        let zones = zones.flat_map(|(min, max)| edge_marks(&box_edges(min, max), rel, Kind::Zone));
        // Put together once, at their length: the parts of a large path's marks are large.
        let marks = [
            hole_marks(path, rel, diagonal),
            pecks,
            programmed_marks(path, rel),
            origin_marks(path, rel, diagonal),
            zones.collect(),
            travel,
        ]
        .concat();
        Self {
            points: Arc::new(points),
            marks,
            bounds: Some((rel(bounds.min), rel(bounds.max))),
            zero: rel(DVec3::ZERO),
            origin,
        }
    }
}

/// The box that framing a view shows: the path's `bounds` and the `marks` drawn with it, but
/// not the travel box; `None` when there is nothing.
#[must_use]
pub fn view_bounds(bounds: Option<(Vec3, Vec3)>, marks: &[PathPoint]) -> Option<(Vec3, Vec3)> {
    let (mut min, mut max) = bounds.unwrap_or((Vec3::INFINITY, Vec3::NEG_INFINITY));
    for (i, p) in marks.iter().enumerate() {
        // A pen-up point starts the segment after it, and is of that segment's kind.
        let next = (marks.get(i + 1)).filter(|next| !next.is_pen_up());
        let kind = if p.is_pen_up() {
            next.and_then(PathPoint::kind)
        } else {
            p.kind()
        };
        let v = p.position();
        if kind.is_some_and(|k| k != Kind::Boundary) && v.is_finite() {
            min = min.min(v);
            max = max.max(v);
        }
    }
    (min.is_finite() && max.is_finite()).then_some((min, max))
}

/// What is drawn beside the path: the grid and axes at machine zero `zero` covering the path's
/// `bounds`, then the `marks`.
#[must_use]
pub fn reference_points(
    zero: Vec3,
    bounds: Option<(Vec3, Vec3)>,
    marks: &[PathPoint],
) -> Vec<PathPoint> {
    let (min, max) = bounds.unwrap_or((Vec3::ONE, Vec3::ZERO));
    [&grid_points_at(zero, min, max), marks].concat()
}

/// Line segments (machine coordinates) as `kind` marks.
fn edge_marks(edges: &[(DVec3, DVec3)], rel: impl Fn(DVec3) -> Vec3, kind: Kind) -> Vec<PathPoint> {
    edges
        .iter()
        .flat_map(|&(a, b)| [PathPoint::pen_up(rel(a)), PathPoint::new(rel(b), kind)])
        .collect()
}

/// An X/Y/Z axis cross at every program zero the moves were programmed from (G54…, with
/// G52/G92 shifts), 1/20 of the path's diagonal long (2 to 50 mm).
fn origin_marks(path: &Toolpath, rel: impl Fn(DVec3) -> Vec3, diagonal: f64) -> Vec<PathPoint> {
    let length = (diagonal / 20.0).clamp(2.0, 50.0);
    let mut marks = Vec::with_capacity(path.origins().len() * 6);
    for &at in path.origins() {
        for (axis, kind) in AXES {
            marks.push(PathPoint::pen_up(rel(at)));
            marks.push(PathPoint::new(rel(at + axis.as_dvec3() * length), kind));
        }
    }
    marks
}

/// The most holes ringed and pecks crossed; past them a hole is a dot and a peck unmarked, so
/// millions of holes (a runaway loop) draw a bounded number of marks.
const MAX_MARKED: usize = 100_000;

/// A ring at the top of every hole (of the first [`MAX_MARKED`]; a dot past them), across the
/// hole's axis, sized to the path (1/150 of its diagonal, 0.5 to 5 mm), so holes stand out
/// where plunges are seen end-on (a top view).
fn hole_marks(path: &Toolpath, rel: impl Fn(DVec3) -> Vec3, diagonal: f64) -> Vec<PathPoint> {
    const SIDES: usize = 12;
    let radius = (diagonal / 150.0).clamp(0.5, 5.0);
    let holes = path.holes();
    let (ringed, dotted) = holes.split_at(holes.len().min(MAX_MARKED));
    let mut marks = Vec::with_capacity(ringed.len() * (SIDES + 1) + dotted.len() * 2);
    for hole in ringed {
        let axis = (hole.bottom - hole.top).normalize_or(DVec3::NEG_Z);
        let u = axis.any_orthonormal_vector();
        let v = axis.cross(u);
        let ring = |k: usize| {
            let a = std::f64::consts::TAU * k as f64 / SIDES as f64;
            rel(hole.top + (u * a.cos() + v * a.sin()) * radius)
        };
        marks.push(PathPoint::pen_up(ring(0)));
        marks.extend((1..=SIDES).map(|k| PathPoint::new(ring(k), Kind::Cycle)));
    }
    for hole in dotted {
        let top = rel(hole.top);
        marks.extend([PathPoint::pen_up(top), PathPoint::new(top, Kind::Cycle)]);
    }
    marks
}

/// A small cross at the bottom of every peck (of the first [`MAX_MARKED`]) of a hole drilled in
/// several plunges (G83, G73), which would otherwise merge into one line.
fn peck_marks(
    path: &Toolpath,
    cycle_moves: &[(usize, CycleMove)],
    rel: impl Fn(DVec3) -> Vec3,
    diagonal: f64,
) -> Vec<PathPoint> {
    let half = (diagonal / 150.0).clamp(0.5, 5.0) * 0.6;
    let plunges: Vec<(usize, usize)> = cycle_moves
        .iter()
        .filter(|(_, role)| *role == CycleMove::Plunge)
        .filter_map(|&(segment, _)| Some((path.hole_of_segment(segment)?, segment)))
        .collect();
    let mut marks = Vec::new();
    for group in plunges.chunk_by(|a, b| a.0 == b.0) {
        if group.len() < 2 {
            continue;
        }
        let Some(hole) = path.holes().get(group[0].0) else {
            continue;
        };
        let axis = (hole.bottom - hole.top).normalize_or(DVec3::NEG_Z);
        let u = axis.any_orthonormal_vector();
        let v = axis.cross(u);
        let left = MAX_MARKED.saturating_sub(marks.len() / 4);
        for &(_, segment) in group.iter().take(left) {
            let Some(&bottom) = path.ends().get(segment) else {
                continue;
            };
            for across in [u, v] {
                marks.push(PathPoint::pen_up(rel(bottom - across * half)));
                marks.push(PathPoint::new(rel(bottom + across * half), Kind::Plunge));
            }
        }
    }
    marks
}

/// The segments of blocks cut under cutter radius compensation are the tool centre's path:
/// they are drawn as compensated (the programmed contour goes beside them as a mark).
fn mark_compensated(path: &Toolpath, points: &mut [PathPoint]) {
    if path.programmed().is_empty() {
        return;
    }
    let lines: std::collections::HashSet<u32> = path.programmed().iter().map(|(l, _)| *l).collect();
    let blocks = path.lines().iter().zip(path.kinds());
    for (point, (line, kind)) in points.iter_mut().skip(1).zip(blocks) {
        if lines.contains(line) && *kind != SegmentKind::Rapid {
            *point = PathPoint::new(point.position(), Kind::Compensated)
                .with_color_index(point.color_index());
        }
    }
}

/// The programmed contour of the compensated blocks (the part as drawn, beside the tool centre's
/// path), as marks: each move from the end of the one before, arcs as chords.
fn programmed_marks(path: &Toolpath, rel: impl Fn(DVec3) -> Vec3) -> Vec<PathPoint> {
    let mut marks = Vec::new();
    let mut last: Option<(u32, DVec3)> = None;
    for (line, event) in path.programmed() {
        let Some(end) = event.end_point() else {
            continue;
        };
        // A move right after the one before continues it; otherwise the contour starts here.
        let from = last.filter(|(l, _)| *l <= *line).map(|(_, p)| p);
        match (from, event) {
            (None, _) => marks.push(PathPoint::pen_up(rel(end))),
            (Some(from), swarf_interp::Canon::Arc(arc)) => {
                for p in swarf_toolpath::tessellate_arc(from, arc) {
                    marks.push(PathPoint::new(rel(p), Kind::Programmed));
                }
            }
            (Some(_), _) => marks.push(PathPoint::new(rel(end), Kind::Programmed)),
        }
        last = Some((*line, end));
    }
    marks
}
