//! The height field and the sweep of a tool along one straight segment.
//!
//! Over a cell's centre, at perpendicular distance `h` from the segment's line in XY and at
//! `sc` along it, the tool's tip at `u` along the segment (its tip height `z0 + m·u`) leaves
//! its end at `z0 + m·u + lift(r)`, where `r² = h² + (u − sc)²`. The tool covers the cell for `u`
//! in `[max(0, sc − w), min(len, sc + w)]` with `w = √(R² − h²)`. Every profile's lift is
//! convex and non-decreasing in `r`, so the end's height is convex in `u`: its minimum has a
//! closed form for flat, ball and cone ends, and is found by a bisection for a bull nose.
//!
//! In a chain of moves of one tool, a cell over which a move's tool is lowest at one of the
//! move's ends is left to the neighbour that shares that end, which comes at least as low
//! there: so a move of a chain cuts little more than the band it sweeps, not the discs of the
//! tool at its ends ([`Cut::join`] shares the cells out).

use glam::DVec3;

use crate::{Shape, Stock, StockError, Tool};

/// How far (mm) a rapid's tool may come below the material at a cell before it counts as
/// meeting it: room for the rounding of the stored heights, so a rapid along a surface the
/// same tool has just cut is not taken for a collision.
pub(crate) const CONTACT_MM: f32 = 0.001;

/// A straight XY move shorter than this (mm) is taken as purely vertical.
const VERTICAL_MM: f64 = 1e-4;

/// How far (mm) a cut reaches past the cells its neighbours leave it, so that rounding never
/// leaves a cell to neither.
const MARGIN: f64 = 1e-5;

/// How far (mm) the height a bull nose's search settles on may lie above the lowest point over a
/// cell in front of or behind the tool (over one beside it, that over the cosine of its angle
/// off the move).
const BULL_MM: f64 = 1e-5;

/// Cells of a bull nose searched at once: enough vectors for the search to keep several in
/// flight.
const GROUP: usize = 16;

/// Cells of a run worked at once: a vector's worth, as most runs are short.
const RUN: usize = 4;

/// Radii at which a bull nose's reach past the ends of a move is sampled.
const TAPER: usize = 6;

/// The stock as a Z-map: one height per cell of a square grid over its XY extent.
#[derive(Debug, Clone)]
pub struct HeightField {
    stock: Stock,
    cell: f64,
    nx: usize,
    ny: usize,
    heights: Vec<f32>,
}

/// A check made while cutting.
#[derive(Debug, Clone, Copy)]
pub(crate) enum Check {
    /// A rapid: the first cell along the move where the tool meets material.
    Rapid,
    /// A feed: the cell where material stands highest above the tip, when higher than the
    /// flute length (mm).
    Shank(f32),
}

/// Where a check found a problem.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Hit {
    /// The cell's index in [`HeightField::heights`].
    pub index: usize,
    /// How deep the tool went into material there (mm): below the material's top for a rapid,
    /// the tip below it for a shank cut.
    pub depth: f32,
}

/// One straight move in the grid's frame (XY from the grid's lowest corner) with its tool's
/// end, and which of the cells it covers it cuts.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Cut {
    /// XY start (a vertical move's lower end).
    a: [f64; 2],
    /// Unit XY direction ((1, 0) for a vertical move).
    e: [f64; 2],
    /// XY length (0 for a vertical move).
    len: f64,
    /// Tip height at the start (the lower end for a vertical move).
    z0: f32,
    /// Tip rise per millimetre along XY.
    m: f32,
    /// The tool's radius.
    r: f32,
    /// A vertical move downwards.
    down: bool,
    profile: AnyProfile,
    reach: Reach,
    /// A checked move leaves no cell to the next one, nor is left any: what it checks is the
    /// material as the moves before it left it.
    checked: bool,
    /// How far behind its start and past its end (mm along it) it cuts.
    behind: f64,
    ahead: f64,
    /// A disc (centre, radius) about one of its ends whose cells a neighbour cuts.
    hole: Option<([f64; 2], f64)>,
    /// Of the cells behind its start (`[0]`) or past its end (`[1]`), it cuts those further
    /// than `wedge` past the line across that end only within [`Cut::keep`] of the end: the
    /// others are lowest at that end, where the neighbour there (which cut them) comes as low.
    wedge: [f64; 2],
    /// Within this of the start (or end), it cuts every cell: the neighbour's hole there.
    disc: [f64; 2],
    /// For a bull nose, `(r, β(r))` at radii from past `ρ` (see [`Reach::of`]) to the tool's
    /// radius: over a cell `r` from an end and at least `β(r)` past the line across it, the
    /// tool is lowest at that end.
    taper: Option<[(f64, f64); TAPER]>,
}

/// Where a move's tool comes lowest over the cells about its ends (mm).
#[derive(Debug, Clone, Copy)]
struct Reach {
    /// Over the cells further than `back` behind its start, the tool is lowest at the start;
    /// over those further than `front` past its end, at the end.
    back: f64,
    front: f64,
    /// Over the cells within `start` of its start, the tool is lowest at the start; within
    /// `end` of its end, at the end.
    start: f64,
    end: f64,
}

