//! The height field and the sweep of a tool along one straight segment.
//!
//! Over a cell's centre, at perpendicular distance `h` from the segment's line in XY and at
//! `sc` along it, the tool's tip at `u` along the segment (its tip height `z0 + m·u`) leaves
//! its end at `z0 + m·u + lift(r)`, where `r² = h² + (u − sc)²`. The tool covers the cell for `u`
//! in `[max(0, sc − w), min(len, sc + w)]` with `w = √(R² − h²)`. Every profile's lift is
//! convex and non-decreasing in `r`, so the end's height is convex in `u`: its minimum has a
//! closed form for flat, ball and cone ends, and is found by a bisection for a bull nose.
//!
//! A move that follows another of the same tool skips the cells behind its start where the
//! tool only rises as it leaves: the cut before it left them at the tool's shape there.

use glam::DVec3;

use crate::{Shape, Stock, StockError, Tool};

/// How far (mm) a rapid's tool may come below the material at a cell before it counts as
/// meeting it: room for the rounding of the stored heights, so a rapid along a surface the
/// same tool has just cut is not taken for a collision.
pub(crate) const CONTACT_MM: f32 = 0.001;

/// A straight XY move shorter than this (mm) is taken as purely vertical.
const VERTICAL_MM: f64 = 1e-4;

