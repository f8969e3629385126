//! Golden programs under `tests/golden/`: the canonical stream must match exactly.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic, missing_docs)]

#[cfg(target_arch = "wasm32")]
use wasm_bindgen_test::wasm_bindgen_test as test;

use swarf_interp::{CanonRecorder, Setup, run};
use swarf_syntax::{Dialect, Severity, parse};

fn canon(text: &str, setup: &str) -> (String, Vec<swarf_syntax::Diagnostic>) {
    let program = parse(text, Dialect::Fanuc);
    assert!(program.diagnostics.is_empty(), "{:?}", program.diagnostics);
    let mut rec = CanonRecorder::default();
    let diags = run(&program, Setup::from_toml(setup).unwrap(), &mut rec);
    let mut out = String::new();
    for (source, event) in &rec.events {
        out.push_str(&event.to_json(*source).to_string());
        out.push('\n');
    }
    (out, diags)
}

macro_rules! golden {
    ($name:ident, $setup:expr) => {
        #[test]
        fn $name() {
            let (out, diags) = canon(
                include_str!(concat!("../../../tests/golden/", stringify!($name), ".nc")),
                $setup,
            );
            let expected = include_str!(concat!(
                "../../../tests/golden/",
                stringify!($name),
                ".jsonl"
            ));
            assert_eq!(out, expected);
            assert!(
                diags.iter().all(|d| d.severity < Severity::Error),
                "{diags:?}"
            );
        }
    };
}

golden!(incremental, "");
golden!(arcs, "");
golden!(
    offsets,
    include_str!("../../../tests/golden/offsets.setup.toml")
);