/// What the sweep knows of one cell the tool covers.
#[derive(Debug, Clone, Copy)]
struct Cell {
    /// Along-coordinate of the centre, its squared distance from the line, and the half-width
    /// of the tool's chord through it.
    sc: f32,
    hh: f32,
    w: f32,
    /// The range of `u` over which the tool covers the centre.
    lo: f32,
    hi: f32,
    /// Where the tool's end is lowest over the centre, and that height.
    u: f32,
    low: f32,
}

/// [`Cell`]s of a group of `N`, field by field.
#[derive(Debug, Clone, Copy)]
struct Group<const N: usize> {
    sc: [f32; N],
    hh: [f32; N],
    w: [f32; N],
    lo: [f32; N],
    hi: [f32; N],
    u: [f32; N],
    low: [f32; N],
}

impl<const N: usize> Group<N> {
    /// The `l`-th cell.
    #[inline(always)]
    fn get(&self, l: usize) -> Cell {
        Cell {
            sc: self.sc[l],
            hh: self.hh[l],
            w: self.w[l],
            lo: self.lo[l],
            hi: self.hi[l],
            u: self.u[l],
            low: self.low[l],
        }
    }
}

/// Cells of a cut gathered to be searched: `n` of them, by their index in the heights, the
/// along-coordinate of the centre and its squared offset from the line.
#[derive(Clone, Copy, Default)]
struct Batch {
    index: [usize; GROUP],
    sc: [f32; GROUP],
    hh: [f32; GROUP],
    n: usize,
}

impl Batch {
    /// Adds a cell; true once the batch is full.
    fn push(&mut self, index: usize, sc: f32, hh: f32) -> bool {
        if let (Some(i), Some(s), Some(h)) = (
            self.index.get_mut(self.n),
            self.sc.get_mut(self.n),
            self.hh.get_mut(self.n),
        ) {
            (*i, *s, *h) = (index, sc, hh);
            self.n += 1;
        }
        self.n == GROUP
    }
}

/// Any of the profiles, chosen once a segment.
#[derive(Debug, Clone, Copy)]
enum AnyProfile {
    Flat(Flat),
    Ball(Ball),
    Cone(Cone),
    Bull(Bull),
}

/// Evaluates `$body` with `$p` bound to the concrete profile inside `$profile`, so each
/// sweep is compiled for one profile.
macro_rules! each_profile {
    ($profile:expr, $p:ident => $body:expr) => {
        match $profile {
            AnyProfile::Flat($p) => $body,
            AnyProfile::Ball($p) => $body,
            AnyProfile::Cone($p) => $body,
            AnyProfile::Bull($p) => $body,
        }
    };
}

/// A tool's end, with the constants of one segment's slope.
trait Profile: Copy {
    /// For each cell of a group, the `u` in `[lo, hi]` where the end is lowest over it.
    fn lowest<const N: usize>(self, g: &Group<N>) -> [f32; N];
    /// [`Profile::lowest`] for the cells where it comes without a search, and for each cell
    /// whether it did (no: it needs the search).
    #[inline(always)]
    fn settled<const N: usize>(self, g: &Group<N>) -> ([f32; N], [bool; N]) {
        (self.lowest(g), [true; N])
    }
    /// Height of the end above the tip at `r² = hh + s²` (within the radius, `w² = R² − hh`).
    fn lift(self, hh: f32, s: f32, w: f32) -> f32;
}

#[derive(Debug, Clone, Copy)]
struct Flat {
    /// The move climbs, so the tip is lowest where it first covers a cell.
    up: bool,
}

impl Profile for Flat {
    #[inline(always)]
    fn lowest<const N: usize>(self, g: &Group<N>) -> [f32; N] {
        if self.up { g.lo } else { g.hi }
    }
    #[inline(always)]
    fn lift(self, _: f32, _: f32, _: f32) -> f32 {
        0.0
    }
}

#[derive(Debug, Clone, Copy)]
struct Ball {
    r: f32,
    /// `−m / √(1 + m²)`: the lowest point's offset along the move over `w`.
    c: f32,
}

impl Profile for Ball {
    #[inline(always)]
    fn lowest<const N: usize>(self, g: &Group<N>) -> [f32; N] {
        std::array::from_fn(|l| clamp(g.sc[l] + self.c * g.w[l], g.lo[l], g.hi[l]))
    }
    #[inline(always)]
    fn lift(self, _: f32, s: f32, w: f32) -> f32 {
        self.r - at_least(w * w - s * s, 0.0).sqrt()
    }
}

#[derive(Debug, Clone, Copy)]
struct Cone {
    /// Rise per millimetre of radius: `1 / tan(half the point angle)`.
    k: f32,
    /// `−m / √(k² − m²)`: the lowest point's offset along the move over `h`, when the move is
    /// shallower than the cone.
    c: f32,
    /// The move is at least as steep as the cone: the lowest point is at an end of the range.
    steep: bool,
    up: bool,
}

