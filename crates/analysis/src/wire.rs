//! Requests and replies as bytes, for a web worker: a short head (numbers, names, messages,
//! in postcard) and beside it the large parts whole, each in a buffer of its own that is moved,
//! not copied, between the page and the worker (the texts one way, the plot's arrays the other).
//! Reading checks every length: a message cut short or from elsewhere reads as `None`.

use serde::{Deserialize, Serialize};
use swarf_interp::Setup;
use swarf_syntax::Dialect;
use swarf_toolpath::Timeline;

use crate::run::Job;
use crate::service::{Reply, Request};
use crate::text::ProgramText;

/// A request's head: all but its texts.
#[derive(Serialize, Deserialize)]
enum RequestHead {
    Analyse {
        generation: u64,
        dialect: Dialect,
        /// The setup as TOML (one that TOML cannot hold, with a NaN, is read as the default).
        setup: String,
        /// The other open files' names; their texts follow the program's, in order.
        others: Option<Vec<String>>,
        lod: Option<crate::LodLevel>,
    },
    /// Any other request, whole.
    Other(Request),
}

/// The head of `request` and the texts that go beside it (the program's, then the other
/// files', in order).
pub fn request_parts(request: &Request) -> (Vec<u8>, Vec<&ProgramText>) {
    let (head, texts) = match request {
        Request::Analyse(job) => {
            let others = job.others.as_ref();
            let texts = std::iter::once(&job.text);
            let texts = texts.chain(others.into_iter().flatten().map(|(_, text)| text));
            let head = RequestHead::Analyse {
                generation: job.generation,
                dialect: job.dialect,
                setup: job.setup.to_toml().unwrap_or_default(),
                others: others.map(|o| o.iter().map(|(name, _)| name.clone()).collect()),
                lod: job.lod,
            };
            (head, texts.collect())
        }
        other => (RequestHead::Other(other.clone()), vec![]),
    };
    (postcard::to_allocvec(&head).unwrap_or_default(), texts)
}

/// The request of a head and its texts ([`request_parts`]).
pub fn request_from(head: &[u8], texts: Vec<String>) -> Option<Request> {
    Some(match whole(head)? {
        RequestHead::Analyse {
            generation,
            dialect,
            setup,
            others,
            lod,
        } => {
            let mut texts = texts.into_iter().map(ProgramText::from);
            let text = texts.next()?;
            let with_text = |n| Some((n, texts.next()?));
            let others = match others {
                Some(names) => Some(names.into_iter().map(with_text).collect::<Option<_>>()?),
                None => None,
            };
            Request::Analyse(Box::new(Job {
                generation,
                text,
                dialect,
                setup: Setup::from_toml(&setup).unwrap_or_default(),
                others,
                lod,
            }))
        }
        RequestHead::Other(request) => request,
    })
}

/// The head of `reply` and the arrays that go beside it.
pub fn reply_parts(reply: &Reply) -> (Vec<u8>, Vec<&[u8]>) {
    let arrays = match reply {
        Reply::Done(results) => {
            let plot = &results.plot;
            vec![
                bytemuck::cast_slice(&plot.drawing.points),
                bytemuck::cast_slice(&plot.drawing.marks),
                bytemuck::cast_slice(&plot.lines),
                bytemuck::cast_slice(&plot.feeds),
                bytemuck::cast_slice(plot.timeline.end_times()),
                bytemuck::cast_slice(&plot.tools),
                bytemuck::cast_slice(plot.lod.as_ref().map_or(&[][..], |l| &l.kept[..])),
            ]
        }
        Reply::Stock(cut) => (cut.field.iter())
            .map(|f| bytemuck::cast_slice(&f.heights))
            .collect(),
        Reply::Lod { kept, .. } => kept.iter().map(|k| bytemuck::cast_slice(&k[..])).collect(),
        Reply::Progress { .. } | Reply::State { .. } => Vec::new(),
    };
    (postcard::to_allocvec(reply).unwrap_or_default(), arrays)
}

