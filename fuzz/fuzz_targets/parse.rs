//! Arbitrary bytes are decoded and parsed in every dialect: no panic, spans inside the text.
#![no_main]

use libfuzzer_sys::fuzz_target;
use swarf_syntax::{Dialect, decode, parse};

fuzz_target!(|bytes: &[u8]| {
    let text = decode(bytes).text;
    for dialect in Dialect::ALL {
        let program = parse(&text, dialect);
        for d in &program.diagnostics {
            assert!(d.span.end as usize <= text.len());
            assert!(text.is_char_boundary(d.span.start as usize));
            assert!(text.is_char_boundary(d.span.end as usize));
        }
    }
});
