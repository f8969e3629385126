// Swarf path shader: every segment of a polyline stream is one screen-space quad.
//
// A texture holds ONE point per path vertex (16 bytes, one texel: position bits + packed kind/
// flags/colour index), a row after another. Vertices 6i .. 6i + 5 draw segment i, reading
// points i and i + 1 (no instancing: a software rasteriser pays for every instance). The
// segment takes its kind and flags from its end point B; a PEN_UP flag on B means "no segment
// from the previous point". Only uniform buffers and a texture read in the vertex stage, so it
// runs on the WebGL2 fallback too.

struct Uniforms {
    // World (relative to the scene origin) to clip space; depth 0..1.
    view_proj: mat4x4<f32>,
    // Size of the render target in physical pixels.
    viewport: vec2<f32>,
    // Width of cutting moves, in pixels.
    line_width: f32,
    // Width of rapid moves, in pixels.
    rapid_width: f32,
    // Width of grid lines, in pixels.
    grid_width: f32,
    // Extra width of highlighted segments, in pixels.
    highlight_extra: f32,
    // Rapid dash pattern: lit pixels, then dark pixels.
    dash_on: f32,
    dash_off: f32,
    // Opacity multiplier for the remainder (segments not executed yet by playback).
    dim_alpha: f32,
    // Seconds since some epoch, for animations (wrapped by the host).
    time: f32,
    // Segments with an index >= this are the remainder (drawn dimmed).
    executed_end: u32,
    // Segments in [highlight_start, highlight_end) are highlighted (selected block).
    highlight_start: u32,
    highlight_end: u32,
    // Bit k set: segments of kind k are not drawn (e.g. the programmed-contour overlay).
    hidden_kinds: u32,
    // 0: colour by kind; 1: colour by the point's colour index (e.g. the tool).
    color_mode: u32,
    _pad0: u32,
    // 0..15: colour of each kind (slot 15: highlight); 16..31: colours by index.
    // sRGB (gamma-encoded) with straight alpha, like egui's Color32.
    palette: array<vec4<f32>, 32>,
};

@group(0) @binding(0)
var<uniform> u: Uniforms;

// One per draw call (one texture of points).
struct Draw {
    // Index in the whole stream of the texture's first point: vertex indices restart at 0 in
    // every texture, segment numbers (highlight, playback) count from the stream's start.
    segment_base: u32,
    // 1 for the toolpath; 0 for the grid and reference marks, which the highlight and the
    // playback ranges (numbers of toolpath segments) never touch.
    path: u32,
    _pad0: u32,
    _pad1: u32,
};

@group(1) @binding(0)
var<uniform> draw: Draw;

// The draw call's points: x, y, z as f32 bits, then the packed word.
@group(1) @binding(1)
var points: texture_2d<u32>;

fn point_at(i: u32) -> vec4<u32> {
    let width = textureDimensions(points).x;
    return textureLoad(points, vec2<u32>(i % width, i / width), 0);
}

const KIND_RAPID: u32 = 0u;
const KIND_PROGRAMMED: u32 = 7u;
const KIND_GRID: u32 = 8u;
const KIND_GRID_MAJOR: u32 = 9u;
const HIGHLIGHT_SLOT: u32 = 15u;
const FLAG_PEN_UP: u32 = 1u;
const FLAG_HIGHLIGHT: u32 = 2u;

struct VertexOutput {
    @builtin(position) clip_position: vec4<f32>,
    // sRGB colour with straight alpha.
    @location(0) color: vec4<f32>,
    // (across, along) in pixels times clip w, and clip w: dividing by w in the fragment
    // shader gives values interpolated linearly in screen space (WebGL2 has no
    // `noperspective`).
    @location(1) edge: vec3<f32>,
    // x: half the line width in pixels; y: 0 solid, 1 dashed (rapid), 2 short dashes
    // (programmed contour).
    @location(2) style: vec2<f32>,
};

