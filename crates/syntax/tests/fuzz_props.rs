//! Property: any text parses without panicking, and every span lies inside the text.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic, missing_docs)]
#![cfg(not(target_arch = "wasm32"))]

use proptest::prelude::*;
use swarf_syntax::{Dialect, decode, parse};

proptest! {
    #[test]
    fn any_text_parses(text in "\\PC{0,200}", d in 0usize..6) {
        let p = parse(&text, Dialect::ALL[d]);
        for diag in &p.diagnostics {
            prop_assert!(diag.span.end as usize <= text.len());
            prop_assert!(text.is_char_boundary(diag.span.start as usize));
            prop_assert!(text.is_char_boundary(diag.span.end as usize));
        }
        for b in &p.blocks {
            prop_assert!(b.span.end as usize <= text.len());
        }
    }

    #[test]
    fn gcode_like_text_parses(text in "[GXYZFNgxyz0-9. ;()%/#\\-\n]{0,300}") {
        let p = parse(&text, Dialect::Fanuc);
        prop_assert!(p.blocks.iter().all(|b| b.span.start <= b.span.end));
    }

    #[test]
    fn any_bytes_decode(bytes in proptest::collection::vec(any::<u8>(), 0..200)) {
        let d = decode(&bytes);
        let p = parse(&d.text, Dialect::Fanuc);
        prop_assert!(p.lines.line_count() >= 1);
    }
}
