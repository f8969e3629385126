//! Validates the line shader with naga (no GPU needed) and checks it matches `Vertex`.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic, missing_docs)]

use naga::valid::{Capabilities, ValidationFlags, Validator};
use swarf_render::{LINES_WGSL, Vertex};

fn parse() -> naga::Module {
    match naga::front::wgsl::parse_str(LINES_WGSL) {
        Ok(module) => module,
        Err(err) => panic!("WGSL parse error:\n{}", err.emit_to_string(LINES_WGSL)),
    }
}

#[test]
fn wgsl_validates_with_all_capabilities() {
    let module = parse();
    let mut validator = Validator::new(ValidationFlags::all(), Capabilities::all());
    if let Err(err) = validator.validate(&module) {
        panic!("WGSL validation error:\n{}", err.emit_to_string(LINES_WGSL));
    }
}

#[test]
fn wgsl_needs_no_capabilities() {
    // Nothing beyond baseline WGSL, so the WebGL2 (GLES 3.0) backend can run it.
    let module = parse();
    let mut validator = Validator::new(ValidationFlags::all(), Capabilities::empty());
    if let Err(err) = validator.validate(&module) {
        panic!(
            "shader needs extra capabilities:\n{}",
            err.emit_to_string(LINES_WGSL)
        );
    }
}

#[test]
fn wgsl_entry_points_and_bindings() {
    let module = parse();
    let names: Vec<&str> = module
        .entry_points
        .iter()
        .map(|e| e.name.as_str())
        .collect();
    for want in [
        "vs_main",
        "fs_main_gamma_framebuffer",
        "fs_main_linear_framebuffer",
    ] {
        assert!(
            names.contains(&want),
            "missing entry point {want}: {names:?}"
        );
    }
    // Exactly one uniform (no storage buffers: WebGL2 has none), 64 bytes = mat4x4<f32>.
    let globals: Vec<_> = module.global_variables.iter().map(|(_, g)| g).collect();
    assert_eq!(globals.len(), 1);
    assert_eq!(globals[0].space, naga::AddressSpace::Uniform);
    let size = module.types[globals[0].ty].inner.size(module.to_ctx());
    assert_eq!(size, 64);
    assert_eq!(
        size % 16,
        0,
        "uniform size must be padded to 16 bytes for WebGL2"
    );
    // Vertex inputs at locations 0 (vec3 position) and 1 (vec4 colour), matching Vertex.
    let vs = module
        .entry_points
        .iter()
        .find(|e| e.name == "vs_main")
        .map(|e| &e.function);
    let Some(vs) = vs else {
        panic!("no vs_main");
    };
    let locations: Vec<u32> = vs
        .arguments
        .iter()
        .filter_map(|a| match a.binding {
            Some(naga::Binding::Location { location, .. }) => Some(location),
            _ => None,
        })
        .collect();
    assert_eq!(locations, vec![0, 1]);
    assert_eq!(size_of::<Vertex>(), 16);
}
