//! Requests and replies as bytes for a web worker: a short postcard head, and the large parts
//! (texts, plot arrays) in buffers of their own, moved, not copied, between page and worker.
//! Reading checks every length: a message cut short or from elsewhere reads as `None`.

use serde::{Deserialize, Serialize};
use swarf_interp::Setup;
use swarf_syntax::Dialect;
use swarf_toolpath::Timeline;

use crate::run::{Job, OpenFile};
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
        /// The other open files' names and revisions, and whether their texts follow the
        /// program's, in order (a text the worker holds from the job before is not sent).
        others: Option<Vec<(String, u64, bool)>>,
        lod: Option<crate::LodLevel>,
    },
    /// Any other request, whole.
    Other(Request),
}

/// The head of `request` and the texts that go beside it (the program's, then the other
/// files' that are not among the revisions `held` from the job sent before, which become
/// this job's).
pub fn request_parts<'a>(
    request: &'a Request,
    held: &mut Vec<u64>,
) -> (Vec<u8>, Vec<&'a ProgramText>) {
    let (head, texts) = match request {
        Request::Analyse(job) => {
            let others = job.others.as_deref().unwrap_or_default();
            let sent = |f: &OpenFile| !held.contains(&f.revision);
            let texts = std::iter::once(&job.text);
            let texts = texts.chain(others.iter().filter(|f| sent(f)).map(|f| &f.text));
            let head = RequestHead::Analyse {
                generation: job.generation,
                dialect: job.dialect,
                setup: job.setup.to_toml().unwrap_or_default(),
                others: (job.others.as_ref()).map(|o| {
                    o.iter()
                        .map(|f| (f.name.clone(), f.revision, sent(f)))
                        .collect()
                }),
                lod: job.lod,
            };
            let texts = texts.collect();
            *held = others.iter().map(|f| f.revision).collect();
            (head, texts)
        }
        other => (RequestHead::Other(other.clone()), vec![]),
    };
    (postcard::to_allocvec(&head).unwrap_or_default(), texts)
}

/// The request of a head and its texts ([`request_parts`]); `held` are the other files of
/// the job read before, and become this job's.
pub fn request_from(head: &[u8], texts: Vec<String>, held: &mut Vec<OpenFile>) -> Option<Request> {
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
            let mut file = |(name, revision, sent)| {
                let text = match sent {
                    true => texts.next()?,
                    false => held.iter().find(|f| f.revision == revision)?.text.clone(),
                };
                Some(OpenFile {
                    name,
                    revision,
                    text,
                })
            };
            let others = match others {
                Some(files) => Some(
                    files
                        .into_iter()
                        .map(&mut file)
                        .collect::<Option<Vec<_>>>()?,
                ),
                None => None,
            };
            *held = others.clone().unwrap_or_default();
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

    fn job(text: &str, others: Option<Vec<OpenFile>>) -> Job {
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
        let sub = file("O1234.nc", 1, "O1234\nG01 X$ F100\nM99\n");
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
        let (head, texts) = request_parts(&request, &mut Vec::new());
        let texts = texts.iter().map(|t| t.to_owned_string()).collect();
        let Some(Request::Analyse(back)) = request_from(&head, texts, &mut Vec::new()) else {
            panic!("not read back");
        };
        assert_eq!(back.lod, Some(Some(-2)));
    }

    fn file(name: &str, revision: u64, text: &str) -> OpenFile {
        OpenFile {
            name: name.to_string(),
            revision,
            text: ProgramText::from(text.to_string()),
        }
    }

    /// `request` through its parts and back, with the revisions and files held on each side;
    /// how many texts went beside the head.
    fn sent(
        request: &Request,
        page: &mut Vec<u64>,
        worker: &mut Vec<OpenFile>,
    ) -> (Option<Request>, usize) {
        let (head, texts) = request_parts(request, page);
        let texts: Vec<String> = texts.iter().map(|t| t.to_owned_string()).collect();
        let count = texts.len();
        (request_from(&head, texts, worker), count)
    }

    #[test]
    fn requests_read_back_with_their_texts() {
        let others = vec![file("a.nc", 7, "O1\nM99\n")];
        let request = Request::Analyse(Box::new(job("G0 X1\n", Some(others))));
        let (Some(Request::Analyse(back)), 2) = sent(&request, &mut vec![], &mut vec![]) else {
            panic!("not read back with both texts");
        };
        let Request::Analyse(sent) = request else {
            unreachable!()
        };
        assert_eq!(back.generation, sent.generation);
        assert_eq!(back.dialect, sent.dialect);
        assert_eq!(back.setup, sent.setup);
        assert_eq!(back.text.to_owned_string(), "G0 X1\n");
        let others = back.others.unwrap();
        assert_eq!((others[0].name.as_str(), others[0].revision), ("a.nc", 7));
        assert_eq!(others[0].text.to_owned_string(), "O1\nM99\n");
        let (head, _) = request_parts(
            &Request::StateAt {
                generation: 4,
                line: 2,
            },
            &mut vec![7],
        );
        assert!(matches!(
            request_from(&head, Vec::new(), &mut Vec::new()),
            Some(Request::StateAt {
                generation: 4,
                line: 2
            })
        ));
    }

    #[test]
    fn an_open_file_unchanged_since_the_job_before_is_not_sent_again() {
        let (mut page, mut worker) = (Vec::new(), Vec::new());
        let big = file("O1234.nc", 7, "O1234\nG1 X1 F100\nM99\n");
        let first = job(
            "M98 P1234\nM30\n",
            Some(vec![big.clone(), file("b.nc", 8, "O3\nM99\n")]),
        );
        let (_, count) = sent(&Request::Analyse(Box::new(first)), &mut page, &mut worker);
        assert_eq!((count, page.as_slice()), (3, &[7, 8][..]));
        // A keystroke in the small tab: the other file is held, only the program goes.
        let changed = file("b.nc", 9, "O3\nG0 X2\nM99\n");
        let second = job("M98 P1234\nM30\n", Some(vec![big, changed]));
        let (Some(Request::Analyse(back)), 2) =
            sent(&Request::Analyse(Box::new(second)), &mut page, &mut worker)
        else {
            panic!("the unchanged file was sent again");
        };
        let others = back.others.as_ref().unwrap();
        assert_eq!(others[0].text.to_owned_string(), "O1234\nG1 X1 F100\nM99\n");
        assert_eq!(others[1].text.to_owned_string(), "O3\nG0 X2\nM99\n");
        assert_eq!(page, [7, 9]);
        let (results, _) = analyse(*back);
        assert_eq!(results.linked.len(), 1);
        // A job without open files leaves nothing held; a file the worker lost does not read.
        let (_, count) = sent(
            &Request::Analyse(Box::new(job("M30\n", None))),
            &mut page,
            &mut worker,
        );
        assert_eq!((count, page.len(), worker.len()), (1, 0, 0));
        let again = job("M30\n", Some(vec![file("O1234.nc", 7, "O1234\nM99\n")]));
        let (head, _) = request_parts(&Request::Analyse(Box::new(again)), &mut vec![7]);
        assert!(request_from(&head, vec!["M30\n".to_string()], &mut worker).is_none());
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
        assert!(request_from(&[0, 1], Vec::new(), &mut Vec::new()).is_none());
        assert!(request_from(&[], Vec::new(), &mut Vec::new()).is_none());
    }
}