impl Profile for Cone {
    #[inline(always)]
    fn lowest<const N: usize>(self, g: &Group<N>) -> [f32; N] {
        match (self.steep, self.up) {
            (true, true) => g.lo,
            (true, false) => g.hi,
            _ => {
                std::array::from_fn(|l| clamp(g.sc[l] + self.c * g.hh[l].sqrt(), g.lo[l], g.hi[l]))
            }
        }
    }
    #[inline(always)]
    fn lift(self, hh: f32, s: f32, _: f32) -> f32 {
        self.k * (hh + s * s).sqrt()
    }
}

#[derive(Debug, Clone, Copy)]
struct Bull {
    /// Radius of the flat centre and of the corner, and the inverse of the corner's.
    flat: f32,
    corner: f32,
    inv_corner: f32,
    /// The slope squared, and `−1` when the move climbs (`1` otherwise).
    m2: f32,
    dir: f32,
    /// Halvings of the search (none on a level move, where the closest point is lowest).
    steps: u32,
}

impl Bull {
    /// Whether the end still falls at `s = dir·(u − sc)` over a cell `hh` from the line (the move
    /// descending): if `s ≤ 0` or `t²·(s² + m²r²) < m²r²`, with `t = (r − flat) / corner` the sine
    /// of the corner's angle there (`tan φ · cos ψ < |m|` without divisions).
    #[inline(always)]
    fn falls(self, s: f32, hh: f32) -> bool {
        let r2 = hh + s * s;
        let t = at_least(r2.sqrt() - self.flat, 0.0) * self.inv_corner;
        (s <= 0.0) | (t * t * (s * s + self.m2 * r2) < self.m2 * r2)
    }

    /// Each cell's range of `s` (see [`Bull::falls`]).
    #[inline(always)]
    fn range<const N: usize>(self, g: &Group<N>, l: usize) -> (f32, f32) {
        let (x, y) = (
            self.dir * (g.lo[l] - g.sc[l]),
            self.dir * (g.hi[l] - g.sc[l]),
        );
        if self.dir > 0.0 { (x, y) } else { (y, x) }
    }
}

impl Profile for Bull {
    /// The end's height is convex in `u`: the search halves the range where it stops falling.
    #[inline(always)]
    fn lowest<const N: usize>(self, g: &Group<N>) -> [f32; N] {
        let (ends, settled) = self.settled(g);
        let mut below: [f32; N] = std::array::from_fn(|l| self.range(g, l).0);
        let mut half: [f32; N] = std::array::from_fn(|l| {
            let (a, b) = self.range(g, l);
            0.5 * (b - a)
        });
        for _ in 0..self.steps {
            for l in 0..N {
                let f = f32::from(u8::from(self.falls(below[l] + half[l], g.hh[l])));
                below[l] += half[l] * f;
                half[l] *= 0.5;
            }
        }
        std::array::from_fn(|l| {
            let u = g.sc[l] + self.dir * (below[l] + half[l]);
            if settled[l] {
                ends[l]
            } else {
                clamp(u, g.lo[l], g.hi[l])
            }
        })
    }
    /// The end is lowest at the start of a cell's range if it rises from there, at the end if
    /// it still falls there; on a level move, at the closest point.
    #[inline(always)]
    fn settled<const N: usize>(self, g: &Group<N>) -> ([f32; N], [bool; N]) {
        if self.steps == 0 {
            return (
                std::array::from_fn(|l| clamp(g.sc[l], g.lo[l], g.hi[l])),
                [true; N],
            );
        }
        let mut ends = [0.0; N];
        let mut settled = [false; N];
        for l in 0..N {
            let (a, b) = self.range(g, l);
            let (rises, falls) = (!self.falls(a, g.hh[l]), self.falls(b, g.hh[l]));
            let s = if rises { a } else { b };
            ends[l] = g.sc[l] + self.dir * s;
            settled[l] = rises | falls;
        }
        (ends, settled)
    }
    #[inline(always)]
    fn lift(self, hh: f32, s: f32, _: f32) -> f32 {
        let out = at_least((hh + s * s).sqrt() - self.flat, 0.0);
        self.corner - at_least(self.corner * self.corner - out * out, 0.0).sqrt()
    }
}

impl HeightField {
    /// Uncut stock: every cell at the stock's top.
    pub fn new(stock: &Stock) -> Result<Self, StockError> {
        let (cell, nx, ny) = stock.grid()?;
        Ok(HeightField {
            stock: *stock,
            cell,
            nx,
            ny,
            heights: vec![stock.max[2] as f32; nx * ny],
        })
    }

    /// The stock the field was made for.
    pub fn stock(&self) -> &Stock {
        &self.stock
    }

    /// Side of one cell, mm.
    pub fn cell_mm(&self) -> f64 {
        self.cell
    }

    /// Cells along X and along Y.
    pub fn size(&self) -> (usize, usize) {
        (self.nx, self.ny)
    }

    /// The height of each cell (machine Z, mm), row by row from the lowest Y: cell `(i, j)` is at
    /// index `j · nx + i` and centred on [`HeightField::cell_center`]`(i, j)`.
    pub fn heights(&self) -> &[f32] {
        &self.heights
    }

    /// The machine XY of the centre of cell `(i, j)`.
    pub fn cell_center(&self, i: usize, j: usize) -> [f64; 2] {
        [
            self.stock.min[0] + (i as f64 + 0.5) * self.cell,
            self.stock.min[1] + (j as f64 + 0.5) * self.cell,
        ]
    }

