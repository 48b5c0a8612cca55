//! `smash merge`: the shard folders read back and checked (every field, every hash, every work
//! item exactly once), their face maps into a scratch file served a band at a time.

use std::path::{Path, PathBuf};

use crate::data::{escape, quote_cell, read_text, DataError};
use crate::sweep::kernel::LaunchGrid;

use super::super::metrics::metric_names;
use super::super::spec::parse_study;
use super::super::sweep::Prepared;
use super::super::StudyError;
use super::fields::{csv_records, index, launch_value, next_record, num};
use super::scratch::{DiskGrids, ScratchWriter};
use super::{check_mergeable, club_sha256, sha256_hex, Hashed, MergeError, ROWS_HEADER};

/// The fields of a `shard.toml`, each checked.
struct ShardMeta {
    shard: usize,
    shards: usize,
    first_item: usize,
    end_item: usize,
    study_sha256: String,
    club_sha256: String,
}

fn read_meta(path: &Path) -> Result<ShardMeta, DataError> {
    let text = read_text(path)?;
    let table: toml::Table = toml::from_str(&text).map_err(|e| {
        DataError::file(
            path,
            format!("not a shard.toml: {}", escape(e.message().trim())),
        )
    })?;
    let int = |key: &str| -> Result<usize, DataError> {
        match table.get(key) {
            Some(toml::Value::Integer(i)) if *i >= 0 => usize::try_from(*i).map_err(|_| {
                DataError::file(path, format!("`{key}` = {i} is too large for this machine"))
            }),
            _ => Err(DataError::file(
                path,
                format!("missing or bad `{key}` (a non-negative integer)"),
            )),
        }
    };
    let hash = |key: &str| -> Result<String, DataError> {
        match table.get(key) {
            Some(toml::Value::String(h))
                if h.len() == 64 && h.bytes().all(|b| b.is_ascii_hexdigit()) =>
            {
                Ok(h.to_ascii_lowercase())
            }
            Some(_) => Err(DataError::file(
                path,
                format!("`{key}` must be 64 hex digits (a SHA-256)"),
            )),
            None => Err(DataError::file(
                path,
                format!(
                    "no `{key}`: the shard was written by an older smash that did not record \
                     which study and club it belongs to; run the shards again"
                ),
            )),
        }
    };
    let meta = ShardMeta {
        shard: int("shard")?,
        shards: int("shards")?,
        first_item: int("first_item")?,
        end_item: int("end_item")?,
        study_sha256: hash("study_sha256")?,
        club_sha256: hash("club_sha256")?,
    };
    if meta.shards == 0 {
        return Err(DataError::file(
            path,
            "`shards` = 0: a study is split into at least 1 shard",
        ));
    }
    if meta.shard >= meta.shards {
        return Err(DataError::file(
            path,
            format!(
                "`shard` = {} with `shards` = {}: shards are numbered 0 to {}",
                meta.shard,
                meta.shards,
                meta.shards - 1
            ),
        ));
    }
    Ok(meta)
}

/// Read the shard folders: the study, each variant's summary metrics, and the face maps into
/// the scratch file `scratch` (see [`DiskGrids`]; a few MB of memory whatever the study). The
/// shards must record the same study and club hashes, which must also match the study and club
/// files as they are now, and must cover the study's work items exactly once.
pub fn merge_shards(
    dirs: &[PathBuf],
    scratch: &Path,
) -> Result<(Prepared, Vec<Vec<f64>>, DiskGrids), StudyError> {
    let first = dirs.first().ok_or(MergeError::NoShards)?;
    let metas = dirs
        .iter()
        .map(|d| read_meta(&d.join("shard.toml")))
        .collect::<Result<Vec<_>, _>>()?;
    let p = read_merged_study(dirs, &metas)?;
    check_mergeable(&p)?;
    let n = metas[0].shards;
    let mut cover = Coverage {
        seen_shards: Vec::new(),
        seen_items: vec![false; p.work_len()],
        per: p.items_per_variant(),
    };
    let mut metrics: Vec<Vec<f64>> = vec![Vec::new(); p.variants.len()];
    let mut out = ScratchWriter::create(scratch, &p)?;
    for (d, m) in dirs.iter().zip(&metas) {
        cover.check_shard(&p, d, m, first, n)?;
        read_rows(&d.join("rows.csv"), &p, &mut cover, &mut out)?;
        read_metrics(&d.join("metrics.csv"), &p, &mut cover, &mut metrics)?;
    }
    cover.check_complete(n)?;
    Ok((p, metrics, out.finish()?))
}

