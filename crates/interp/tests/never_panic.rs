//! Arbitrary G-code-like programs run through the interpreter in every dialect without a panic
//! and within the block budget (what the fuzz target checks at random, here on every test run).
#![cfg(not(target_arch = "wasm32"))]
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic, missing_docs)]

use proptest::prelude::*;
use swarf_interp::{CanonRecorder, Setup, run};
use swarf_syntax::{Dialect, parse};

/// One block of words and macro pieces the parser and interpreter know, in any order.
fn block() -> impl Strategy<Value = String> {
    let word = prop_oneof![
        "[GM][0-9]{1,3}(\\.[0-9])?",
        "[XYZIJKRQPFSTDHLEABC]-?[0-9]{0,4}(\\.[0-9]{0,3})?",
        "#[0-9]{1,3}=[-0-9.#\\[\\]+*/ ]{0,12}",
        "(IF|WHILE)\\[#[0-9] (EQ|LT|GT) [0-9]\\] (GOTO[0-9]|DO1)",
        "END1|M99|M98 P[0-9]{1,4}|O[0-9]{1,4}|N[0-9]{1,4}",
        ",[CR][0-9]\\.?",
        "o[0-9]{1,3} (sub|endsub|call|if \\[1\\]|endif|while \\[1\\]|endwhile)",
    ];
    prop::collection::vec(word, 0..6).prop_map(|w| w.join(" "))
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(200))]
    #[test]
    fn any_program_runs_without_a_panic(
        blocks in prop::collection::vec(block(), 0..25),
        d in 0usize..6,
    ) {
        let text = blocks.join("\n");
        let dialect = Dialect::ALL[d];
        let program = parse(&text, dialect);
        let mut setup = Setup::default();
        setup.machine.max_blocks = 5_000;
        setup.machine.max_motions = 20_000;
        let mut rec = CanonRecorder::default();
        let _ = run(&program, setup, &mut rec);
        // Bounded: every event came from a block budget of 5,000.
        prop_assert!(rec.events.len() < 5_000_000);
    }
}