    /// The height of the cell under machine (`x`, `y`), if it lies on the grid.
    pub fn height_at(&self, x: f64, y: f64) -> Option<f64> {
        let i = (x - self.stock.min[0]) / self.cell;
        let j = (y - self.stock.min[1]) / self.cell;
        if !(0.0..self.nx as f64).contains(&i) || !(0.0..self.ny as f64).contains(&j) {
            return None;
        }
        let h = self.heights.get(j as usize * self.nx + i as usize)?;
        Some(f64::from(*h))
    }

    /// The material removed so far, mm³: each cell's depth below the stock's top times its
    /// area.
    pub fn removed_volume(&self) -> f64 {
        let top = f64::from(self.stock.max[2] as f32);
        let depth: f64 = self.heights.iter().map(|&h| top - f64::from(h)).sum();
        depth * self.cell * self.cell
    }

    /// Lowers every cell to the lowest point `tool`'s end reaches over it as its tip moves in a
    /// straight line from `from` to `to` (never below the stock's bottom).
    pub fn cut(&mut self, from: DVec3, to: DVec3, tool: &Tool) {
        if let Some(cut) = self.plan(from, to, tool, false, false) {
            self.apply(&cut, None);
        }
    }

    /// The move `from`..`to` (grid frame) with `tool`, cutting all it covers but, if it `continues`
    /// the tool's last cut, the start cells that cut left; `checked` if it will be checked. `None`
    /// for coordinates that are not numbers or a tool out of range.
    pub(crate) fn plan(
        &self,
        from: DVec3,
        to: DVec3,
        tool: &Tool,
        continues: bool,
        checked: bool,
    ) -> Option<Cut> {
        let origin = DVec3::new(self.stock.min[0], self.stock.min[1], 0.0);
        let (a, b) = (from - origin, to - origin);
        if !(a.is_finite() && b.is_finite() && tool.validate(0).is_ok()) {
            return None;
        }
        let d = b - a;
        let len = d.x.hypot(d.y);
        // A vertical move cuts as its tool at its lower end.
        let (start, e, len, m) = if len > VERTICAL_MM {
            (a, [d.x / len, d.y / len], len, (d.z / len) as f32)
        } else {
            (if b.z < a.z { b } else { a }, [1.0, 0.0], 0.0, 0.0)
        };
        let r = (tool.diameter / 2.0) as f32;
        let up = m > 0.0;
        let ball = Ball {
            r,
            c: -m / (1.0 + m * m).sqrt(),
        };
        let profile = match tool.shape {
            Shape::Flat => AnyProfile::Flat(Flat { up }),
            Shape::Ball => AnyProfile::Ball(ball),
            Shape::Bull { corner_radius } => {
                let corner = (corner_radius as f32).min(r);
                if corner <= 1e-6 {
                    AnyProfile::Flat(Flat { up })
                } else if corner >= r * (1.0 - 1e-6) {
                    AnyProfile::Ball(ball)
                } else {
                    // Halvings of the range the tool covers a cell over (at most the move or
                    // the diameter) down to `delta` either side of the lowest point, where the
                    // height's curvature along the move is at most `2·(1 + |m|)³ / corner`
                    // (over the cosine of the angle off the move).
                    let range = len.min(2.0 * f64::from(r));
                    let curve = (1.0 + f64::from(m.abs())).powi(3) / f64::from(corner);
                    let delta = (BULL_MM / curve).sqrt();
                    let steps = if m == 0.0 {
                        0
                    } else {
                        ((range / delta).log2().ceil() - 1.0).clamp(1.0, 30.0) as u32
                    };
                    AnyProfile::Bull(Bull {
                        flat: r - corner,
                        corner,
                        inv_corner: 1.0 / corner,
                        m2: m * m,
                        dir: if up { -1.0 } else { 1.0 },
                        steps,
                    })
                }
            }
            Shape::Drill { point_angle_deg } | Shape::Chamfer { point_angle_deg } => {
                let k = (1.0 / (point_angle_deg.to_radians() / 2.0).tan()) as f32;
                let steep = m.abs() >= k;
                let c = if steep {
                    0.0
                } else {
                    -m / (k * k - m * m).sqrt()
                };
                AnyProfile::Cone(Cone { k, c, steep, up })
            }
        };
        let reach = Reach::of(profile, f64::from(r), m, len, checked);
        // Past the radius `ρ` where the corner is as steep as the move, the corner under a
        // cell beyond an end rises away from it faster than the move falls unless the cell
        // lies less than `β(r) = |m|·r / tan φ` past the line across the end (`sin φ = (r −
        // flat) / corner`), which falls as `r` grows.
        let taper = match profile {
            AnyProfile::Bull(Bull { flat, corner, .. }) if m != 0.0 && !checked => {
                let (flat, corner, m) = (f64::from(flat), f64::from(corner), f64::from(m.abs()));
                let rho = flat + corner * m / (1.0 + m * m).sqrt();
                Some(std::array::from_fn(|k| {
                    let r = rho + (f64::from(r) - rho) * (k + 1) as f64 / TAPER as f64;
                    let d = r - flat;
                    (r, m * r * (corner * corner - d * d).max(0.0).sqrt() / d)
                }))
            }
            _ => None,
        };
        Some(Cut {
            a: [start.x, start.y],
            e,
            len,
            z0: start.z as f32,
            m,
            r,
            down: b.z < a.z,
            profile,
            reach,
            checked,
            // Until joined to its neighbours it leaves nothing past its end and, continuing the
            // last cut (which left it nothing), the cells about its start that the tool is
            // lowest over at the start.
            behind: if continues { reach.back } else { f64::INFINITY },
            ahead: f64::INFINITY,
            hole: (continues && reach.start > 0.0).then_some(([start.x, start.y], reach.start)),
            wedge: [if continues { 0.0 } else { f64::INFINITY }, f64::INFINITY],
            disc: [0.0; 2],
            taper,
        })
    }