/// The reply of a head and its arrays ([`reply_parts`]): `sizes` are the arrays' lengths in
/// bytes, and `fill(i, bytes)` copies array `i` into `bytes` (of that length).
pub fn reply_from(
    head: &[u8],
    sizes: &[usize],
    mut fill: impl FnMut(usize, &mut [u8]),
) -> Option<Reply> {
    let mut reply: Reply = whole(head)?;
    let mut array = Arrays {
        sizes,
        fill: &mut fill,
    };
    match &mut reply {
        Reply::Done(results) => {
            let plot = &mut results.plot;
            plot.drawing.points = std::sync::Arc::new(array.take(0)?);
            plot.drawing.marks = array.take(1)?;
            plot.lines = array.take(2)?;
            plot.feeds = array.take(3)?;
            let dwells = plot.timeline.dwells().to_vec();
            plot.timeline = Timeline::from_parts(array.take(4)?, dwells);
            plot.tools = array.take(5)?;
            if let Some(lod) = &mut plot.lod {
                lod.kept = std::sync::Arc::new(array.take(6)?);
            }
        }
        Reply::Stock(cut) => {
            if let Some(field) = &mut cut.field {
                field.heights = array.take(0)?;
                if field.heights.len() != field.size.0.checked_mul(field.size.1)? {
                    return None;
                }
            }
        }
        Reply::Lod { kept, .. } => {
            if !sizes.is_empty() {
                *kept = Some(std::sync::Arc::new(array.take(0)?));
            }
        }
        Reply::Progress { .. } | Reply::State { .. } => {}
    }
    Some(reply)
}

/// The value `head` holds, `None` unless it reads to its last byte.
fn whole<'a, T: Deserialize<'a>>(head: &'a [u8]) -> Option<T> {
    match postcard::take_from_bytes(head) {
        Ok((value, [])) => Some(value),
        _ => None,
    }
}

/// The arrays beside a reply's head: their lengths in bytes, and how to copy one.
struct Arrays<'a, F: FnMut(usize, &mut [u8])> {
    sizes: &'a [usize],
    fill: &'a mut F,
}