fn hidden() -> VertexOutput {
    var out: VertexOutput;
    // Outside the clip volume and identical for every corner: nothing is rasterised.
    out.clip_position = vec4<f32>(2.0, 2.0, 2.0, 1.0);
    out.color = vec4<f32>(0.0);
    out.edge = vec3<f32>(0.0, 0.0, 1.0);
    out.style = vec2<f32>(0.0);
    return out;
}

@vertex
fn vs_main(@builtin(vertex_index) vertex: u32) -> VertexOutput {
    let segment = vertex / 6u;
    // Two triangles over the quad's corners 0 1 2 and 2 1 3.
    var corner = vertex % 6u;
    if corner == 3u {
        corner = 2u;
    } else if corner == 4u {
        corner = 1u;
    } else if corner == 5u {
        corner = 3u;
    }
    let a = point_at(segment);
    let b = point_at(segment + 1u);
    let pos_a = bitcast<vec3<f32>>(a.xyz);
    let pos_b = bitcast<vec3<f32>>(b.xyz);
    let packed_b = b.w;
    let kind = packed_b & 0xffu;
    let flags = (packed_b >> 8u) & 0xffu;
    let color_index = packed_b >> 16u;
    if (flags & FLAG_PEN_UP) != 0u || ((u.hidden_kinds >> kind) & 1u) != 0u {
        return hidden();
    }

    var ca = u.view_proj * vec4<f32>(pos_a, 1.0);
    var cb = u.view_proj * vec4<f32>(pos_b, 1.0);
    // Clip against the near plane (z >= 0 in clip space) so segments passing behind the
    // eye keep their visible part.
    if ca.z < 0.0 && cb.z < 0.0 {
        return hidden();
    }
    if ca.z < 0.0 {
        ca = mix(ca, cb, ca.z / (ca.z - cb.z));
    }
    if cb.z < 0.0 {
        cb = mix(cb, ca, cb.z / (cb.z - ca.z));
    }
    if ca.w <= 0.0 || cb.w <= 0.0 {
        return hidden();
    }

    let on_path = draw.path != 0u;
    let index = draw.segment_base + segment;
    let highlighted = (flags & FLAG_HIGHLIGHT) != 0u
        || (on_path && index >= u.highlight_start && index < u.highlight_end);
    let dashed = kind == KIND_RAPID;
    var dash_style = 0.0;
    if dashed {
        dash_style = 1.0;
    } else if kind == KIND_PROGRAMMED {
        dash_style = 2.0;
    }
    var width = u.line_width;
    if dashed {
        width = u.rapid_width;
    } else if kind == KIND_GRID || kind == KIND_GRID_MAJOR {
        width = u.grid_width;
    }
    if highlighted {
        width = width + u.highlight_extra;
    }
    let half_width = max(width, 0.5) * 0.5;

    // Endpoints in pixels (origin at the centre; only differences matter).
    let half_viewport = u.viewport * 0.5;
    let sa = ca.xy / ca.w * half_viewport;
    let sb = cb.xy / cb.w * half_viewport;
    let d = sb - sa;
    let len = length(d);
    var dir = vec2<f32>(1.0, 0.0);
    if len > 1.0e-6 {
        dir = d / len;
    }
    let normal = vec2<f32>(-dir.y, dir.x);

    // Corners: 0 (A, -), 1 (A, +), 2 (B, -), 3 (B, +).
    let at_b = corner >= 2u;
    let side = select(-1.0, 1.0, (corner & 1u) == 1u);
    // One pixel beyond the line's edge for the anti-aliasing ramp; square caps of half the
    // width so consecutive segments overlap at their joints instead of leaving notches.
    let across = side * (half_width + 1.0);
    let cap = half_width;
    var clip = ca;
    var along = -cap;
    var offset = normal * across - dir * cap;
    if at_b {
        clip = cb;
        along = len + cap;
        offset = normal * across + dir * cap;
    }
    clip = vec4<f32>(clip.xy + offset / half_viewport * clip.w, clip.zw);

    var color: vec4<f32>;
    if highlighted {
        color = u.palette[HIGHLIGHT_SLOT];
    } else if u.color_mode == 1u && kind < KIND_GRID {
        color = u.palette[16u + (color_index & 15u)];
    } else {
        color = u.palette[kind & 15u];
    }
    if on_path && index >= u.executed_end && kind < KIND_GRID && !highlighted {
        color.a = color.a * u.dim_alpha;
    }

    var out: VertexOutput;
    out.clip_position = clip;
    out.color = color;
    out.edge = vec3<f32>(across * clip.w, along * clip.w, clip.w);
    out.style = vec2<f32>(half_width, dash_style);
    return out;
}

