//! What `smash run` does by default for a 5.8 M-impact study: 9 design variants (3 CoM heights ×
//! 3 CoM depths) × an 801 × 801 face grid, the default six outputs, CSV long table (and, for
//! comparison, `--format parquet`). Each iteration runs the same library calls as the CLI —
//! summary metrics, sensitivities/optimiser (none here), then the streamed outputs written into
//! a fresh folder — and removes the folder. About 1.0 GB (CSV) are written per iteration, so
//! the group takes a few minutes: `cargo bench --bench study`.

use std::hint::black_box;
use std::path::Path;

use criterion::{criterion_group, criterion_main, Criterion};

use smash::data::write_folder_atomic_with;
use smash::study::output::{write_study, TableFormat};
use smash::study::{finish, parse_study, Prepared};

fn study_text() -> String {
    let club = Path::new(env!("CARGO_MANIFEST_DIR")).join("configs/clubs/paper_driver.toml");
    format!(
        "[study]\nname = \"bench\"\nclub = \"{}\"\n\n[delivery]\nclub_speed_mph = 100.0\n\
         dynamic_loft_deg = 12.0\n\n[grid]\ny_mm = {{ from = -25.0, to = 25.0, count = 801 }}\n\
         z_mm = {{ from = -40.0, to = 40.0, count = 801 }}\n\n[design]\n\
         com_dx_mm = [-5.0, 0.0, 5.0]\ncom_dy_mm = [-3.0, 0.0, 3.0]\n",
        club.display().to_string().replace('\\', "/")
    )
}

/// The CLI's unsharded `smash run` after parsing: returns the number of files written.
fn run(p: &Prepared, dir: &Path, format: TableFormat) -> usize {
    let metrics = p.all_metrics();
    let (sens, opt) = finish(p, &metrics).unwrap();
    let kernels = p.kernels();
    write_folder_atomic_with(dir, "study.toml", |tmp| {
        write_study(tmp, p, &kernels, &metrics, &sens, opt.as_ref(), format)
    })
    .unwrap()
}

fn bench(c: &mut Criterion) {
    let study = parse_study(Path::new("bench.toml"), &study_text()).unwrap();
    let p = Prepared::new(study).unwrap();
    let base = tempfile::tempdir().unwrap();
    let mut g = c.benchmark_group("study_9x801x801");
    g.sample_size(10);
    g.measurement_time(std::time::Duration::from_secs(20));
    for (name, format) in [("csv", TableFormat::Csv), ("parquet", TableFormat::Parquet)] {
        let dir = base.path().join(name);
        g.bench_function(
            format!("smash run, default outputs, {name} long table"),
            |b| {
                b.iter(|| {
                    let n = run(black_box(&p), &dir, format);
                    std::fs::remove_dir_all(&dir).unwrap();
                    n
                })
            },
        );
    }
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