impl<F: FnMut(usize, &mut [u8])> Arrays<'_, F> {
    /// Array `i` as values of a type any bit pattern is (`None` when it is missing or its
    /// length is not a whole number of them), copied once, straight into place.
    fn take<T: bytemuck::Pod>(&mut self, i: usize) -> Option<Vec<T>> {
        let size = *self.sizes.get(i)?;
        let one = std::mem::size_of::<T>();
        if one == 0 || size % one != 0 {
            return None;
        }
        let mut values = vec![<T as bytemuck::Zeroable>::zeroed(); size / one];
        (self.fill)(i, bytemuck::cast_slice_mut(&mut values));
        Some(values)
    }
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]
    use super::*;
    use crate::run::{Progress, analyse};

    /// `reply` through its parts and back.
    fn again(reply: &Reply) -> Option<Reply> {
        let (head, arrays) = reply_parts(reply);
        let sizes: Vec<usize> = arrays.iter().map(|a| a.len()).collect();
        reply_from(&head, &sizes, |i, bytes| bytes.copy_from_slice(arrays[i]))
    }

    fn job(text: &str, others: Option<Vec<(String, ProgramText)>>) -> Job {
        let mut setup = Setup::default();
        setup.registers.insert(
            3,
            swarf_interp::Register {
                radius: 2.5,
                ..Default::default()
            },
        );
        Job {
            generation: 9,
            text: ProgramText::from(text.to_string()),
            dialect: Dialect::Fanuc,
            setup,
            others,
            lod: None,
        }
    }

    #[test]
    fn results_states_and_progress_read_back_equal() {
        let main = "G90 G21 G54 // Syntec\nG00 X0 Y0 Z5\nT3 M06\nG04 P500\nG01 Z-1 F100\nG02 X10 Y0 I5 J0\nG81 X5 Y5 Z-3 R1\nG80\nM98 P1234\nM98 P4321\nM30\n";
        let sub = (
            "O1234.nc".to_string(),
            ProgramText::from("O1234\nG01 X$ F100\nM99\n".to_string()),
        );
        let (results, kept) = analyse(job(main, Some(vec![sub])));
        assert!(results.problems.iter().any(|p| p.code == "E-SUBPROGRAM"));
        assert!(!results.elsewhere.is_empty());
        assert!(!results.linked.is_empty());
        assert!(results.hint.is_some());
        assert!(!results.plot.drawing.marks.is_empty());
        assert!(!results.plot.timeline.dwells().is_empty());
        assert_eq!(results.plot.tool_radii.get(&3), Some(&2.5));
        let done = Reply::Done(Box::new(results));
        assert_eq!(again(&done), Some(done));
        let state = kept.state_at(5);
        assert!(state.is_some());
        for state in [None, Some(None), Some(state)] {
            let reply = Reply::State {
                generation: 9,
                line: 5,
                state,
            };
            assert_eq!(again(&reply), Some(reply));
        }
        let progress = Reply::Progress {
            generation: 3,
            progress: Progress::Running {
                reached: 7,
                blocks: 11,
            },
        };
        assert_eq!(again(&progress), Some(progress));
    }

    #[test]
    fn the_path_simplified_reads_back_with_its_level() {
        let text = "G0 X0 Y0\nG1 X1 F100\nG1 X2\nG1 X3 Y0.001\nG1 X4 Y5\nM30\n";
        let mut lod_job = job(text, None);
        lod_job.lod = Some(Some(-2));
        let (results, kept) = analyse(lod_job.clone());
        let lod = results.plot.lod.clone().expect("the job asked for a level");
        assert_eq!(lod.level, Some(-2));
        assert_eq!(*lod.kept, swarf_render::simplify_at(&kept.points, Some(-2)));
        // The collinear feeds merge: fewer points are kept than drawn.
        assert!(lod.kept.len() < kept.points.len());
        let done = Reply::Done(Box::new(results));
        assert_eq!(again(&done), Some(done));
        for kept in [
            None,
            Some(std::sync::Arc::new(vec![0, 3, 5])),
            Some(std::sync::Arc::default()),
        ] {
            let reply = Reply::Lod {
                generation: 9,
                level: None,
                kept,
            };
            assert_eq!(again(&reply), Some(reply));
        }
        let request = Request::Analyse(Box::new(lod_job));
        let (head, texts) = request_parts(&request);
        let texts = texts.iter().map(|t| t.to_owned_string()).collect();
        let Some(Request::Analyse(back)) = request_from(&head, texts) else {
            panic!("not read back");
        };
        assert_eq!(back.lod, Some(Some(-2)));
    }

    #[test]
    fn requests_read_back_with_their_texts() {
        let others = vec![(
            "a.nc".to_string(),
            ProgramText::from("O1\nM99\n".to_string()),
        )];
        let request = Request::Analyse(Box::new(job("G0 X1\n", Some(others))));
        let (head, texts) = request_parts(&request);
        let texts: Vec<String> = texts.iter().map(|t| t.to_owned_string()).collect();
        let Some(Request::Analyse(back)) = request_from(&head, texts) else {
            panic!("not read back");
        };
        let Request::Analyse(sent) = request else {
            unreachable!()
        };
        assert_eq!(back.generation, sent.generation);
        assert_eq!(back.dialect, sent.dialect);
        assert_eq!(back.setup, sent.setup);
        assert_eq!(back.text.to_owned_string(), "G0 X1\n");
        let others = back.others.unwrap();
        assert_eq!(others[0].0, "a.nc");
        assert_eq!(others[0].1.to_owned_string(), "O1\nM99\n");
        let (head, _) = request_parts(&Request::StateAt {
            generation: 4,
            line: 2,
        });
        assert!(matches!(
            request_from(&head, Vec::new()),
            Some(Request::StateAt {
                generation: 4,
                line: 2
            })
        ));
    }

    #[test]
    fn cut_or_foreign_messages_read_as_none() {
        let (results, _) = analyse(job("G0 X1\nG1 X$\n", None));
        let done = Reply::Done(Box::new(results));
        let (head, arrays) = reply_parts(&done);
        let sizes: Vec<usize> = arrays.iter().map(|a| a.len()).collect();
        for cut in 0..head.len() {
            assert!(
                reply_from(&head[..cut], &sizes, |_, _| {}).is_none(),
                "{cut}"
            );
        }
        // An array whose length is not a whole number of its values.
        let mut odd = sizes.clone();
        odd[0] += 1;
        assert!(reply_from(&head, &odd, |_, _| {}).is_none());
        assert!(reply_from(&[7, 1, 2], &[], |_, _| {}).is_none());
        assert!(request_from(&[0, 1], Vec::new()).is_none());
        assert!(request_from(&[], Vec::new()).is_none());
    }
}