/// The stock as a Z-map: one height per cell of a square grid over its XY extent.
#[derive(Debug, Clone)]
pub struct HeightField {
    stock: Stock,
    cell: f64,
    nx: usize,
    ny: usize,
    heights: Vec<f32>,
    /// A row's worth of working space for the checks, kept between cuts.
    scratch: Vec<f32>,
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

/// One segment in the grid's frame (XY from the grid's lowest corner).
#[derive(Debug, Clone, Copy)]
struct Segment {
    a: [f64; 2],
    b: [f64; 2],
    /// Unit XY direction ((1, 0) for a vertical move), and the inverse of each component.
    e: [f64; 2],
    inv_e: [f64; 2],
    /// XY length (0 for a vertical move).
    len: f64,
    /// Tip height at the start (the lower end for a vertical move).
    z0: f32,
    /// Tip rise per millimetre along XY.
    m: f32,
    /// A vertical move downwards.
    down: bool,
    /// How far behind its start the segment needs cutting (mm along it): the tool is lowest
    /// at the start over cells further back, which the cut ending there has already lowered.
    behind: f64,
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
    /// Where the tool's end is lowest over the centre, and that height (infinite when the
    /// tool misses the centre).
    u: f32,
    low: f32,
}

/// [`Cell`]s of a group of `N` neighbours in a row, field by field.
#[derive(Debug, Clone, Copy)]
struct Cells<const N: usize> {
    sc: [f32; N],
    hh: [f32; N],
    w: [f32; N],
    lo: [f32; N],
    hi: [f32; N],
    u: [f32; N],
    low: [f32; N],
}

impl<const N: usize> Cells<N> {
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

/// Any of the profiles, chosen once a segment.
#[derive(Clone, Copy)]
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
    /// The tool's radius.
    fn radius(self) -> f32;
    /// The `u` in `[lo, hi]` where the end is lowest over a cell.
    fn lowest_at(self, sc: f32, hh: f32, w: f32, lo: f32, hi: f32) -> f32;
    /// Whether a group of cells is worked field by field ([`Profile::lowest_of`] loops).
    const GROUPED: bool = false;
    /// [`Profile::lowest_at`] for a group of cells (a profile whose search loops overrides it
    /// to loop over the group inside, which is what vectorizes).
    #[inline(always)]
    fn lowest_of<const N: usize>(self, c: &Cells<N>) -> [f32; N] {
        std::array::from_fn(|l| self.lowest_at(c.sc[l], c.hh[l], c.w[l], c.lo[l], c.hi[l]))
    }
    /// Height of the end above the tip at `r² = hh + s²` (within the radius, `w² = R² − hh`).
    fn lift(self, hh: f32, s: f32, w: f32) -> f32;
}

#[derive(Clone, Copy)]
struct Flat {
    r: f32,
    /// The move climbs, so the tip is lowest where it first covers a cell.
    up: bool,
}

impl Profile for Flat {
    fn radius(self) -> f32 {
        self.r
    }
    #[inline(always)]
    fn lowest_at(self, _: f32, _: f32, _: f32, lo: f32, hi: f32) -> f32 {
        if self.up { lo } else { hi }
    }
    #[inline(always)]
    fn lift(self, _: f32, _: f32, _: f32) -> f32 {
        0.0
    }
}

#[derive(Clone, Copy)]
struct Ball {
    r: f32,
    /// `−m / √(1 + m²)`: the lowest point's offset along the move over `w`.
    c: f32,
}

impl Profile for Ball {
    fn radius(self) -> f32 {
        self.r
    }
    #[inline(always)]
    fn lowest_at(self, sc: f32, _: f32, w: f32, lo: f32, hi: f32) -> f32 {
        at_most(at_least(sc + self.c * w, lo), hi)
    }
    #[inline(always)]
    fn lift(self, _: f32, s: f32, w: f32) -> f32 {
        self.r - at_least(w * w - s * s, 0.0).sqrt()
    }
}

#[derive(Clone, Copy)]
struct Cone {
    r: f32,
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
    fn radius(self) -> f32 {
        self.r
    }
    #[inline(always)]
    fn lowest_at(self, sc: f32, hh: f32, _: f32, lo: f32, hi: f32) -> f32 {
        if self.steep {
            if self.up { lo } else { hi }
        } else {
            at_most(at_least(sc + self.c * hh.sqrt(), lo), hi)
        }
    }
    #[inline(always)]
    fn lift(self, hh: f32, s: f32, _: f32) -> f32 {
        self.k * (hh + s * s).sqrt()
    }
}

#[derive(Clone, Copy)]
struct Bull {
    r: f32,
    /// Radius of the flat centre and of the corner.
    flat: f32,
    corner: f32,
    /// The slope squared, and the side of the lowest point (against the slope).
    m2: f32,
    ahead: f32,
    /// The least sine of the corner's angle at a lowest point, `|m| / √(1 + m²)` (over a
    /// cell on the move's line).
    least: f32,
}

impl Profile for Bull {
    fn radius(self) -> f32 {
        self.r
    }
    const GROUPED: bool = true;
    fn lowest_at(self, sc: f32, hh: f32, w: f32, lo: f32, hi: f32) -> f32 {
        let [u] = self.lowest_of(&Cells {
            sc: [sc],
            hh: [hh],
            w: [w],
            lo: [lo],
            hi: [hi],
            u: [0.0],
            low: [0.0],
        });
        u
    }
    /// The lowest point is where the corner's surface is parallel to the move: at the angle
    /// `φ` up the corner (its sine `s`, at radius `ρ = flat + corner·s`) and `ψ` off the move
    /// with `tan φ · cos ψ = |m|` and `ρ · sin ψ = h`. That fixes one `s` in `[least, 1]` with
    /// `s² · (ρ² − h² + m²ρ²) = m²ρ²`, found by bisection without a branch; the point is then
    /// `√(ρ² − h²)` behind or ahead of the centre's foot.
    #[inline(always)]
    fn lowest_of<const N: usize>(self, c: &Cells<N>) -> [f32; N] {
        // The root's lower bound, raised by halving steps (a sum, not a branch per cell).
        let (mut below, mut step) = ([self.least; N], 0.5 * (1.0 - self.least));
        for _ in 0..18 {
            for (below, &hh) in below.iter_mut().zip(&c.hh) {
                let s = *below + step;
                let rho = self.flat + self.corner * s;
                let rho2 = rho * rho;
                let short = s * s * (at_least(rho2 - hh, 0.0) + self.m2 * rho2) < self.m2 * rho2;
                *below += step * f32::from(u8::from(short));
            }
            step *= 0.5;
        }
        std::array::from_fn(|l| {
            let rho = self.flat + self.corner * (below[l] + step);
            let lead = at_least(rho * rho - c.hh[l], 0.0).sqrt();
            at_most(at_least(c.sc[l] + self.ahead * lead, c.lo[l]), c.hi[l])
        })
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
            scratch: Vec::new(),
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
        self.cut_checked(from, to, tool, false, None);
    }

    /// Cuts like [`HeightField::cut`] and makes `check` on the material as it was. `continues`
    /// says the last cut was made with the same tool and ended at `from`, so the cells it left
    /// at the tool's shape there are skipped.
    pub(crate) fn cut_checked(
        &mut self,
        from: DVec3,
        to: DVec3,
        tool: &Tool,
        continues: bool,
        check: Option<Check>,
    ) -> Option<Hit> {
        let (seg, profile) = self.prepare(from, to, tool, continues)?;
        // A level move of a flat end lowers everything it covers to its height.
        let fill = matches!(profile, AnyProfile::Flat(_)) && seg.m == 0.0;
        each_profile!(profile, p => self.sweep(&seg, p, fill, check))
    }

