//! Requests and replies as bytes, for a web worker: a short head (numbers, names, messages) and
//! beside it the large parts whole, each in a buffer of its own that is moved, not copied,
//! between the page and the worker (the texts one way, the plot's arrays the other). Reading
//! checks every length: a message cut short or from elsewhere reads as `None`.

use glam::{DVec3, Vec3};
use swarf_interp::{BlockState, Setup};
use swarf_render::Drawing;
use swarf_syntax::{DiagnosticDef, Dialect, LinkedFile, Severity};
use swarf_toolpath::{Dwell, Timeline};

use crate::hint::DialectHint;
use crate::run::{Job, LinkedProblem, Plot, Problem, Progress, Results, Stats};
use crate::service::{Reply, Request};
use crate::stock::{StockCut, StockField};
use crate::text::ProgramText;

/// The head of `request` and the texts that go beside it (the program's, then the other
/// files', in order).
pub fn request_parts(request: &Request) -> (Vec<u8>, Vec<&ProgramText>) {
    let mut w = Writer::default();
    match request {
        Request::Analyse(job) => {
            w.u8(0);
            w.u64(job.generation);
            w.str(job.dialect.name());
            // A setup TOML cannot hold (a NaN) is read as the default one.
            w.str(&job.setup.to_toml().unwrap_or_default());
            let mut texts = vec![&job.text];
            w.option(job.others.as_ref(), |w, others| {
                w.len(others.len());
                for (name, text) in others {
                    w.str(name);
                    texts.push(text);
                }
            });
            (w.0, texts)
        }
        Request::StateAt { generation, line } => {
            w.u8(1);
            w.u64(*generation);
            w.u32(*line);
            (w.0, Vec::new())
        }
        Request::Stock { generation, upto } => {
            w.u8(2);
            w.u64(*generation);
            w.len(*upto);
            (w.0, Vec::new())
        }
    }
}

/// The request of a head and its texts ([`request_parts`]).
pub fn request_from(head: &[u8], texts: Vec<String>) -> Option<Request> {
    let mut r = Reader { bytes: head, at: 0 };
    let request = match r.u8()? {
        0 => {
            let generation = r.u64()?;
            let dialect = r.str()?.parse::<Dialect>().ok()?;
            let setup = Setup::from_toml(&r.str()?).unwrap_or_default();
            let mut texts = texts.into_iter().map(ProgramText::from);
            let text = texts.next()?;
            let others = r.option(|r| r.many(|r| Some((r.str()?, texts.next()?))))?;
            Request::Analyse(Box::new(Job {
                generation,
                text,
                dialect,
                setup,
                others,
            }))
        }
        1 => Request::StateAt {
            generation: r.u64()?,
            line: r.u32()?,
        },
        2 => Request::Stock {
            generation: r.u64()?,
            upto: r.len()?,
        },
        _ => return None,
    };
    r.end().then_some(request)
}

/// The head of `reply` and the arrays that go beside it as bytes (a finished analysis' plot:
/// points, marks, lines, feeds, end times, tools; a cut stock's heights).
pub fn reply_parts(reply: &Reply) -> (Vec<u8>, Vec<&[u8]>) {
    let mut w = Writer::default();
    match reply {
        Reply::Progress {
            generation,
            progress,
        } => {
            w.u8(0);
            w.u64(*generation);
            let (kind, a, b) = match *progress {
                Progress::Reading { read, lines } => (0, read, lines),
                Progress::Running { reached, blocks } => (1, reached, blocks),
            };
            w.u8(kind);
            w.len(a);
            w.len(b);
            (w.0, Vec::new())
        }
        Reply::Done(results) => {
            w.u8(1);
            w.results(results);
            let plot = &results.plot;
            let arrays = vec![
                bytemuck::cast_slice(&plot.drawing.points),
                bytemuck::cast_slice(&plot.drawing.marks),
                bytemuck::cast_slice(&plot.lines),
                bytemuck::cast_slice(&plot.feeds),
                bytemuck::cast_slice(plot.timeline.end_times()),
                bytemuck::cast_slice(&plot.tools),
            ];
            (w.0, arrays)
        }
        Reply::State {
            generation,
            line,
            state,
        } => {
            w.u8(2);
            w.u64(*generation);
            w.u32(*line);
            match state {
                None => w.u8(0),
                Some(None) => w.u8(1),
                Some(Some(s)) => {
                    w.u8(2);
                    w.block_state(s);
                }
            }
            (w.0, Vec::new())
        }
        Reply::Stock(cut) => {
            w.u8(3);
            w.stock_cut(cut);
            let heights = cut.field.iter().map(|f| bytemuck::cast_slice(&f.heights));
            (w.0, heights.collect())
        }
    }
}

