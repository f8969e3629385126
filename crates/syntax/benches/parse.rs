#![allow(missing_docs)]
//! Parse throughput: the corpus's big surfacing programs (when `../shared` is present) and a
//! generated 4 MB program. Run with `cargo bench -p swarf-syntax --bench parse`.

#[cfg(not(target_arch = "wasm32"))]
mod surfacing;

#[cfg(not(target_arch = "wasm32"))]
mod native {
    use std::hint::black_box;
    use std::path::Path;

    use criterion::{Criterion, Throughput};
    use swarf_syntax::{Dialect, decode, parse};

    use super::surfacing;

    pub fn parse_throughput(c: &mut Criterion) {
        let mut group = c.benchmark_group("parse");
        group.sample_size(20);
        let corpus = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../../shared/corpus/programs");
        let files = [
            ("la_peinture.gc", corpus.join("camotics/la_peinture.gc")),
            ("stellabee1.ngc", corpus.join("linuxcnc/stellabee1.ngc")),
        ];
        for (name, path) in files {
            let Ok(bytes) = std::fs::read(&path) else {
                eprintln!("skipping {name}: {} not found", path.display());
                continue;
            };
            let text = decode(&bytes).text;
            group.throughput(Throughput::Bytes(text.len() as u64));
            group.bench_function(name, |b| {
                b.iter(|| parse(black_box(&text), Dialect::LinuxCnc));
            });
        }
        let generated = surfacing::surfacing_program(4 << 20);
        group.throughput(Throughput::Bytes(generated.len() as u64));
        group.bench_function("generated-4MB-fanuc", |b| {
            b.iter(|| parse(black_box(&generated), Dialect::Fanuc));
        });
        group.finish();
    }
}

#[cfg(not(target_arch = "wasm32"))]
criterion::criterion_group!(benches, native::parse_throughput);
#[cfg(not(target_arch = "wasm32"))]
criterion::criterion_main!(benches);

#[cfg(target_arch = "wasm32")]
fn main() {}
