// Swarf stock shader: the cut stock as a lit surface over its height field.
//
// The heights are a texture of one f32 per cell, read in the vertex stage: no vertex buffer and
// no storage buffer, so it runs on the WebGL2 fallback too. Vertex v belongs to quad v / 6 of a
// grid of (nx + 4) × (ny + 4) points: the inner nx × ny are the cells' centres at their heights,
// and the two rings round them lie on the stock's edge, the inner one at the edge cell's height
// and the outer one at the bottom, with the wall's normal, so every edge drops to a wall.

// The first member of the path shader's uniforms (the same buffer is bound).
struct Frame {
    // World (relative to the scene origin) to clip space; depth 0..1.
    view_proj: mat4x4<f32>,
};

@group(0) @binding(0)
var<uniform> frame: Frame;

struct Stock {
    // Centre of cell (0, 0) in the scene's frame (X, Y); what brings a height into it (Z).
    first: vec3<f32>,
    // Side of a cell.
    cell: f32,
    // Cells along X and along Y.
    size: vec2<u32>,
    // The stock's bottom and top in the scene's frame.
    bottom: f32,
    top: f32,
};

@group(1) @binding(0)
var<uniform> stock: Stock;

// One height (machine Z) per cell, R32Float, read with textureLoad only.
@group(1) @binding(1)
var heights: texture_2d<f32>;

struct VertexOutput {
    @builtin(position) clip: vec4<f32>,
    @location(0) normal: vec3<f32>,
    // 0 on the uncut top, 1 where the cell is cut: the cut surfaces' own colour.
    @location(1) cut: f32,
    // How deep the cell is cut, 0 at the top to 1 at the bottom.
    @location(2) depth: f32,
};

// The height of cell (i, j) in the scene's frame, the nearest edge cell's outside the grid.
fn height(i: i32, j: i32) -> f32 {
    let last = vec2<i32>(stock.size) - vec2<i32>(1);
    return textureLoad(heights, clamp(vec2<i32>(i, j), vec2<i32>(0), last), 0).r + stock.first.z;
}

// The slope of the heights along one axis at cell `at` of `n` (central differences, one-sided
// at the edges), from the heights before and after it.
fn slope(before: f32, after: f32, at: i32, n: i32) -> f32 {
    let cells = max(min(at + 1, n - 1) - max(at - 1, 0), 1);
    return (after - before) / (f32(cells) * stock.cell);
}

@vertex
fn vs_main(@builtin(vertex_index) v: u32) -> VertexOutput {
    let n = vec2<i32>(stock.size);
    let columns = stock.size.x + 3u;
    let corner = v % 6u;
    let quad = v / 6u;
    // Two triangles a quad: (0, 0) (1, 0) (1, 1), then (0, 0) (1, 1) (0, 1).
    let a = i32(quad % columns + ((0x16u >> corner) & 1u));
    let b = i32(quad / columns + ((0x34u >> corner) & 1u));
    let i = a - 2;
    let j = b - 2;
    // −1 or +1 on the rings past an edge, 0 over the cells.
    let outside = vec2<f32>(
        f32(select(0, -1, i < 0) + select(0, 1, i >= n.x)),
        f32(select(0, -1, j < 0) + select(0, 1, j >= n.y)),
    );
    let h = height(i, j);
    let on_bottom = a == 0 || b == 0 || a == n.x + 3 || b == n.y + 3;
    let cells = clamp(vec2<f32>(f32(i), f32(j)), vec2<f32>(-0.5), vec2<f32>(n) - vec2<f32>(0.5));
    let xy = stock.first.xy + cells * stock.cell;
    var out: VertexOutput;
    out.clip = frame.view_proj * vec4<f32>(xy, select(h, stock.bottom, on_bottom), 1.0);
    // A wall is the stock's uncut side, below whatever was cut above it.
    out.normal = vec3<f32>(outside, 0.0);
    out.cut = 0.0;
    out.depth = 0.0;
    if all(outside == vec2<f32>(0.0)) {
        let dx = slope(height(i - 1, j), height(i + 1, j), i, n.x);
        let dy = slope(height(i, j - 1), height(i, j + 1), j, n.y);
        out.normal = vec3<f32>(-dx, -dy, 1.0);
        out.cut = select(0.0, 1.0, h < stock.top - 1e-3);
        out.depth = clamp((stock.top - h) / max(stock.top - stock.bottom, 1e-6), 0.0, 1.0);
    }
    return out;
}

// A light from above, in front and to the right of the isometric view.
const LIGHT: vec3<f32> = vec3<f32>(0.35, -0.6, 0.9);

// The surface's colour (sRGB): grey stock, cut surfaces bluer, each darker the deeper it lies,
// lit by LIGHT over an ambient quarter.
fn shade(in: VertexOutput) -> vec3<f32> {
    let normal = normalize(in.normal + vec3<f32>(0.0, 0.0, 1e-6));
    let diffuse = max(dot(normal, normalize(LIGHT)), 0.0);
    let base = mix(vec3<f32>(0.72, 0.73, 0.76), vec3<f32>(0.55, 0.76, 0.95), in.cut);
    return base * (0.25 + 0.75 * diffuse) * (1.0 - 0.35 * in.depth);
}

// For gamma-space framebuffers (Rgba8Unorm / Bgra8Unorm): opaque, so premultiplied as is.
@fragment
fn fs_main_gamma_framebuffer(in: VertexOutput) -> @location(0) vec4<f32> {
    return vec4<f32>(shade(in), 1.0);
}

fn linear_from_gamma(srgb: vec3<f32>) -> vec3<f32> {
    let cutoff = srgb < vec3<f32>(0.04045);
    let lower = srgb / vec3<f32>(12.92);
    let higher = pow((srgb + vec3<f32>(0.055)) / vec3<f32>(1.055), vec3<f32>(2.4));
    return select(higher, lower, cutoff);
}

// For sRGB framebuffers (the hardware re-encodes): decode to linear first.
@fragment
fn fs_main_linear_framebuffer(in: VertexOutput) -> @location(0) vec4<f32> {
    return vec4<f32>(linear_from_gamma(shade(in)), 1.0);
}