    /// Makes `cut` (see [`HeightField::plan`]) and `check` on the material as it was.
    pub(crate) fn apply(&mut self, cut: &Cut, check: Option<Check>) -> Option<Hit> {
        each_profile!(cut.profile, p => self.sweep(cut, p, check))
    }

    /// The cut of [`HeightField::apply`] with one profile.
    fn sweep<P: Profile>(&mut self, cut: &Cut, profile: P, check: Option<Check>) -> Option<Hit> {
        let bottom = self.stock.min[2] as f32;
        let threshold = match check {
            None => f32::INFINITY,
            Some(Check::Rapid) => CONTACT_MM,
            Some(Check::Shank(flutes)) => flutes + CONTACT_MM,
        };
        // No cell at or below the tip's lowest point can be cut, nor pass the check unless
        // above it by the threshold.
        let lowest = at_least(cut.z0.min(cut.z0 + cut.m * cut.len as f32), bottom);
        let mut sweeper = Sweeper {
            sweep: Sweep::new(cut, profile),
            heights: &mut self.heights,
            check,
            bottom,
            threshold,
            clear: lowest + threshold,
            later: check.is_none().then(Batch::default),
            found: None,
        };
        // A level move of a flat end lowers everything it covers to its height.
        let fill = matches!(cut.profile, AnyProfile::Flat(_)) && cut.m == 0.0;
        cut.runs(
            self.cell,
            self.nx,
            self.ny,
            |start, step, n, [sc0, h0, dsc, dh]| {
                // Worked out in double precision so that a cell's are the same whatever run it
                // is in: whether the tool covers it never depends on how the cut is split up.
                let at = |k: usize| ((sc0 + k as f64 * dsc) as f32, (h0 + k as f64 * dh) as f32);
                let cells = (0..n).map(|k| {
                    let (sc, h) = at(k);
                    (start + k * step, sc, h)
                });
                let heights = &mut *sweeper.heights;
                let above = |level: f32| {
                    (cells.clone()).any(|(i, _, _)| heights.get(i).is_some_and(|&h| h > level))
                };
                if !above(lowest) {
                    return;
                }
                if fill && (check.is_none() || !above(sweeper.clear)) {
                    for (i, _, _) in cells {
                        if let Some(height) = heights.get_mut(i) {
                            *height = lower(*height, lowest);
                        }
                    }
                    return;
                }
                for k in (0..n).step_by(RUN) {
                    let sc: [f32; RUN] = std::array::from_fn(|l| at(k + l).0);
                    let hh: [f32; RUN] = std::array::from_fn(|l| at(k + l).1.powi(2));
                    let index: [usize; RUN] = std::array::from_fn(|l| start + (k + l) * step);
                    let index = index.get(..(n - k).min(RUN)).unwrap_or_default();
                    sweeper.work(&sc, &hh, index, false);
                }
            },
        );
        if let Some(later) = sweeper.later.take() {
            let index = later.index.get(..later.n).unwrap_or_default();
            sweeper.work(&later.sc, &later.hh, index, true);
        }
        sweeper.found.map(|(_, hit)| hit)
    }
}

/// A cut under way with one profile.
struct Sweeper<'a, P> {
    sweep: Sweep<P>,
    heights: &'a mut [f32],
    check: Option<Check>,
    /// The stock's bottom, the depth a check looks for, and the height a cell must stand
    /// above to pass it.
    bottom: f32,
    threshold: f32,
    clear: f32,
    /// Cells whose lowest point needs a search, gathered to be searched a group at a time
    /// (when nothing is checked, so that the order cells are cut in does not matter).
    later: Option<Batch>,
    /// The hit so far and what ranks it first: its contact along the move and its depth, or
    /// only its depth.
    found: Option<((f32, f32), Hit)>,
}