/// The study the shards record, checked: the same hashes in every `shard.toml`, every
/// `study.toml` the one recorded, the club file unchanged since.
fn read_merged_study(dirs: &[PathBuf], metas: &[ShardMeta]) -> Result<Prepared, StudyError> {
    let first = &dirs[0];
    for (d, m) in dirs.iter().zip(metas).skip(1) {
        for (what, a, b) in [
            (Hashed::Study, &metas[0].study_sha256, &m.study_sha256),
            (Hashed::Club, &metas[0].club_sha256, &m.club_sha256),
        ] {
            if a != b {
                return Err(MergeError::Differ {
                    first: first.clone(),
                    other: d.clone(),
                    what,
                    first_sha: a.clone(),
                    other_sha: b.clone(),
                }
                .into());
            }
        }
    }
    let study_path = first.join("study.toml");
    let study_text = read_text(&study_path)?;
    for d in dirs {
        let t = read_text(&d.join("study.toml"))?;
        if sha256_hex(t.as_bytes()) != metas[0].study_sha256 {
            return Err(MergeError::StudyEdited { dir: d.clone() }.into());
        }
    }
    let p = Prepared::new(parse_study(&study_path, &study_text)?)?;
    let club_now = club_sha256(&p)?;
    if club_now != metas[0].club_sha256 {
        return Err(MergeError::ClubChanged {
            club: p.study.club_path.clone(),
            now: club_now,
            recorded: metas[0].club_sha256.clone(),
        }
        .into());
    }
    Ok(p)
}

/// Which shards and work items have been read.
struct Coverage {
    seen_shards: Vec<usize>,
    seen_items: Vec<bool>,
    /// Work items per variant.
    per: usize,
}

impl Coverage {
    /// Shard `d` (its `shard.toml` read into `m`) is of the same split as the first, not given
    /// before, and holds the work items of its index.
    fn check_shard(
        &mut self,
        p: &Prepared,
        d: &Path,
        m: &ShardMeta,
        first: &Path,
        n: usize,
    ) -> Result<(), MergeError> {
        let file = d.join("shard.toml");
        let k = m.shard;
        if m.shards != n {
            return Err(MergeError::ShardCount {
                file,
                shards: m.shards,
                first: first.to_owned(),
                expected: n,
            });
        }
        if self.seen_shards.contains(&k) {
            return Err(MergeError::Duplicate {
                shard: k,
                dir: d.to_owned(),
            });
        }
        self.seen_shards.push(k);
        let t = p.work_len() as u128;
        let expected = (k as u128 * t / n as u128, (k as u128 + 1) * t / n as u128);
        if (m.first_item as u128, m.end_item as u128) != expected {
            return Err(MergeError::WrongItems {
                file,
                first_item: m.first_item,
                end_item: m.end_item,
                shard: k,
                shards: n,
                expected,
            });
        }
        Ok(())
    }

    /// Work item `item` read from `file` at `line`: an error if read before.
    fn mark(&mut self, file: &Path, line: u64, item: usize) -> Result<(), MergeError> {
        if self.seen_items[item] {
            return Err(MergeError::ItemTwice {
                file: file.to_owned(),
                line,
                item,
            });
        }
        self.seen_items[item] = true;
        Ok(())
    }

    /// Every shard of `n` and every work item was read.
    fn check_complete(&self, n: usize) -> Result<(), MergeError> {
        if self.seen_shards.len() != n {
            let missing: Vec<usize> = (0..n)
                .filter(|k| !self.seen_shards.contains(k))
                .take(10)
                .collect();
            return Err(MergeError::MissingShards {
                more: n - self.seen_shards.len() > missing.len(),
                missing,
                shards: n,
            });
        }
        if let Some(item) = self.seen_items.iter().position(|s| !s) {
            return Err(MergeError::MissingItem {
                item,
                variant: item / self.per,
            });
        }
        Ok(())
    }
}

/// A grid row being read from `rows.csv`: variant, row, its points, how many were given, and
/// the line of the last.
struct RowBuf {
    variant: usize,
    row: usize,
    grid: LaunchGrid,
    filled: usize,
    line: u64,
}

