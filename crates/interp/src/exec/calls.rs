//! G65 and G66 macro calls: the repeat count and the arguments, for the machine to call.

use swarf_syntax::{Quantity, Word, WordForm};

use super::actions::{Action, Actions};
use super::{MAX_COUNT, Request, Requests, count_range};
use crate::machine::find;
use crate::macros::argument_variable;
use crate::state::{MacroCall, State};

/// A macro call's repeat count L (1 when absent), clamped to 0–9999 with a diagnostic.
fn repeat_count(st: &mut State, l: Option<&Word>) -> u32 {
    let Some(l) = l else {
        return 1;
    };
    if !(0.0..=MAX_COUNT).contains(&l.value) {
        st.diagnostics.push(count_range(l, "repeats"));
    }
    l.value.clamp(0.0, MAX_COUNT) as u32
}

/// Macro-call arguments (argument specification I): letter → local variable, value as read.
fn arguments(st: &State, words: &[Word]) -> Vec<(u8, f64)> {
    words
        .iter()
        .filter(|w| w.form == WordForm::Plain && !b"GLNOP".contains(&w.letter))
        .filter_map(|w| {
            let value = if b"XYZUVWIJKRQ".contains(&w.letter) {
                st.dialect
                    .read(w, Quantity::Length, st.calculator(), !st.metric)
            } else {
                w.value
            };
            argument_variable(w.letter).map(|n| (n, value))
        })
        .collect()
}

/// G65 (a macro call) and G66 (the modal macro, called after each move) with P, L and the
/// arguments: the block does nothing else; `None` without either.
pub(super) fn macro_codes(
    st: &mut State,
    words: &[Word],
    actions: &Actions<'_>,
) -> Option<Requests> {
    let g65 = actions.iter().find(|(a, _)| *a == Action::MacroCall);
    let g66 = || actions.iter().find(|(a, _)| *a == Action::ModalMacro(true));
    let (action, code) = g65.or_else(g66)?;
    let modal = *action != Action::MacroCall;
    let p = find(words, b'P');
    // L: the repeat count (G66: runs after each move), read unless G65 lacks P.
    let repeats = (p.is_some() || modal).then(|| repeat_count(st, find(words, b'L')));
    let Some(p) = p else {
        let name = if modal { "G66" } else { "G65" };
        let message = format!("{name} needs the macro program number in P");
        return Some(st.fail(code.span, "E-WORD-MISSING", message));
    };
    let call = MacroCall {
        number: p.value,
        repeats: repeats.unwrap_or(1),
        args: arguments(st, words),
    };
    if !modal {
        return Some(Requests::from_elem(Request::Macro(call), 1));
    }
    st.modal_macro = Some(call);
    Some(Requests::new())
}