impl<P: Profile> Sweeper<'_, P> {
    /// Cuts the cells at `index` (`sc` along the line, `hh` from it squared), searching their
    /// lowest points now or by group later; with a cell high enough for the check, notes depths and
    /// ranks passes.
    fn work<const N: usize>(
        &mut self,
        sc: &[f32; N],
        hh: &[f32; N],
        index: &[usize],
        search: bool,
    ) {
        let (g, settled) = self.sweep.group(sc, hh, search || self.later.is_none());
        let check = self.check.filter(|_| {
            (index.iter()).any(|&i| self.heights.get(i).is_some_and(|&h| h > self.clear))
        });
        for (l, &index) in index.iter().enumerate() {
            if !settled[l] {
                if let Some(later) = &mut self.later
                    && later.push(index, sc[l], hh[l])
                {
                    let full = *later;
                    later.n = 0;
                    self.work(&full.sc, &full.hh, &full.index, true);
                }
                continue;
            }
            let (Some(height), cell) = (self.heights.get_mut(index), g.get(l)) else {
                continue;
            };
            let floor = at_least(cell.low, self.bottom);
            let Some(check) = check else {
                *height = lower(*height, floor);
                continue;
            };
            let sweep = &self.sweep;
            let depth = match check {
                Check::Rapid => *height - floor,
                Check::Shank(_) => {
                    let tip = sweep.z0 + sweep.m * if sweep.m > 0.0 { cell.lo } else { cell.hi };
                    *height - at_least(tip, self.bottom)
                }
            };
            *height = lower(*height, floor);
            if depth <= self.threshold {
                continue;
            }
            let top = floor + depth;
            let rank = match check {
                // When the tool meets the cell: how far along the move, or for a plunge how
                // far down (a vertical move up meets everything at its start).
                Check::Rapid if sweep.len > 0.0 => {
                    (sweep.first_contact(cell, top - CONTACT_MM), -depth)
                }
                Check::Rapid if sweep.down => (cell.low - top, -depth),
                Check::Rapid => (f32::NEG_INFINITY, -depth),
                Check::Shank(_) => (-depth, 0.0),
            };
            // Of equals, the first in rows from the lowest, whatever order the cells came in.
            let first =
                |(best, hit): ((f32, f32), Hit)| rank < best || (rank == best && index < hit.index);
            if self.found.is_none_or(first) {
                self.found = Some((rank, Hit { index, depth }));
            }
        }
    }
}

impl Reach {
    /// The reach of `profile`, of radius `r`, on a move of slope `m` and XY length `len`. A checked move is
    /// given none but for the cells behind its start where the tool only rises as it leaves,
    /// so that it cuts and checks every other cell as a lone move would.
    fn of(profile: AnyProfile, r: f64, m: f32, len: f64, checked: bool) -> Reach {
        let all = f64::INFINITY;
        let reach = |back, front, start, end| Reach {
            back,
            front,
            start,
            end,
        };
        // Descending, the tool is lowest at the start over cells more than `lead` behind it,
        // and at the end over cells past it or within `near` of it; climbing, the other way.
        let ends = |lead: f64, near: f64| {
            if m < 0.0 {
                reach(lead, 0.0, 0.0, near)
            } else {
                reach(0.0, lead, near, 0.0)
            }
        };
        let free = match profile {
            _ if len == 0.0 => reach(all, all, 0.0, 0.0),
            // On a level move the closest point is lowest.
            _ if m == 0.0 => ends(0.0, 0.0),
            // The tip is lowest where the tool first (climbing) or last covers a cell.
            AnyProfile::Flat(_) | AnyProfile::Cone(Cone { steep: true, .. }) => ends(r, r),
            AnyProfile::Ball(Ball { c, .. }) => {
                let lead = f64::from(c.abs()) * r;
                ends(lead, lead)
            }
            AnyProfile::Cone(Cone { c, .. }) => ends(f64::from(c.abs()) * r, 0.0),
            // Within `ρ = flat + corner·sin(atan |m|)`, where the corner is as steep as the
            // move, the tool is lowest at the end; further, the corner rises away from a cell
            // behind the tool faster than the move falls unless the cell lies less than `β(r)
            // ≤ ρ` behind the line across its end (see `Cut::taper`).
            AnyProfile::Bull(Bull {
                flat, corner, m2, ..
            }) => {
                let near = f64::from(flat + corner * (m2 / (1.0 + m2)).sqrt());
                ends(near, near)
            }
        };
        if checked {
            let bull_down = matches!(profile, AnyProfile::Bull(_)) && m < 0.0;
            reach(if bull_down { all } else { free.back }, all, 0.0, 0.0)
        } else {
            free
        }
    }
}

impl Cut {
    /// The XY end of the move.
    fn end(&self) -> [f64; 2] {
        [
            self.a[0] + self.len * self.e[0],
            self.a[1] + self.len * self.e[1],
        ]
    }

    /// Shares the cells about the joint with `next` (same tool, neither checked): each may leave to
    /// the other those where its tool is lowest at the joint, never both, as cells left past an end
    /// lie within `R·sin θ` (`θ` the turn, under 90°) of the line across `next`'s start.
    pub(crate) fn join(&mut self, next: &mut Cut) {
        if self.checked || next.checked {
            return;
        }
        let r = f64::from(self.r);
        let ([ex, ey], [fx, fy]) = (self.e, next.e);
        let turn = if ex * fx + ey * fy >= 0.0 {
            r * (ex * fy - ey * fx).abs()
        } else {
            r
        };
        if self.reach.end >= next.reach.start {
            if self.reach.end > 0.0 {
                if self.hole.is_some() {
                    return;
                }
                self.hole = Some((self.end(), self.reach.end));
            }
            self.ahead = self.reach.front;
            let round = if self.ahead < r { turn } else { 0.0 };
            next.behind = next.reach.back.max(self.reach.end).max(round);
            next.hole = None;
            (next.wedge[0], next.disc[0]) = (round, self.reach.end);
        } else {
            next.behind = next.reach.back;
            next.hole = Some((next.a, next.reach.start));
            let round = if next.behind < r { turn } else { 0.0 };
            self.ahead = self.reach.front.max(next.reach.start).max(round);
            (self.wedge[1], self.disc[1]) = (round, next.reach.start);
        }
    }