/// The grid rows of one shard's `rows.csv` into `out`, each a work item marked in `cover`.
fn read_rows(
    rp: &Path,
    p: &Prepared,
    cover: &mut Coverage,
    out: &mut ScratchWriter,
) -> Result<(), StudyError> {
    let (nv, ny, nz) = (p.variants.len(), p.ys_mm.len(), p.zs_mm.len());
    crate::data::safe_write::note_input(rp);
    let rf =
        std::fs::File::open(rp).map_err(|e| DataError::file(rp, format!("cannot read: {e}")))?;
    let mut reader = csv_records(
        rp,
        std::io::BufReader::with_capacity(1 << 20, rf),
        ROWS_HEADER,
    )?;
    let mut current: Option<RowBuf> = None;
    let mut flush = |cur: Option<RowBuf>| -> Result<(), StudyError> {
        let Some(b) = cur else { return Ok(()) };
        if b.filled != nz {
            return Err(MergeError::ShortRow {
                file: rp.to_owned(),
                line: b.line,
                variant: b.variant,
                row: b.row,
                points: b.filled,
                nz,
            }
            .into());
        }
        cover.mark(rp, b.line, b.variant * cover.per + b.row + 1)?;
        out.put_row(b.variant, b.row, &b.grid)?;
        Ok(())
    };
    let mut f = csv::StringRecord::new();
    while let Some(ln) = next_record(rp, &mut reader, &mut f)? {
        let (v, r, c) = (
            index(rp, ln, "variant", &f[0], nv, "variants")?,
            index(rp, ln, "row", &f[1], ny, "grid rows")?,
            index(rp, ln, "col", &f[2], nz, "grid columns")?,
        );
        if current
            .as_ref()
            .is_none_or(|x| x.variant != v || x.row != r)
        {
            flush(current.take())?;
            current = Some(RowBuf {
                variant: v,
                row: r,
                grid: LaunchGrid::with_len(nz),
                filled: 0,
                line: ln,
            });
        }
        let cur = current.as_mut().expect("set above");
        read_point(rp, ln, &f, c, cur)?;
    }
    flush(current.take())
}

/// Point `c` of the row being read, from the record `f` at line `ln`.
fn read_point(
    rp: &Path,
    ln: u64,
    f: &csv::StringRecord,
    c: usize,
    cur: &mut RowBuf,
) -> Result<(), DataError> {
    if c != cur.filled {
        return Err(DataError::at(
            rp,
            Some(ln as usize),
            Some("column col".into()),
            format!(
                "expected column {} of {}, got {c}",
                cur.filled,
                cur.grid.len()
            ),
        ));
    }
    let g = &mut cur.grid;
    g.valid[c] = match &f[3] {
        "1" => true,
        "0" => false,
        other => {
            return Err(DataError::at(
                rp,
                Some(ln as usize),
                Some("column valid".into()),
                format!("must be 0 or 1, got {}", quote_cell(other)),
            ))
        }
    };
    let valid = g.valid[c];
    let value = |col: &str, s: &str| launch_value(rp, ln, col, s, valid);
    g.ball_speed_m_s[c] = value("ball_speed_m_s", &f[4])?;
    g.launch_angle_rad[c] = value("launch_angle_rad", &f[5])?;
    g.azimuth_rad[c] = value("azimuth_rad", &f[6])?;
    g.backspin_rad_s[c] = value("backspin_rad_s", &f[7])?;
    g.sidespin_rad_s[c] = value("sidespin_rad_s", &f[8])?;
    cur.filled += 1;
    cur.line = ln;
    Ok(())
}

/// The summary metrics of one shard's `metrics.csv` into `metrics`, each variant's a work item
/// marked in `cover`.
fn read_metrics(
    mp: &Path,
    p: &Prepared,
    cover: &mut Coverage,
    metrics: &mut [Vec<f64>],
) -> Result<(), StudyError> {
    let names = metric_names(p.study.distribution.is_some());
    let mt = read_text(mp)?;
    let mut reader = csv_records(mp, mt.as_bytes(), "variant,metric,value")?;
    // Variant, its values, the line of its last.
    let mut cur: Option<(usize, Vec<f64>, u64)> = None;
    let mut push = |cur: Option<(usize, Vec<f64>, u64)>| -> Result<(), MergeError> {
        let Some((variant, values, line)) = cur else {
            return Ok(());
        };
        if values.len() != names.len() {
            return Err(MergeError::MetricCount {
                file: mp.to_owned(),
                variant,
                got: values.len(),
                expected: names.len(),
            });
        }
        cover.mark(mp, line, variant * cover.per)?;
        metrics[variant] = values;
        Ok(())
    };
    let mut f = csv::StringRecord::new();
    while let Some(ln) = next_record(mp, &mut reader, &mut f)? {
        let v = index(mp, ln, "variant", &f[0], p.variants.len(), "variants")?;
        if cur.as_ref().is_none_or(|c| c.0 != v) {
            push(cur.take())?;
            cur = Some((v, Vec::new(), ln));
        }
        let c = cur.as_mut().expect("set above");
        if names.get(c.1.len()).map(String::as_str) != Some(&f[1]) {
            return Err(DataError::at(
                mp,
                Some(ln as usize),
                Some("column metric".into()),
                match names.get(c.1.len()) {
                    Some(want) => format!("expected metric {want}, got {}", quote_cell(&f[1])),
                    None => format!(
                        "variant {v} has more than the study's {} metrics",
                        names.len()
                    ),
                },
            )
            .into());
        }
        c.1.push(num(mp, ln, "value", &f[2])?);
        c.2 = ln;
    }
    Ok(push(cur.take())?)
}