/// The reply of a head and its arrays ([`reply_parts`]): `sizes` are the arrays' lengths in
/// bytes, and `fill(i, bytes)` copies array `i` into `bytes` (of that length).
pub fn reply_from(
    head: &[u8],
    sizes: &[usize],
    mut fill: impl FnMut(usize, &mut [u8]),
) -> Option<Reply> {
    let mut r = Reader { bytes: head, at: 0 };
    let reply = match r.u8()? {
        0 => {
            let generation = r.u64()?;
            let kind = r.u8()?;
            let (a, b) = (r.len()?, r.len()?);
            let progress = match kind {
                0 => Progress::Reading { read: a, lines: b },
                1 => Progress::Running {
                    reached: a,
                    blocks: b,
                },
                _ => return None,
            };
            Reply::Progress {
                generation,
                progress,
            }
        }
        1 => {
            let mut results = r.results()?;
            let mut array = Arrays {
                sizes,
                fill: &mut fill,
            };
            let plot = &mut results.plot;
            plot.drawing.points = array.take(0)?;
            plot.drawing.marks = array.take(1)?;
            plot.lines = array.take(2)?;
            plot.feeds = array.take(3)?;
            let dwells = plot.timeline.dwells().to_vec();
            plot.timeline = Timeline::from_parts(array.take(4)?, dwells);
            plot.tools = array.take(5)?;
            Reply::Done(Box::new(results))
        }
        2 => {
            let generation = r.u64()?;
            let line = r.u32()?;
            let state = match r.u8()? {
                0 => None,
                1 => Some(None),
                _ => Some(Some(r.block_state()?)),
            };
            Reply::State {
                generation,
                line,
                state,
            }
        }
        3 => {
            let mut cut = r.stock_cut()?;
            if let Some(field) = &mut cut.field {
                field.heights = Arrays {
                    sizes,
                    fill: &mut fill,
                }
                .take(0)?;
                if field.heights.len() != field.size.0.checked_mul(field.size.1)? {
                    return None;
                }
            }
            Reply::Stock(cut)
        }
        _ => return None,
    };
    r.end().then_some(reply)
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

/// Appends values to a head.
#[derive(Default)]
struct Writer(Vec<u8>);

impl Writer {
    fn u8(&mut self, v: u8) {
        self.0.push(v);
    }

    fn u32(&mut self, v: u32) {
        self.0.extend_from_slice(&v.to_le_bytes());
    }

    fn u64(&mut self, v: u64) {
        self.0.extend_from_slice(&v.to_le_bytes());
    }

    fn len(&mut self, v: usize) {
        self.u64(v as u64);
    }

    fn f32(&mut self, v: f32) {
        self.0.extend_from_slice(&v.to_le_bytes());
    }

    fn f64(&mut self, v: f64) {
        self.0.extend_from_slice(&v.to_le_bytes());
    }

    fn str(&mut self, v: &str) {
        self.len(v.len());
        self.0.extend_from_slice(v.as_bytes());
    }

    fn dvec3(&mut self, v: DVec3) {
        v.to_array().into_iter().for_each(|c| self.f64(c));
    }

    /// 1 and the value written by `write`, or 0 for `None`.
    fn option<T>(&mut self, v: Option<T>, write: impl FnOnce(&mut Self, T)) {
        self.u8(u8::from(v.is_some()));
        if let Some(v) = v {
            write(self, v);
        }
    }

    fn vec3(&mut self, v: Vec3) {
        v.to_array().into_iter().for_each(|c| self.f32(c));
    }

    fn problem(&mut self, p: &Problem) {
        self.u32(p.line);
        self.u32(p.col);
        self.u8(match p.severity {
            Severity::Note => 0,
            Severity::Warning => 1,
            Severity::Error => 2,
        });
        self.str(p.code);
        self.str(&p.message);
        self.len(p.chars.start);
        self.len(p.chars.end);
    }

    /// Everything of `results` but the plot's arrays, and their lengths.
    fn results(&mut self, results: &Results) {
        self.u64(results.generation);
        self.len(results.problems.len());
        results.problems.iter().for_each(|p| self.problem(p));
        self.len(results.elsewhere.len());
        for l in &results.elsewhere {
            self.str(&l.file);
            self.problem(&l.problem);
        }
        let s = &results.stats;
        self.len(s.blocks);
        self.len(s.motions);
        self.option(s.bounds, |w, (min, max)| {
            w.dvec3(min);
            w.dvec3(max);
        });
        self.f64(s.estimated_secs);
        let plot = &results.plot;
        let d = &plot.drawing;
        self.option(d.bounds, |w, (min, max)| {
            w.vec3(min);
            w.vec3(max);
        });
        self.vec3(d.zero);
        self.dvec3(d.origin);
        self.len(plot.timeline.dwells().len());
        for dwell in plot.timeline.dwells() {
            self.len(dwell.segment);
            self.f64(dwell.secs);
        }
        self.len(plot.tool_radii.len());
        for (&n, &r) in &plot.tool_radii {
            self.u32(n);
            self.f32(r);
        }
        self.len(results.linked.len());
        for f in &results.linked {
            self.str(&f.name);
            self.u32(f.first_byte);
            self.u32(f.first_line);
            self.u32(f.len);
            self.u32(f.lines);
        }
        self.option(results.hint.as_ref(), |w, h| {
            w.str(h.from.name());
            w.str(h.to.name());
            w.option(h.first.as_ref(), |w, (what, line)| {
                w.str(what);
                w.u32(*line);
            });
        });
    }

    /// Everything of `cut` but its heights.
    fn stock_cut(&mut self, cut: &StockCut) {
        self.u64(cut.generation);
        self.len(cut.upto);
        self.len(cut.done);
        self.u8(u8::from(cut.whole));
        self.option(cut.field.as_ref(), |w, f| {
            w.len(f.size.0);
            w.len(f.size.1);
            w.f64(f.cell_mm);
            w.dvec3(f.min);
            w.f64(f.top);
        });
        self.len(cut.rapids.len());
        for (segment, [x, y]) in &cut.rapids {
            self.len(*segment);
            self.f64(*x);
            self.f64(*y);
        }
        self.len(cut.problems.len());
        cut.problems.iter().for_each(|p| self.problem(p));
        self.option(cut.error.as_deref(), Self::str);
    }

    fn block_state(&mut self, s: &BlockState) {
        self.len(s.codes.len());
        s.codes.iter().for_each(|c| self.str(c));
        self.dvec3(s.machine);
        self.dvec3(s.work);
        self.str(&s.work_offset_name);
        self.dvec3(s.work_offset);
        self.u32(s.tool);
        self.option(s.length_offset, |w, (h, v)| {
            w.u32(h);
            w.f64(v);
        });
        self.f64(s.feed);
        self.f64(s.spindle_rpm);
        self.u64(s.executed);
    }
}

/// Reads values from a head, each `None` past its end.
struct Reader<'a> {
    bytes: &'a [u8],
    at: usize,
}