    /// How far from its start (`side` 0) or end (1) it cuts the cells `s` past the line across
    /// that end, beyond its wedge: as far as the tool can come lower than at the end, and over
    /// the neighbour's hole.
    fn keep(&self, side: usize, s: f64) -> f64 {
        let r = f64::from(self.r);
        let taper = (self.taper.iter().flatten()).find(|&&(_, beta)| beta <= s);
        let taper = taper.map_or(r, |&(r, _)| r);
        taper.max(self.disc[side]) + MARGIN
    }

    /// Calls `each(first, step, n, [sc, h, dsc, dh])` (`h` may be negated) for the runs of cells it
    /// cuts: in its radius, `behind`..`ahead` and [`Cut::keep`] past its wedges ([`MARGIN`] more),
    /// not its hole. A short move's runs go across it, so there are few.
    fn runs(
        &self,
        cell: f64,
        nx: usize,
        ny: usize,
        mut each: impl FnMut(usize, usize, usize, [f64; 4]),
    ) {
        let r = f64::from(self.r);
        let back = -(self.behind + MARGIN).min(r + MARGIN);
        let front = self.len + (self.ahead + MARGIN).min(r + MARGIN);
        // In the frame that has the runs along its X, with `n` cells along them and `lines`
        // of them, the cell `k` along line `j` at `k·step + j·next`. Runs go along Y only over
        // a band shorter than the diameter: the cells of a column share a set of the cache.
        let across = front - back < 2.0 * r && self.e[0].abs() > self.e[1].abs();
        let swap = |[x, y]: [f64; 2]| if across { [y, x] } else { [x, y] };
        let ([ax, ay], [ex, ey], b) = (swap(self.a), swap(self.e), swap(self.end()));
        let (n, lines, step, next) = if across {
            (ny, nx, nx, 1)
        } else {
            (nx, ny, 1, nx)
        };
        let inv = 1.0 / cell;
        let (ylo, yhi) = (
            ay + (back * ey).min(front * ey) - r * ex.abs(),
            ay + (back * ey).max(front * ey) + r * ex.abs(),
        );
        let Some((j0, j1)) = cells_between(ylo * inv, yhi * inv, lines) else {
            return;
        };
        let inv_e = [1.0 / ex, 1.0 / ey];
        let hole = self.hole.map(|(c, radius)| (swap(c), radius - MARGIN));
        let (dsc, dh) = (cell * ex, cell * ey);
        for j in j0..=j1 {
            let y = (j as f64 + 0.5) * cell;
            let uy = y - ay;
            // The along-coordinate and the offset from the line are linear in x − a.x.
            let (l1, h1) = linear_span(uy * ey, ex, inv_e[0], back, front);
            let (l2, h2) = linear_span(-uy * ex, ey, inv_e[1], -r, r);
            let (l3, h3) = linear_span(uy * ey, ex, inv_e[0], 0.0, self.len);
            // Within the tool's radius of the move (the discs about its ends and the band
            // between them, which together are convex): exactly the cells the tool covers,
            // whatever cut asks. And between `back` and `front`.
            let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
            if l2.max(l3) <= h2.min(h3) {
                (lo, hi) = (ax + l2.max(l3), ax + h2.min(h3));
            }
            for [px, py] in [[ax, ay], b] {
                let w2 = r * r - (y - py) * (y - py);
                if w2 >= 0.0 {
                    let w = w2.sqrt();
                    (lo, hi) = (lo.min(px - w), hi.max(px + w));
                }
            }
            let (mut lo, mut hi) = (lo.max(ax + l1), hi.min(ax + h1));
            // A line wholly beyond the wedge behind the start or past the end is cut only
            // within `keep` of that end.
            let (s0, s1) = ((lo - ax) * ex + uy * ey, (hi - ax) * ex + uy * ey);
            let (s_lo, s_hi) = (s0.min(s1), s0.max(s1));
            for (side, [px, py], past) in [(0, [ax, ay], -s_hi), (1, b, s_lo - self.len)] {
                if self.taper.is_some() && past > self.wedge[side] + MARGIN {
                    let keep = self.keep(side, past);
                    let w = (keep * keep - (y - py) * (y - py)).max(0.0).sqrt();
                    (lo, hi) = (lo.max(px - w), hi.min(px + w));
                }
            }
            let Some((i0, i1)) = cells_between(lo * inv, hi * inv, n) else {
                continue;
            };
            // The run either side of the hole, where the line crosses it.
            let hole = hole.and_then(|([cx, cy], radius)| {
                let w2 = radius * radius - (y - cy) * (y - cy);
                let w = (w2 > 0.0).then(|| w2.sqrt())?;
                cells_between((cx - w) * inv, (cx + w) * inv, n)
            });
            let runs = match hole {
                Some((p, q)) => [(i0, p.min(i1 + 1)), ((q + 1).max(i0), i1 + 1)],
                None => [(i0, i1 + 1), (0, 0)],
            };
            for (p, q) in runs {
                if p < q {
                    let ux = (p as f64 + 0.5) * cell - ax;
                    let (sc, h) = (ux * ex + uy * ey, ux * ey - uy * ex);
                    each(p * step + j * next, step, q - p, [sc, h, dsc, dh]);
                }
            }
        }
    }
}