#[cfg(test)]
mod tests {
    use super::super::shard_files;
    use super::*;

    /// A 2-variant 3 × 4 study, split in two shards written under `dir`.
    fn shards(dir: &Path) -> Vec<PathBuf> {
        let club = Path::new(env!("CARGO_MANIFEST_DIR")).join("configs/clubs/paper_driver.toml");
        let text = format!(
            "[study]\nname = \"m\"\nclub = \"{}\"\n\n[delivery]\nclub_speed_mph = 100.0\n\
             dynamic_loft_deg = 12.0\n\n[grid]\ny_mm = {{ from = -5.0, to = 5.0, count = 3 }}\n\
             z_mm = {{ from = -6.0, to = 6.0, count = 4 }}\n\n[design]\ncom_dx_mm = [-1.0, 1.0]\n",
            club.display().to_string().replace('\\', "/")
        );
        let p = Prepared::new(parse_study(Path::new("m.toml"), &text).unwrap()).unwrap();
        (0..2)
            .map(|k| {
                let d = dir.join(format!("s{k}"));
                std::fs::create_dir_all(&d).unwrap();
                let items = p.compute(p.shard_range(k, 2), &|| ());
                for (rel, bytes) in shard_files(&p, k, 2, &items).unwrap() {
                    std::fs::write(d.join(rel), bytes).unwrap();
                }
                d
            })
            .collect()
    }

    fn merge_error(dirs: &[PathBuf], scratch: &Path) -> MergeError {
        match merge_shards(dirs, scratch) {
            Err(StudyError::Merge(e)) => e,
            Err(other) => panic!("not a merge error: {other}"),
            Ok(_) => panic!("merged"),
        }
    }

    #[test]
    fn merge_errors_name_the_file_the_line_and_what_mismatched() {
        let dir = tempfile::tempdir().unwrap();
        let dirs = shards(dir.path());
        let scratch = dir.path().join("scratch");
        assert!(merge_shards(&dirs, &scratch).is_ok());
        assert!(!scratch.exists(), "the scratch file is removed");

        // Shard 0 twice, shard 1 missing.
        let e = merge_error(&[dirs[0].clone(), dirs[0].clone()], &scratch);
        assert_eq!(
            e,
            MergeError::Duplicate {
                shard: 0,
                dir: dirs[0].clone()
            }
        );
        let e = merge_error(&dirs[..1], &scratch);
        assert!(
            matches!(e, MergeError::MissingShards { ref missing, shards: 2, more: false } if missing == &[1])
        );

        // The last point of a row removed from shard 1's rows.csv: the row is short, at the
        // line of its last point.
        let rows = dirs[1].join("rows.csv");
        let text = std::fs::read_to_string(&rows).unwrap();
        let mut lines: Vec<&str> = text.lines().collect();
        // Variant 1, row 0, column 3 (the last).
        let cut = lines.iter().position(|l| l.starts_with("1,0,3,")).unwrap();
        lines.remove(cut);
        std::fs::write(&rows, lines.join("\n") + "\n").unwrap();
        let e = merge_error(&dirs, &scratch);
        let MergeError::ShortRow {
            file,
            line,
            points,
            nz,
            ..
        } = &e
        else {
            panic!("{e}")
        };
        assert_eq!((file, *line, *points, *nz), (&rows, cut as u64, 3, 4));
        assert!(e
            .to_string()
            .starts_with(&format!("{}:{cut}: ", rows.display())));
        assert!(
            !scratch.exists(),
            "the scratch file is removed after an error"
        );
    }
}
