//! `swarf render`: draws a program's toolpath offscreen as the backplot draws it (its
//! [`Drawing`] and renderer, wgpu; Mesa lavapipe works with no display), with the cut stock
//! under it on request, and writes it as a PNG.

use std::io::Write;
use std::path::{Path, PathBuf};

use anyhow::Result;
use glam::{DVec3, Vec3};
use swarf_render::{
    Drawing, HeadlessGpu, OrbitCamera, Projection, StandardView, StockSurface, ViewParams,
    reference_points, view_bounds,
};
use swarf_toolpath::Toolpath;

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
    /// Draw the stock as the program cuts it (the setup's [stock], or a box around the feed
    /// moves), as a lit surface under the toolpath.
    #[arg(long)]
    stock: bool,
    /// Draw no toolpath: with --stock, the cut stock alone.
    #[arg(long)]
    no_path: bool,
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

/// Runs `swarf render`: interprets the program (diagnostics to `err` as with `check`), draws
/// it and writes the PNG, even when the program has errors; the exit status follows them.
pub(crate) fn render(args: &RenderArgs, out: &mut dyn Write, err: &mut dyn Write) -> Result<i32> {
    let (setup, stock) = super::read_setup(&args.opts, err)?;
    let mut loaded = super::load(&args.file, &args.opts)?;
    let mut path = Toolpath::for_machine(DVec3::ZERO, &setup.machine);
    path.reserve(loaded.program.blocks.len());
    let run = swarf_interp::run(&loaded.program, setup.clone(), &mut path);
    let mut diags = loaded.all_diagnostics(run);
    let cut = super::cut_stock(&path, &stock, args.stock, &loaded).map(|(cut, more)| {
        diags = super::merged(std::mem::take(&mut diags), more);
        cut
    });
    let status = loaded.print(&diags, err)?;

    // What the backplot draws, framed as its Fit frames it, with the stock.
    let drawing = Drawing::of(&path, setup.machine.travel_mm);
    let field = cut
        .as_ref()
        .filter(|_| args.stock)
        .map(|cut| cut.simulation.field());
    let surface = field.map(|field| StockSurface {
        heights: field.heights(),
        size: field.size(),
        cell_mm: field.cell_mm(),
        min: DVec3::from_array(field.stock().min),
        top: field.stock().max[2],
        origin: drawing.origin,
    });
    let stock_box = field.map(|field| {
        let corner = |p: [f64; 3]| (DVec3::from_array(p) - drawing.origin).as_vec3();
        (corner(field.stock().min), corner(field.stock().max))
    });
    let (points, marks) = if args.no_path {
        (&[][..], &[][..])
    } else {
        (&drawing.points[..], &drawing.marks[..])
    };
    let (min, max) = match (view_bounds(drawing.bounds, marks), stock_box) {
        (Some(a), Some(b)) if !args.no_path => (a.0.min(b.0), a.1.max(b.1)),
        (a, b) => b.or(a).unwrap_or((Vec3::ONE, Vec3::ZERO)),
    };
    let reference = reference_points(drawing.zero, drawing.bounds, marks);

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
    let (stock, size) = (surface.as_ref(), args.size);
    let pixels = gpu.render_rgba8(stock, points, &reference, &params, size, BACKGROUND)?;
    write_png(&args.output, width, height, &pixels)?;
    let (shown, segments, gpu) = (args.output.display(), path.len(), gpu.info);
    let (name, backend) = (gpu.name, gpu.backend);
    writeln!(
        out,
        "{shown}: {width}x{height}, {segments} segments ({name} on {backend:?})"
    )?;
    Ok(status)
}

/// Writes tightly packed RGBA8 pixels as a PNG.
fn write_png(path: &Path, width: u32, height: u32, rgba: &[u8]) -> Result<()> {
    let file = std::fs::File::create(path)
        .map_err(|e| anyhow::anyhow!("cannot create {}: {e}", path.display()))?;
    let failed = |e: png::EncodingError| anyhow::anyhow!("cannot write {}: {e}", path.display());
    let mut encoder = png::Encoder::new(std::io::BufWriter::new(file), width, height);
    encoder.set_color(png::ColorType::Rgba);
    encoder.set_depth(png::BitDepth::Eight);
    let mut writer = encoder.write_header().map_err(failed)?;
    writer.write_image_data(rgba).map_err(failed)?;
    writer.finish().map_err(failed)
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
