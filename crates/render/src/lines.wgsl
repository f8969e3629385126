// Swarf line shader: line-list vertices with per-vertex sRGB colours.
// Only a uniform buffer and vertex attributes, so it runs on the WebGL2 fallback too.

struct Uniforms {
    // World (relative to the caller's origin) to clip space; depth 0..1.
    view_proj: mat4x4<f32>,
};

@group(0) @binding(0)
var<uniform> uniforms: Uniforms;

struct VertexOutput {
    @builtin(position) clip_position: vec4<f32>,
    // sRGB-encoded (gamma space) colour with straight alpha, like egui's Color32.
    @location(0) color: vec4<f32>,
};

@vertex
fn vs_main(@location(0) position: vec3<f32>, @location(1) color: vec4<f32>) -> VertexOutput {
    var out: VertexOutput;
    out.clip_position = uniforms.view_proj * vec4<f32>(position, 1.0);
    out.color = color;
    return out;
}

// For gamma-space framebuffers (Rgba8Unorm / Bgra8Unorm, what egui prefers): write the
// colour as is, premultiplied like the rest of egui.
@fragment
fn fs_main_gamma_framebuffer(in: VertexOutput) -> @location(0) vec4<f32> {
    return vec4<f32>(in.color.rgb * in.color.a, in.color.a);
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
    return vec4<f32>(linear_from_gamma(in.color.rgb) * in.color.a, in.color.a);
}
