//! M codes: pauses, spindle, coolant, tool change, program end, subprogram calls and returns.

use swarf_syntax::codes::{self, Code};
use swarf_syntax::{Dialect, Word, WordForm};

use super::{Request, Requests};
use crate::state::State;
use crate::{Canon, Sink, Source};

/// M codes, and the flow they ask for (calls, returns, program end), in the block's order.
pub(super) fn m_codes(
    st: &mut State,
    words: &[Word],
    source: Source,
    sink: &mut dyn Sink,
) -> Requests {
    let mut requests = Requests::new();
    for word in (words.iter()).filter(|w| w.letter == b'M' && w.form == WordForm::Plain) {
        let Some(code) = Code::from_value(b'M', word.value) else {
            continue;
        };
        let event = match code.tenths {
            0 => Canon::Pause { optional: false },
            10 => Canon::Pause { optional: true },
            20 | 300 => {
                requests.push(Request::Stop);
                Canon::End
            }
            600 if st.dialect == Dialect::LinuxCnc => Canon::Pause { optional: false },
            30 | 40 | 50 => {
                let clockwise = (code.tenths != 50).then_some(code.tenths == 30);
                let rpm = clockwise.map_or(0.0, |_| st.spindle_rpm);
                st.spindle_dir = clockwise;
                Canon::Spindle { clockwise, rpm }
            }
            60 => Canon::ToolChange { tool: st.tool },
            70 | 80 => Canon::Coolant { on: true },
            90 => Canon::Coolant { on: false },
            190 => continue,
            // M198: a program from outside the control's memory (a linked file), called as M98.
            980 | 1980 => {
                requests.push(Request::Subprogram);
                continue;
            }
            990 => {
                requests.push(Request::Return);
                continue;
            }
            _ => {
                // Codes outside the dialect's list were reported by the parser.
                if let Some(def) = codes::lookup(st.dialect, code) {
                    let message = format!("{} ({}) is not interpreted yet", def.code, def.name);
                    st.warning(word.span, "W-NOT-INTERPRETED", message);
                }
                continue;
            }
        };
        crate::corners::emit(st, sink, source, &event);
    }
    requests
}