/// A profile with the constants of one segment's sweep.
#[derive(Clone, Copy)]
struct Sweep<P> {
    profile: P,
    r2: f32,
    z0: f32,
    m: f32,
    len: f32,
    down: bool,
}

impl<P: Profile> Sweep<P> {
    fn new(cut: &Cut, profile: P) -> Self {
        Sweep {
            profile,
            r2: cut.r * cut.r,
            z0: cut.z0,
            m: cut.m,
            len: cut.len as f32,
            down: cut.down,
        }
    }

    /// The cells whose centres lie at `sc` along the line and `hh` from it squared, with the
    /// lowest point over each found (`search`) or over those that need no search, and which
    /// those are.
    #[inline(always)]
    fn group<const N: usize>(
        &self,
        sc: &[f32; N],
        hh: &[f32; N],
        search: bool,
    ) -> (Group<N>, [bool; N]) {
        let mut g = Group {
            sc: *sc,
            hh: *hh,
            w: [0.0; N],
            lo: [0.0; N],
            hi: [0.0; N],
            u: [0.0; N],
            low: [0.0; N],
        };
        for l in 0..N {
            let w = at_least(self.r2 - hh[l], 0.0).sqrt();
            g.w[l] = w;
            (g.lo[l], g.hi[l]) = (at_least(sc[l] - w, 0.0), at_most(sc[l] + w, self.len));
        }
        let settled = if search {
            g.u = self.profile.lowest(&g);
            [true; N]
        } else {
            let (u, settled) = self.profile.settled(&g);
            g.u = u;
            settled
        };
        for l in 0..N {
            let lift = self.profile.lift(g.hh[l], g.u[l] - g.sc[l], g.w[l]);
            g.low[l] = self.z0 + self.m * g.u[l] + lift;
        }
        (g, settled)
    }

    /// The earliest `u` at which the tool's end comes below `level` over `cell`, which it does
    /// by its lowest point.
    fn first_contact(&self, cell: Cell, level: f32) -> f32 {
        let at = |u: f32| self.z0 + self.m * u + self.profile.lift(cell.hh, u - cell.sc, cell.w);
        if at(cell.lo) < level {
            return cell.lo;
        }
        let (mut a, mut b) = (cell.lo, cell.u);
        for _ in 0..24 {
            let mid = 0.5 * (a + b);
            if at(mid) < level {
                b = mid;
            } else {
                a = mid;
            }
        }
        b
    }
}

/// The larger of `a` and `b`; `a` when it is not a number, so that a height is never lowered by
/// one.
#[inline(always)]
fn at_least(a: f32, b: f32) -> f32 {
    if a < b { b } else { a }
}

/// The smaller of `a` and `b`.
#[inline(always)]
fn at_most(a: f32, b: f32) -> f32 {
    if a > b { b } else { a }
}

/// `x` brought into `[lo, hi]` (`hi` when the range is empty).
#[inline(always)]
fn clamp(x: f32, lo: f32, hi: f32) -> f32 {
    at_most(at_least(x, lo), hi)
}

/// `height` lowered to `floor`, unless `floor` is not a number.
#[inline(always)]
fn lower(height: f32, floor: f32) -> f32 {
    if floor < height { floor } else { height }
}

/// The indices of the cells (of `n`) whose centres lie in `[lo, hi]` (in cells from the grid's
/// lowest corner).
fn cells_between(lo: f64, hi: f64, n: usize) -> Option<(usize, usize)> {
    let (lo, hi) = (lo - 0.5, hi - 0.5);
    if !(lo <= hi && hi >= 0.0 && lo <= n as f64 - 1.0) {
        return None;
    }
    // Both are now within the grid give or take a cell, so the casts are exact.
    let below = lo.max(0.0) as usize;
    let first = below + usize::from((below as f64) < lo);
    let last = (hi as usize).min(n - 1);
    (first <= last).then_some((first, last))
}

/// The `x` with `c0 + c1·x` in `[lo, hi]`, given `inv = 1 / c1`.
fn linear_span(c0: f64, c1: f64, inv: f64, lo: f64, hi: f64) -> (f64, f64) {
    if c1.abs() < 1e-12 {
        if (lo..=hi).contains(&c0) {
            (f64::NEG_INFINITY, f64::INFINITY)
        } else {
            (f64::INFINITY, f64::NEG_INFINITY)
        }
    } else {
        let (a, b) = ((lo - c0) * inv, (hi - c0) * inv);
        (a.min(b), a.max(b))
    }
}