impl Reader<'_> {
    fn take<const N: usize>(&mut self) -> Option<[u8; N]> {
        let bytes = self.bytes.get(self.at..self.at.checked_add(N)?)?;
        self.at += N;
        bytes.try_into().ok()
    }

    fn end(&self) -> bool {
        self.at == self.bytes.len()
    }

    fn u8(&mut self) -> Option<u8> {
        Some(self.take::<1>()?[0])
    }

    fn u32(&mut self) -> Option<u32> {
        self.take().map(u32::from_le_bytes)
    }

    fn u64(&mut self) -> Option<u64> {
        self.take().map(u64::from_le_bytes)
    }

    fn len(&mut self) -> Option<usize> {
        usize::try_from(self.u64()?).ok()
    }

    fn f32(&mut self) -> Option<f32> {
        self.take().map(f32::from_le_bytes)
    }

    fn f64(&mut self) -> Option<f64> {
        self.take().map(f64::from_le_bytes)
    }

    fn str(&mut self) -> Option<String> {
        let n = self.len()?;
        let bytes = self.bytes.get(self.at..self.at.checked_add(n)?)?;
        self.at += n;
        String::from_utf8(bytes.to_vec()).ok()
    }

    fn dvec3(&mut self) -> Option<DVec3> {
        Some(DVec3::new(self.f64()?, self.f64()?, self.f64()?))
    }

    fn vec3(&mut self) -> Option<Vec3> {
        Some(Vec3::new(self.f32()?, self.f32()?, self.f32()?))
    }

    /// `None` after a 0, else the value `read` reads.
    fn option<T>(&mut self, read: impl FnOnce(&mut Self) -> Option<T>) -> Option<Option<T>> {
        match self.u8()? {
            0 => Some(None),
            _ => read(self).map(Some),
        }
    }

    /// `n` values read by `read` (a count past what the head holds fails as it runs out).
    fn many<T>(&mut self, mut read: impl FnMut(&mut Self) -> Option<T>) -> Option<Vec<T>> {
        let n = self.len()?;
        let mut out = Vec::with_capacity(n.min(self.bytes.len() - self.at));
        for _ in 0..n {
            out.push(read(self)?);
        }
        Some(out)
    }

    fn problem(&mut self) -> Option<Problem> {
        let line = self.u32()?;
        let col = self.u32()?;
        let severity = match self.u8()? {
            0 => Severity::Note,
            1 => Severity::Warning,
            _ => Severity::Error,
        };
        // Every code is registered; one that is not reads as `?`.
        let code = DiagnosticDef::lookup(&self.str()?).map_or("?", |d| d.code);
        let message = self.str()?;
        let (start, end) = (self.len()?, self.len()?);
        Some(Problem {
            line,
            col,
            severity,
            code,
            message,
            chars: start..end,
        })
    }

    fn results(&mut self) -> Option<Results> {
        let generation = self.u64()?;
        let problems = self.many(Self::problem)?;
        let elsewhere = self.many(|r| {
            Some(LinkedProblem {
                file: r.str()?,
                problem: r.problem()?,
            })
        })?;
        let blocks = self.len()?;
        let motions = self.len()?;
        let bounds = self.option(|r| Some((r.dvec3()?, r.dvec3()?)))?;
        let stats = Stats {
            blocks,
            motions,
            bounds,
            estimated_secs: self.f64()?,
        };
        let bounds = self.option(|r| Some((r.vec3()?, r.vec3()?)))?;
        let drawing = Drawing {
            bounds,
            zero: self.vec3()?,
            origin: self.dvec3()?,
            ..Drawing::default()
        };
        let dwells = self.many(|r| {
            Some(Dwell {
                segment: r.len()?,
                secs: r.f64()?,
            })
        })?;
        let tool_radii = self.many(|r| Some((r.u32()?, r.f32()?)))?;
        let linked = self.many(|r| {
            Some(LinkedFile {
                name: r.str()?,
                first_byte: r.u32()?,
                first_line: r.u32()?,
                len: r.u32()?,
                lines: r.u32()?,
            })
        })?;
        let hint = self.option(|r| {
            Some(DialectHint {
                from: r.str()?.parse().ok()?,
                to: r.str()?.parse().ok()?,
                first: r.option(|r| Some((r.str()?, r.u32()?)))?,
            })
        })?;
        Some(Results {
            generation,
            problems,
            elsewhere,
            stats,
            plot: Plot {
                drawing,
                timeline: Timeline::from_parts(Vec::new(), dwells),
                tool_radii: tool_radii.into_iter().collect(),
                ..Plot::default()
            },
            linked,
            hint,
        })
    }

    fn stock_cut(&mut self) -> Option<Box<StockCut>> {
        let generation = self.u64()?;
        let upto = self.len()?;
        let done = self.len()?;
        let whole = self.u8()? != 0;
        let field = self.option(|r| {
            Some(StockField {
                size: (r.len()?, r.len()?),
                cell_mm: r.f64()?,
                min: r.dvec3()?,
                top: r.f64()?,
                heights: Vec::new(),
            })
        })?;
        let rapids = self.many(|r| Some((r.len()?, [r.f64()?, r.f64()?])))?;
        let problems = self.many(Self::problem)?;
        let error = self.option(Self::str)?;
        Some(Box::new(StockCut {
            generation,
            upto,
            done,
            whole,
            field,
            rapids,
            problems,
            error,
        }))
    }

    fn block_state(&mut self) -> Option<BlockState> {
        Some(BlockState {
            codes: self.many(Self::str)?,
            machine: self.dvec3()?,
            work: self.dvec3()?,
            work_offset_name: self.str()?,
            work_offset: self.dvec3()?,
            tool: self.u32()?,
            length_offset: self.option(|r| Some((r.u32()?, r.f64()?)))?,
            feed: self.f64()?,
            spindle_rpm: self.f64()?,
            executed: self.u64()?,
        })
    }
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]
    use super::*;
    use crate::run::analyse;

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
