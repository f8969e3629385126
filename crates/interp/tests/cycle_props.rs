//! Properties of every drilling cycle over random hole data: each hole ends exactly at the
//! programmed bottom, pecks never cut more than Q, and no rapid goes down below the R level into
//! material not yet cut.
#![cfg(not(target_arch = "wasm32"))]
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic, missing_docs)]

use proptest::prelude::*;
use swarf_interp::{Canon, CanonRecorder, Setup, run};
use swarf_syntax::{Dialect, Severity, parse};

const CYCLES: [u32; 11] = [73, 74, 76, 81, 82, 83, 84, 85, 86, 88, 89];

/// One hole's motions: (rapid?, start z, end z).
fn hole_moves(events: &[Canon], start_z: f64) -> Vec<Vec<(bool, f64, f64)>> {
    let mut holes: Vec<Vec<(bool, f64, f64)>> = Vec::new();
    let mut z = start_z;
    for e in events {
        match e {
            Canon::Hole { .. } => holes.push(Vec::new()),
            Canon::Rapid { to } | Canon::Feed { to, .. } => {
                if let Some(h) = holes.last_mut() {
                    h.push((matches!(e, Canon::Rapid { .. }), z, to.z));
                }
                z = to.z;
            }
            _ => {}
        }
    }
    holes
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(300))]
    #[test]
    fn holes_reach_the_bottom_pecks_respect_q_and_rapids_stay_above_r(
        cycle in prop::sample::select(&CYCLES[..]),
        dialect in prop::sample::select(&[Dialect::Fanuc, Dialect::Syntec, Dialect::Kt][..]),
        initial in 5.0f64..60.0,
        r_below in 0.0f64..5.0,
        depth in 0.5f64..40.0,
        q in 0.3f64..8.0,
        g98 in any::<bool>(),
        holes in prop::collection::vec((-100.0f64..100.0, -100.0f64..100.0), 1..4),
    ) {
        let r = initial - r_below;
        let bottom = r - depth;
        let mut text = format!("G90 G0 X0 Y0 Z{initial:.3}\nS800 M03\n");
        text.push_str(&format!(
            "{} G{cycle} X{:.3} Y{:.3} R{r:.3} Z{bottom:.3} Q{q:.3} P300 F200.\n",
            if g98 { "G98" } else { "G99" },
            holes[0].0,
            holes[0].1,
        ));
        for (x, y) in &holes[1..] {
            text.push_str(&format!("X{x:.3} Y{y:.3}\n"));
        }
        text.push_str("G80\n");
        let program = parse(&text, dialect);
        let mut rec = CanonRecorder::default();
        let diags = run(&program, Setup::default(), &mut rec);
        prop_assert!(diags.iter().all(|d| d.severity < Severity::Error), "{diags:?}");
        let events: Vec<Canon> = rec.events.iter().map(|(_, e)| e.clone()).collect();
        let moves = hole_moves(&events, 0.0);
        prop_assert_eq!(moves.len(), holes.len());
        // Levels as the control reads them (three decimals written).
        let r = (r * 1e3).round() / 1e3;
        let bottom = (bottom * 1e3).round() / 1e3;
        let q = (q * 1e3).round() / 1e3;
        for hole in &moves {
            let deepest = hole.iter().map(|m| m.2).fold(f64::INFINITY, f64::min);
            prop_assert!((deepest - bottom).abs() < 1e-9, "deepest {deepest} bottom {bottom}");
            prop_assert!(hole.iter().any(|m| !m.0 && (m.2 - bottom).abs() < 1e-9));
            // No rapid goes down below R into uncut material (pecks rapid back down into the
            // part of the hole already cut).
            let mut cut = r;
            for m in hole {
                if m.0 && m.2 < m.1 {
                    prop_assert!(m.2 >= cut - 1e-9, "rapid down to {} below R {r} and the cut {cut}", m.2);
                } else if !m.0 {
                    cut = cut.min(m.2);
                }
            }
            // Each feed cuts at most Q of new depth in the peck cycles.
            if matches!(cycle, 73 | 83) {
                let mut cut = r;
                for m in hole.iter().filter(|m| !m.0 && m.2 < m.1) {
                    if m.2 < cut {
                        prop_assert!(cut - m.2 <= q + 1e-9, "peck of {} > Q {q}", cut - m.2);
                        cut = m.2;
                    }
                }
            }
        }
    }
}
