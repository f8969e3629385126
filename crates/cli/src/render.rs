//! `swarf render`: draws a program's toolpath offscreen with the backplot's renderer (wgpu;
//! Mesa lavapipe works with no display) and writes it as a PNG, with the machine's travel box and
//! the G22 stroke limits as outlines.

use std::io::Write;
use std::path::{Path, PathBuf};

use glam::{DVec3, Vec3};
use swarf_render::{
    HeadlessGpu, Kind, OrbitCamera, PathPoint, Projection, StandardView, ViewParams, grid_points_at,
};
use swarf_toolpath::{CycleMove, SegmentKind, Toolpath, box_edges};

/// Background of the image: the app's dark backplot (sRGB).
const BACKGROUND: [u8; 4] = [16, 16, 18, 255];

/// Arguments of `swarf render`.
#[derive(clap::Args, Debug)]
pub(crate) struct RenderArgs {
    /// Program file.
    file: PathBuf,
    /// PNG file to write.
    #[arg(short = 'o', long = "output", value_name = "OUT.png")]
    output: PathBuf,
    /// Standard view: iso, top, front or right.
    #[arg(long, default_value = "iso", value_parser = parse_view)]
    view: StandardView,
    /// Image size in pixels, WIDTHxHEIGHT.
    #[arg(long, default_value = "1024x768", value_name = "WxH", value_parser = parse_size)]
    size: (u32, u32),
    /// Perspective projection (orthographic by default).
    #[arg(long)]
    perspective: bool,
    #[command(flatten)]
    opts: super::RunOptions,
}

fn parse_view(s: &str) -> Result<StandardView, String> {
    match s.to_ascii_lowercase().as_str() {
        "iso" => Ok(StandardView::Iso),
        "top" => Ok(StandardView::Top),
        "front" => Ok(StandardView::Front),
        "right" => Ok(StandardView::Right),
        _ => Err(format!("unknown view {s:?} (iso, top, front or right)")),
    }
}

/// Largest image side accepted on the command line (the device may allow less).
const MAX_SIDE: u32 = 16384;

fn parse_size(s: &str) -> Result<(u32, u32), String> {
    let bad = || format!("size {s:?} is not WIDTHxHEIGHT (e.g. 1024x768)");
    let (w, h) = s.split_once(['x', 'X', '×']).ok_or_else(bad)?;
    let w: u32 = w.trim().parse().map_err(|_| bad())?;
    let h: u32 = h.trim().parse().map_err(|_| bad())?;
    if w == 0 || h == 0 || w > MAX_SIDE || h > MAX_SIDE {
        return Err(format!(
            "size {w}x{h} must be 1 to {MAX_SIDE} pixels per side"
        ));
    }
    Ok((w, h))
}

/// The toolpath as the renderer's point stream relative to `origin`: the start (pen up),
/// then one point per segment end with its kind.
fn path_points(path: &Toolpath, origin: DVec3) -> Vec<PathPoint> {
    let rel = |p: DVec3| (p - origin).as_vec3();
    let mut points = Vec::with_capacity(path.len() + 1);
    points.push(PathPoint::pen_up(rel(path.start())));
    points.extend(path.ends().iter().zip(path.kinds()).map(|(end, kind)| {
        let kind = match kind {
            SegmentKind::Rapid => Kind::Rapid,
            SegmentKind::Feed => Kind::Feed,
            SegmentKind::Arc => Kind::Arc,
        };
        PathPoint::new(rel(*end), kind)
    }));
    for (segment, role) in path.cycle_moves() {
        if let Some(p) = points.get_mut(segment + 1) {
            *p = PathPoint::new(p.position(), cycle_kind(role));
        }
    }
    points
}

/// The renderer's kind for a canned-cycle move.
fn cycle_kind(role: CycleMove) -> Kind {
    match role {
        CycleMove::Plunge => Kind::Plunge,
        CycleMove::Retract => Kind::Retract,
        CycleMove::Other => Kind::Cycle,
    }
}