// Coverage of the fragment: anti-aliased edges and the rapid dash pattern.
fn coverage(in: VertexOutput) -> f32 {
    let across = in.edge.x / in.edge.z;
    let along = in.edge.y / in.edge.z;
    let half_width = in.style.x;
    var alpha = 1.0 - smoothstep(half_width - 0.5, half_width + 0.5, abs(across));
    if in.style.y > 0.5 {
        var on = u.dash_on;
        var off = u.dash_off;
        if in.style.y > 1.5 {
            // The programmed contour: dashes half as long as a rapid's.
            on = max(u.dash_on * 0.5, 1.0);
            off = u.dash_off * 0.75;
        }
        let period = max(on + off, 1.0);
        let phase = along - floor(along / period) * period;
        alpha = alpha * (1.0 - smoothstep(on - 0.5, on + 0.5, phase));
    }
    return alpha;
}

fn linear_from_gamma(srgb: vec3<f32>) -> vec3<f32> {
    let cutoff = srgb < vec3<f32>(0.04045);
    let lower = srgb / vec3<f32>(12.92);
    let higher = pow((srgb + vec3<f32>(0.055)) / vec3<f32>(1.055), vec3<f32>(2.4));
    return select(higher, lower, cutoff);
}

// The fragment premultiplied, if its coverage lies in [least, most): for gamma-space framebuffers
// (Rgba8Unorm / Bgra8Unorm, what egui prefers) as it is, like the rest of egui; for sRGB ones
// (the hardware re-encodes) decoded to linear first.
fn shade(in: VertexOutput, least: f32, most: f32, linear: bool) -> vec4<f32> {
    let covered = coverage(in);
    let alpha = in.color.a * covered;
    if alpha < 0.004 || covered < least || covered >= most {
        discard;
    }
    var rgb = in.color.rgb;
    if linear {
        rgb = linear_from_gamma(rgb);
    }
    return vec4<f32>(rgb * alpha, alpha);
}

// Whole lines (the grid and marks).
@fragment
fn fs_main_gamma_framebuffer(in: VertexOutput) -> @location(0) vec4<f32> {
    return shade(in, 0.0, 2.0, false);
}

@fragment
fn fs_main_linear_framebuffer(in: VertexOutput) -> @location(0) vec4<f32> {
    return shade(in, 0.0, 2.0, true);
}

// The path in two passes: its cores (at least half covered), which write depth, then its
// anti-aliased edges, which do not, so an edge never hides a line behind it (lines under a
// pixel apart would show only the nearest one's faint edge).
@fragment
fn fs_core_gamma_framebuffer(in: VertexOutput) -> @location(0) vec4<f32> {
    return shade(in, 0.5, 2.0, false);
}

@fragment
fn fs_core_linear_framebuffer(in: VertexOutput) -> @location(0) vec4<f32> {
    return shade(in, 0.5, 2.0, true);
}

@fragment
fn fs_edge_gamma_framebuffer(in: VertexOutput) -> @location(0) vec4<f32> {
    return shade(in, 0.0, 0.5, false);
}

@fragment
fn fs_edge_linear_framebuffer(in: VertexOutput) -> @location(0) vec4<f32> {
    return shade(in, 0.0, 0.5, true);
}