    /// The cut of [`HeightField::cut_checked`] with one profile, row by row. A row where no
    /// cell stands high enough to pass the check is only cut; any other is cut in a pass that
    /// notes, per cell, the depth the check is about, and then gone over again to rank the
    /// cells that pass.
    fn sweep<P: Profile>(
        &mut self,
        seg: &Segment,
        profile: P,
        fill: bool,
        check: Option<Check>,
    ) -> Option<Hit> {
        let bottom = self.stock.min[2] as f32;
        let sweep = Sweep::new(seg, profile, self.cell);
        let threshold = match check {
            None => f32::INFINITY,
            Some(Check::Rapid) => CONTACT_MM,
            Some(Check::Shank(flutes)) => flutes + CONTACT_MM,
        };
        // No cell at or below the tip's lowest point (plus the threshold) can pass the check.
        let lowest = at_least(seg.z0.min(seg.z0 + seg.m * seg.len as f32), bottom);
        let clear = lowest + threshold;
        // The hit so far and what ranks it first: its contact along the move and its depth,
        // or only its depth.
        let mut found: Option<((f32, f32), Hit)> = None;
        let mut depths = std::mem::take(&mut self.scratch);
        self.rows(
            seg,
            f64::from(profile.radius()),
            !fill,
            |row, start, sc0, h0| {
                let check = check.filter(|_| row.iter().fold(false, |any, &h| any | (h > clear)));
                let Some(check) = check else {
                    if fill {
                        for height in row {
                            *height = lower(*height, lowest);
                        }
                    } else {
                        sweep.each(row, sc0, h0, |_, height, cell| {
                            *height = lower(*height, at_least(cell.low, bottom));
                        });
                    }
                    return;
                };
                depths.clear();
                depths.resize(row.len(), f32::NEG_INFINITY);
                let mut over = false;
                sweep.each(row, sc0, h0, |k, height, cell| {
                    let floor = at_least(cell.low, bottom);
                    let depth = match check {
                        Check::Rapid => *height - floor,
                        Check::Shank(_) => {
                            let tip =
                                sweep.z0 + sweep.m * if sweep.m > 0.0 { cell.lo } else { cell.hi };
                            let depth = *height - at_least(tip, bottom);
                            if cell.low.is_finite() {
                                depth
                            } else {
                                f32::NEG_INFINITY
                            }
                        }
                    };
                    if let Some(slot) = depths.get_mut(k) {
                        *slot = depth;
                    }
                    over |= depth > threshold;
                    *height = lower(*height, floor);
                });
                if !over {
                    return;
                }
                for (k, &depth) in depths.iter().enumerate() {
                    if depth <= threshold {
                        continue;
                    }
                    let cell = sweep.cell(sc0, h0, k);
                    let top = at_least(cell.low, bottom) + depth;
                    let rank = match check {
                        // When the tool meets the cell: how far along the move, or for a plunge how
                        // far down (a vertical move up meets everything at its start).
                        Check::Rapid if seg.len > 0.0 => {
                            (sweep.first_contact(cell, top - CONTACT_MM), -depth)
                        }
                        Check::Rapid if seg.down => (cell.low - top, -depth),
                        Check::Rapid => (f32::NEG_INFINITY, -depth),
                        Check::Shank(_) => (-depth, 0.0),
                    };
                    if found.is_none_or(|(best, _)| rank < best) {
                        found = Some((
                            rank,
                            Hit {
                                index: start + k,
                                depth,
                            },
                        ));
                    }
                }
            },
        );
        self.scratch = depths;
        found.map(|(_, hit)| hit)
    }

