//! Validates the WGSL shaders with naga (no GPU needed) and checks they match the Rust side:
//! uniform size, vertex inputs and no storage buffers (WebGL2 has none).
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic, missing_docs)]

use naga::valid::{Capabilities, ValidationFlags, Validator};
use swarf_render::{
    COMPOSITE_WGSL, DRAW_UNIFORMS_SIZE, PATH_WGSL, POINT_SIZE, PathPoint, STOCK_UNIFORMS_SIZE,
    STOCK_WGSL, UNIFORMS_SIZE,
};

const SHADERS: [(&str, &str); 3] = [
    ("path", PATH_WGSL),
    ("composite", COMPOSITE_WGSL),
    ("stock", STOCK_WGSL),
];

fn parse(name: &str, source: &str) -> naga::Module {
    match naga::front::wgsl::parse_str(source) {
        Ok(module) => module,
        Err(err) => panic!("{name}: WGSL parse error:\n{}", err.emit_to_string(source)),
    }
}

#[test]
fn wgsl_validates_with_all_capabilities() {
    for (name, source) in SHADERS {
        let module = parse(name, source);
        let mut validator = Validator::new(ValidationFlags::all(), Capabilities::all());
        if let Err(err) = validator.validate(&module) {
            panic!(
                "{name}: WGSL validation error:\n{}",
                err.emit_to_string(source)
            );
        }
    }
}

#[test]
fn wgsl_needs_no_capabilities() {
    // Nothing beyond baseline WGSL, so the WebGL2 (GLES 3.0) backend can run it.
    for (name, source) in SHADERS {
        let module = parse(name, source);
        let mut validator = Validator::new(ValidationFlags::all(), Capabilities::empty());
        if let Err(err) = validator.validate(&module) {
            panic!(
                "{name}: shader needs extra capabilities:\n{}",
                err.emit_to_string(source)
            );
        }
    }
}

fn entry_names(module: &naga::Module) -> Vec<&str> {
    module
        .entry_points
        .iter()
        .map(|e| e.name.as_str())
        .collect()
}

#[test]
fn path_shader_entry_points_bindings_and_inputs() {
    let module = parse("path", PATH_WGSL);
    let names = entry_names(&module);
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
    // Two uniforms (no storage buffers): the frame's, the size of the Rust `Uniforms`, and
    // the draw call's, the size of its `DrawUniforms`, both padded to 16 bytes as std140
    // (WebGL2) requires; and the draw call's points, a texture.
    let globals: Vec<_> = module.global_variables.iter().map(|(_, g)| g).collect();
    assert_eq!(globals.len(), 3);
    assert!(
        globals[..2]
            .iter()
            .all(|g| g.space == naga::AddressSpace::Uniform)
    );
    assert_eq!(globals[2].space, naga::AddressSpace::Handle);
    let draw = module.types[globals[1].ty].inner.size(module.to_ctx());
    assert_eq!(u64::from(draw), DRAW_UNIFORMS_SIZE);
    let groups: Vec<u32> = globals
        .iter()
        .filter_map(|g| g.binding.as_ref().map(|b| b.group))
        .collect();
    assert_eq!(groups, [0, 1, 1]);
    let size = module.types[globals[0].ty].inner.size(module.to_ctx());
    assert_eq!(u64::from(size), UNIFORMS_SIZE);
    assert_eq!(size % 16, 0);
    // The palette array starts at a 16-byte boundary (std140 arrays of vec4).
    let naga::TypeInner::Struct { members, .. } = &module.types[globals[0].ty].inner else {
        panic!("uniform is not a struct");
    };
    let palette = members
        .iter()
        .find(|m| m.name.as_deref() == Some("palette"));
    assert_eq!(palette.map(|m| m.offset), Some(128));
    // No vertex data but the vertex index: the points come from the texture.
    let vs = module
        .entry_points
        .iter()
        .find(|e| e.name == "vs_main")
        .map(|e| &e.function)
        .unwrap();
    let mut locations: Vec<u32> = vs
        .arguments
        .iter()
        .filter_map(|a| match a.binding {
            Some(naga::Binding::Location { location, .. }) => Some(location),
            _ => None,
        })
        .collect();
    locations.sort_unstable();
    assert!(locations.is_empty(), "{locations:?}");
    let builtins = vs
        .arguments
        .iter()
        .filter(|a| matches!(a.binding, Some(naga::Binding::BuiltIn(_))))
        .count();
    assert_eq!(builtins, 1);
    assert_eq!(size_of::<PathPoint>() as u64, POINT_SIZE);
    assert_eq!(POINT_SIZE, 16);
}

#[test]
fn composite_shader_samples_one_texture() {
    let module = parse("composite", COMPOSITE_WGSL);
    let names = entry_names(&module);
    assert!(names.contains(&"vs_main") && names.contains(&"fs_main_linear_framebuffer"));
    assert!(
        module
            .global_variables
            .iter()
            .all(|(_, g)| g.space == naga::AddressSpace::Handle),
        "only a texture and a sampler"
    );
}

#[test]
fn stock_shader_reads_heights_from_a_texture_and_two_uniforms() {
    let module = parse("stock", STOCK_WGSL);
    let names = entry_names(&module);
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
    // Group 0: the path renderer's frame uniforms, of which it reads the first member; group 1:
    // the stock's uniforms and its heights. No storage buffer, no sampler.
    let globals: Vec<_> = module.global_variables.iter().map(|(_, g)| g).collect();
    let spaces: Vec<_> = globals.iter().map(|g| g.space).collect();
    assert_eq!(
        spaces,
        [
            naga::AddressSpace::Uniform,
            naga::AddressSpace::Uniform,
            naga::AddressSpace::Handle
        ]
    );
    let size = |i: usize| u64::from(module.types[globals[i].ty].inner.size(module.to_ctx()));
    assert!(size(0) <= UNIFORMS_SIZE);
    assert_eq!(size(1), STOCK_UNIFORMS_SIZE);
    assert_eq!(STOCK_UNIFORMS_SIZE % 16, 0);
    // No vertex attributes: every vertex comes from its index.
    let vs = module
        .entry_points
        .iter()
        .find(|e| e.name == "vs_main")
        .map(|e| &e.function)
        .unwrap();
    assert!(
        vs.arguments
            .iter()
            .all(|a| matches!(a.binding, Some(naga::Binding::BuiltIn(_))))
    );
}

#[test]
fn translates_to_webgl2_glsl_es_300() {
    use naga::back::glsl;
    for (name, source) in SHADERS {
        let module = parse(name, source);
        let mut validator = Validator::new(ValidationFlags::all(), Capabilities::empty());
        let info = validator.validate(&module).unwrap();
        let options = glsl::Options {
            version: glsl::Version::Embedded {
                version: 300,
                is_webgl: true,
            },
            ..glsl::Options::default()
        };
        for entry in &module.entry_points {
            let pipeline = glsl::PipelineOptions {
                shader_stage: entry.stage,
                entry_point: entry.name.clone(),
                multiview: None,
            };
            let mut out = String::new();
            let written = glsl::Writer::new(
                &mut out,
                &module,
                &info,
                &options,
                &pipeline,
                naga::proc::BoundsCheckPolicies::default(),
            )
            .and_then(|mut writer| writer.write());
            if let Err(err) = written {
                panic!(
                    "{name}::{}: no GLSL ES 3.00 for WebGL2: {err:?}",
                    entry.name
                );
            }
            assert!(out.starts_with("#version 300 es"), "{name}: {out}");
        }
    }
}