/// Runs `swarf render`: interprets the program (diagnostics to `err` as with `check`), draws
/// it and writes the PNG. The exit status follows the diagnostics; the image is written
/// even when the program has errors (it shows what runs).
pub(crate) fn render(
    args: &RenderArgs,
    out: &mut dyn Write,
    err: &mut dyn Write,
) -> anyhow::Result<i32> {
    let setup = super::read_setup(&args.opts)?;
    let mut loaded = super::load(&args.file, &args.opts)?;
    let mut path = Toolpath::for_machine(DVec3::ZERO, &setup.machine);
    path.reserve(loaded.program.blocks.len());
    let run = loaded.interpret(&setup, &mut path);
    let diags = loaded.all_diagnostics(run);
    let status = loaded.print(&diags, err)?;

    let origin = path.bounds().map_or(DVec3::ZERO, |b| b.center());
    let points = path_points(&path, origin);
    let zones = path.zone_boxes();
    // The view takes in the path and the stroke limits it set.
    let (min, max) = path.bounds().map_or((Vec3::ONE, Vec3::ZERO), |b| {
        let (lo, hi) = zones
            .iter()
            .fold((b.min, b.max), |(lo, hi), z| (lo.min(z.0), hi.max(z.1)));
        ((lo - origin).as_vec3(), (hi - origin).as_vec3())
    });
    let zero = (DVec3::ZERO - origin).as_vec3();
    let mut grid = grid_points_at(zero, min, max);
    // Outlines: the machine's travel and every G22 stroke limit the program set.
    let travel = setup
        .machine
        .travel_mm
        .map(|[lo, hi]| (DVec3::from_array(lo), DVec3::from_array(hi)));
    let outlines = travel
        .into_iter()
        .map(|b| (b, Kind::Boundary))
        .chain(zones.into_iter().map(|b| (b, Kind::Zone)));
    for ((lo, hi), kind) in outlines {
        for (a, b) in box_edges(lo, hi) {
            grid.push(PathPoint::pen_up((a - origin).as_vec3()));
            grid.push(PathPoint::new((b - origin).as_vec3(), kind));
        }
    }

    let (width, height) = args.size;
    let aspect = width as f32 / height as f32;
    let mut camera = OrbitCamera::new(args.view);
    if args.perspective {
        camera.projection = Projection::Perspective;
    }
    camera.fit_aspect(min, max, aspect);
    let params = ViewParams {
        view_proj: camera.view_proj(aspect),
        ..ViewParams::default()
    }
    .scaled((height as f32 / 768.0).clamp(1.0, 4.0));

    let gpu = pollster::block_on(HeadlessGpu::new())?;
    let pixels = gpu.render_rgba8(&points, &grid, &params, args.size, BACKGROUND)?;
    write_png(&args.output, width, height, &pixels)?;
    writeln!(
        out,
        "{}: {width}x{height}, {} segments ({} on {:?})",
        args.output.display(),
        path.len(),
        gpu.info.name,
        gpu.info.backend
    )?;
    Ok(status)
}

/// Writes tightly packed RGBA8 pixels as a PNG.
fn write_png(path: &Path, width: u32, height: u32, rgba: &[u8]) -> anyhow::Result<()> {
    let file = std::fs::File::create(path)
        .map_err(|e| anyhow::anyhow!("cannot create {}: {e}", path.display()))?;
    let mut encoder = png::Encoder::new(std::io::BufWriter::new(file), width, height);
    encoder.set_color(png::ColorType::Rgba);
    encoder.set_depth(png::BitDepth::Eight);
    let mut writer = encoder
        .write_header()
        .map_err(|e| anyhow::anyhow!("cannot write {}: {e}", path.display()))?;
    writer
        .write_image_data(rgba)
        .map_err(|e| anyhow::anyhow!("cannot write {}: {e}", path.display()))?;
    writer
        .finish()
        .map_err(|e| anyhow::anyhow!("cannot write {}: {e}", path.display()))?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sizes_and_views_parse() {
        assert_eq!(parse_size("256x192"), Ok((256, 192)));
        assert_eq!(parse_size("64X48"), Ok((64, 48)));
        assert!(parse_size("0x10").is_err());
        assert!(parse_size("100").is_err());
        assert!(parse_size("axb").is_err());
        assert!(parse_size("99999x10").is_err());
        assert_eq!(parse_view("TOP"), Ok(StandardView::Top));
        assert!(parse_view("bottom").is_err());
    }
}