    /// The segment in the grid's frame and the tool's profile for its slope (see
    /// [`HeightField::cut_checked`] for `continues`); `None` for coordinates that are not
    /// numbers or a tool outside its ranges.
    fn prepare(
        &self,
        from: DVec3,
        to: DVec3,
        tool: &Tool,
        continues: bool,
    ) -> Option<(Segment, AnyProfile)> {
        let origin = DVec3::new(self.stock.min[0], self.stock.min[1], 0.0);
        let (a, b) = (from - origin, to - origin);
        if !(a.is_finite() && b.is_finite() && tool.check().is_ok()) {
            return None;
        }
        let d = b - a;
        let len = d.x.hypot(d.y);
        let seg = if len > VERTICAL_MM {
            Segment {
                a: [a.x, a.y],
                b: [b.x, b.y],
                e: [d.x / len, d.y / len],
                inv_e: [len / d.x, len / d.y],
                len,
                z0: a.z as f32,
                m: (d.z / len) as f32,
                down: false,
                behind: f64::INFINITY,
            }
        } else {
            Segment {
                a: [a.x, a.y],
                b: [a.x, a.y],
                e: [1.0, 0.0],
                inv_e: [1.0, f64::INFINITY],
                len: 0.0,
                z0: a.z.min(b.z) as f32,
                m: 0.0,
                down: b.z < a.z,
                behind: f64::INFINITY,
            }
        };
        let r = (tool.diameter / 2.0) as f32;
        let m = seg.m;
        let up = m > 0.0;
        let ball = Ball {
            r,
            c: -m / (1.0 + m * m).sqrt(),
        };
        let profile = match tool.shape {
            Shape::Flat => AnyProfile::Flat(Flat { r, up }),
            Shape::Ball => AnyProfile::Ball(ball),
            Shape::Bull { corner_radius } => {
                let corner = (corner_radius as f32).min(r);
                if corner <= 1e-6 {
                    AnyProfile::Flat(Flat { r, up })
                } else if corner >= r * (1.0 - 1e-6) {
                    AnyProfile::Ball(ball)
                } else {
                    AnyProfile::Bull(Bull {
                        r,
                        flat: r - corner,
                        corner,
                        m2: m * m,
                        ahead: if up { -1.0 } else { 1.0 },
                        least: m.abs() / (1.0 + m * m).sqrt(),
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
                AnyProfile::Cone(Cone { r, k, c, steep, up })
            }
        };
        let mut seg = seg;
        if continues && seg.len > 0.0 {
            // Behind the start the tool only rises away from a cell when the move climbs or
            // is level; going down, a ball or a shallow cone still comes lower over cells
            // within its lowest point's lead (`c·R`) of the start.
            seg.behind = match profile {
                _ if m >= 0.0 => 0.0,
                AnyProfile::Ball(Ball { c, .. })
                | AnyProfile::Cone(Cone {
                    c, steep: false, ..
                }) => f64::from(c * r),
                _ => f64::INFINITY,
            };
        }
        Some((seg, profile))
    }

    /// Calls `each` with every row's run of cells whose centres lie within `r` of the segment
    /// in XY and no further than `seg.behind` behind its start, with the along-coordinate and
    /// the offset from the line of its first cell's centre. With `widen`, a run is widened
    /// within its row to whole groups of [`LANES`] cells, so it is worked in full vectors.
    #[inline(always)]
    fn rows(
        &mut self,
        seg: &Segment,
        r: f64,
        widen: bool,
        mut each: impl FnMut(&mut [f32], usize, f32, f32),
    ) {
        let inv = 1.0 / self.cell;
        let (ylo, yhi) = (seg.a[1].min(seg.b[1]) - r, seg.a[1].max(seg.b[1]) + r);
        let Some((j0, j1)) = cells_between(ylo * inv, yhi * inv, self.ny) else {
            return;
        };
        let [ex, ey] = seg.e;
        for j in j0..=j1 {
            let y = (j as f64 + 0.5) * self.cell;
            let Some((xlo, xhi)) = row_span(seg, r, y) else {
                continue;
            };
            let Some((mut i0, mut i1)) = cells_between(xlo * inv, xhi * inv, self.nx) else {
                continue;
            };
            let n = (i1 - i0 + 1).next_multiple_of(LANES);
            if widen && n <= self.nx {
                i0 = i0.min(self.nx - n);
                i1 = i0 + n - 1;
            }
            let start = j * self.nx + i0;
            let Some(row) = self.heights.get_mut(start..=j * self.nx + i1) else {
                continue;
            };
            let (ux, uy) = ((i0 as f64 + 0.5) * self.cell - seg.a[0], y - seg.a[1]);
            each(
                row,
                start,
                (ux * ex + uy * ey) as f32,
                (ux * ey - uy * ex) as f32,
            );
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
    /// The change of the along-coordinate and of the offset from one cell to the next in a
    /// row.
    dsc: f32,
    dh: f32,
}

impl<P: Profile> Sweep<P> {
    fn new(seg: &Segment, profile: P, cell: f64) -> Self {
        Sweep {
            profile,
            r2: profile.radius() * profile.radius(),
            z0: seg.z0,
            m: seg.m,
            len: seg.len as f32,
            dsc: (cell * seg.e[0]) as f32,
            dh: (cell * seg.e[1]) as f32,
        }
    }

    /// The `N` cells from the `k`-th of a row whose first centre is at `sc0` along and `h0`
    /// off the line (a cell the tool misses has an infinite `low`).
    #[inline(always)]
    fn cells<const N: usize>(&self, sc0: f32, h0: f32, k: usize) -> Cells<N> {
        let mut c = Cells {
            sc: [0.0; N],
            hh: [0.0; N],
            w: [0.0; N],
            lo: [0.0; N],
            hi: [0.0; N],
            u: [0.0; N],
            low: [0.0; N],
        };
        for l in 0..N {
            let step = (k + l) as f32;
            let sc = sc0 + step * self.dsc;
            let h = h0 + step * self.dh;
            let hh = h * h;
            let w = at_least(self.r2 - hh, 0.0).sqrt();
            (c.sc[l], c.hh[l], c.w[l]) = (sc, hh, w);
            (c.lo[l], c.hi[l]) = (at_least(sc - w, 0.0), at_most(sc + w, self.len));
        }
        c.u = self.profile.lowest_of(&c);
        for l in 0..N {
            let lift = self.profile.lift(c.hh[l], c.u[l] - c.sc[l], c.w[l]);
            let covered = c.hh[l] <= self.r2 && c.lo[l] <= c.hi[l];
            c.low[l] = if covered {
                self.z0 + self.m * c.u[l] + lift
            } else {
                f32::INFINITY
            };
        }
        c
    }

    /// The `k`-th cell of a row (see [`Sweep::cells`]).
    #[inline(always)]
    fn cell(&self, sc0: f32, h0: f32, k: usize) -> Cell {
        self.cells::<1>(sc0, h0, k).get(0)
    }

    /// Calls `visit` with the index, the height and the cell of each of `row` (whose first
    /// centre is at `sc0` along and `h0` off the line): one at a time, or a group of
    /// [`GROUP`] at a time for a profile that works groups.
    #[inline(always)]
    fn each(
        &self,
        row: &mut [f32],
        sc0: f32,
        h0: f32,
        mut visit: impl FnMut(usize, &mut f32, Cell),
    ) {
        if !P::GROUPED {
            for (k, height) in row.iter_mut().enumerate() {
                visit(k, height, self.cell(sc0, h0, k));
            }
            return;
        }
        for (g, group) in row.chunks_mut(GROUP).enumerate() {
            let cells = self.cells::<GROUP>(sc0, h0, g * GROUP);
            for (l, height) in group.iter_mut().enumerate() {
                visit(g * GROUP + l, height, cells.get(l));
            }
        }
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

/// Cells a row's run is widened to a multiple of, so it is worked in full vectors (a multiple of
/// every vector width the crate is built for).
const LANES: usize = 8;

/// Cells a profile that searches works at once: enough vectors in flight to hide the latency
/// of each step of the search.
const GROUP: usize = 32;

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

/// The X range of the points of row `y` within `r` of the segment (the union of the two end
/// discs and the band along the segment, which together are convex), and no further than
/// `behind` behind its start.
fn row_span(seg: &Segment, r: f64, y: f64) -> Option<(f64, f64)> {
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for [px, py] in [seg.a, seg.b] {
        let w2 = r * r - (y - py) * (y - py);
        if w2 >= 0.0 {
            let w = w2.sqrt();
            (lo, hi) = (lo.min(px - w), hi.max(px + w));
        }
    }
    if seg.len > 0.0 {
        let ([ex, ey], [to_x, to_y]) = (seg.e, seg.inv_e);
        let uy = y - seg.a[1];
        // The offset from the line and the along-coordinate are linear in x − a.x.
        let (l1, h1) = linear_span(-uy * ex, ey, to_y, -r, r);
        let (l2, h2) = linear_span(uy * ey, ex, to_x, 0.0, seg.len);
        let (l3, h3) = linear_span(uy * ey, ex, to_x, -seg.behind, f64::INFINITY);
        let (band_lo, band_hi) = (l1.max(l2), h1.min(h2));
        if band_lo <= band_hi {
            (lo, hi) = (lo.min(seg.a[0] + band_lo), hi.max(seg.a[0] + band_hi));
        }
        (lo, hi) = (lo.max(seg.a[0] + l3), hi.min(seg.a[0] + h3));
    }
    (lo <= hi).then_some((lo, hi))
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
