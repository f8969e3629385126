//! G65 and G66 macro calls: the repeat count and the arguments, for the machine to call.

use swarf_syntax::{Quantity, Word, WordForm};

use super::actions::{Action, Actions};
use super::{MAX_COUNT, Request, Requests, count_range};
use crate::machine::find;
use crate::macros::argument_variable;
use crate::state::{ModalMacro, State};

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

/// G65 P L args: the call, or nothing without P.
fn macro_call(st: &mut State, words: &[Word], g65: &Word) -> Requests {
    let Some(p) = find(words, b'P') else {
        let message = "G65 needs the macro program number in P";
        return st.fail(g65.span, "E-WORD-MISSING", message);
    };
    let repeats = repeat_count(st, find(words, b'L'));
    let args = arguments(st, words);
    let call = Request::Macro {
        number: p.value,
        repeats,
        args,
    };
    Requests::from_elem(call, 1)
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

/// G65 (a macro call) and G66 (the modal macro): the block does nothing else; `None` without.
pub(super) fn macro_codes(
    st: &mut State,
    words: &[Word],
    actions: &Actions<'_>,
) -> Option<Requests> {
    // G65: a macro call takes the block's words as arguments.
    if let Some((_, g65)) = actions.iter().find(|(a, _)| matches!(a, Action::MacroCall)) {
        return Some(macro_call(st, words, g65));
    }
    let (_, g66) = actions
        .iter()
        .find(|(a, _)| matches!(a, Action::ModalMacro(true)))?;
    let args = arguments(st, words);
    // L: how many times the macro runs after each move.
    let repeats = repeat_count(st, find(words, b'L'));
    let Some(p) = find(words, b'P') else {
        let message = "G66 needs the macro program number in P";
        return Some(st.fail(g66.span, "E-WORD-MISSING", message));
    };
    st.modal_macro = Some(ModalMacro {
        number: p.value,
        repeats,
        args,
    });
    Some(Requests::new())
}
