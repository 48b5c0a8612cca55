//! Shards: a part of a study's work list written to disk, and their merge.
//!
//! A shard folder holds `study.toml` (the resolved study, identical for every shard and for the
//! unsharded run), `shard.toml` (`shard`, `shards`, `first_item`, `end_item`), `rows.csv` (the
//! shard's grid rows: `variant,row,col,valid` and the five launch components in SI units) and
//! `metrics.csv` (`variant,metric,value`). `shard.toml` also records the SHA-256 of the resolved
//! study and of the club file; merge refuses shards that disagree, or that disagree with the
//! files as they are now, and checks every field it reads back. Values are written in their shortest round-trip
//! decimal form, so reading them back gives the same bits; invalid values are empty cells.

use std::fmt::Write as _;
use std::io::Write as _;
use std::path::{Path, PathBuf};

use crate::data::{escape, read_text, DataError};
use crate::sweep::kernel::LaunchGrid;

use super::metrics::metric_names;
use super::output::{cell, Files};
use super::spec::{parse_study, resolved_toml};
use super::sweep::{GridSource, ItemResult, Prepared};
use super::StudyError;

const ROWS_HEADER: &str =
    "variant,row,col,valid,ball_speed_m_s,launch_angle_rad,azimuth_rad,backspin_rad_s,sidespin_rad_s";

/// Parse `k/N` (0-based `k < N`).
pub fn parse_shard_spec(s: &str) -> Result<(usize, usize), String> {
    let err = || {
        format!("--shard '{s}': expected k/N with 0 ≤ k < N, e.g. 0/4 (k is 0-based, as $SLURM_ARRAY_TASK_ID)")
    };
    let (a, b) = s.split_once('/').ok_or_else(err)?;
    let k: usize = a.trim().parse().map_err(|_| err())?;
    let n: usize = b.trim().parse().map_err(|_| err())?;
    if n == 0 || k >= n {
        return Err(err());
    }
    Ok((k, n))
}

/// SHA-256 of `bytes`, as 64 lowercase hex digits (what `sha256sum` prints).
pub fn sha256_hex(bytes: &[u8]) -> String {
    use sha2::Digest;
    sha2::Sha256::digest(bytes)
        .iter()
        .fold(String::with_capacity(64), |mut s, b| {
            let _ = write!(s, "{b:02x}");
            s
        })
}

/// SHA-256 of the study's club file as it is now.
fn club_sha256(p: &Prepared) -> Result<String, StudyError> {
    let path = &p.study.club_path;
    let bytes = std::fs::read(path)
        .map_err(|e| DataError::file(path, format!("cannot read the study's club file: {e}")))?;
    Ok(sha256_hex(&bytes))
}

/// Files of shard `k` of `n` holding `items`. `shard.toml` records the SHA-256 of the resolved
/// study (`study.toml` as written) and of the club file, so that `smash merge` can prove the
/// shards belong together.
pub fn shard_files(
    p: &Prepared,
    k: usize,
    n: usize,
    items: &[ItemResult],
) -> Result<Files, StudyError> {
    let range = p.shard_range(k, n);
    let study = resolved_toml(&p.study);
    let mut meta = String::new();
    let _ = writeln!(
        meta,
        "# Shard of a study; merge all shards with `smash merge`."
    );
    let _ = writeln!(
        meta,
        "shard = {k}\nshards = {n}\nfirst_item = {}\nend_item = {}",
        range.start, range.end
    );
    let _ = writeln!(
        meta,
        "# SHA-256 of study.toml and of the club file it names (compare with `sha256sum`)."
    );
    let _ = writeln!(
        meta,
        "study_sha256 = \"{}\"\nclub_sha256 = \"{}\"",
        sha256_hex(study.as_bytes()),
        club_sha256(p)?
    );
    let mut rows = format!("{ROWS_HEADER}\n");
    let mut metrics = String::from("variant,metric,value\n");
    let names = metric_names(p.study.distribution.is_some());
    for it in items {
        match it {
            ItemResult::Row { variant, row, grid } => {
                for j in 0..grid.len() {
                    let _ = writeln!(
                        rows,
                        "{variant},{row},{j},{},{},{},{},{},{}",
                        u8::from(grid.valid[j]),
                        cell(grid.ball_speed_m_s[j]),
                        cell(grid.launch_angle_rad[j]),
                        cell(grid.azimuth_rad[j]),
                        cell(grid.backspin_rad_s[j]),
                        cell(grid.sidespin_rad_s[j]),
                    );
                }
            }
            ItemResult::Metrics { variant, values } => {
                for (name, v) in names.iter().zip(values) {
                    let _ = writeln!(metrics, "{variant},{name},{}", cell(*v));
                }
            }
        }
    }
    Ok(vec![
        ("study.toml".into(), study.into_bytes()),
        ("shard.toml".into(), meta.into_bytes()),
        ("rows.csv".into(), rows.into_bytes()),
        ("metrics.csv".into(), metrics.into_bytes()),
    ])
}

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

/// `value` of `col` on `line` as an index below `limit` (what it counts is `what`).
fn index(
    path: &Path,
    line: u64,
    col: &str,
    s: &str,
    limit: usize,
    what: &str,
) -> Result<usize, DataError> {
    let at = |m: String| DataError::at(path, Some(line as usize), Some(format!("column {col}")), m);
    let v = s
        .parse::<usize>()
        .map_err(|_| at(format!("not an index: '{}'", escape(s))))?;
    if v >= limit {
        return Err(at(format!(
            "{v} is outside the study: it has {limit} {what} (0 to {})",
            limit.saturating_sub(1)
        )));
    }
    Ok(v)
}

fn num(path: &Path, line: u64, col: &str, s: &str) -> Result<f64, DataError> {
    if s.is_empty() {
        return Ok(f64::NAN);
    }
    s.parse::<f64>()
        .ok()
        .filter(|v| v.is_finite())
        .ok_or_else(|| {
            DataError::at(
                path,
                Some(line as usize),
                Some(format!("column {col}")),
                format!("not a finite number: '{}'", escape(s)),
            )
        })
}

/// A CSV reader over `text` whose header must be exactly `header`; records must have as many
/// fields.
fn csv_records<R: std::io::Read>(
    path: &Path,
    input: R,
    header: &str,
) -> Result<csv::Reader<R>, DataError> {
    let mut r = csv::ReaderBuilder::new()
        .has_headers(true)
        .from_reader(input);
    let h = r
        .headers()
        .map_err(|e| DataError::at(path, Some(1), None, format!("cannot read the header: {e}")))?;
    if h.iter().collect::<Vec<_>>().join(",") != header {
        return Err(DataError::at(
            path,
            Some(1),
            None,
            format!("header must be {header}"),
        ));
    }
    Ok(r)
}

fn csv_error(path: &Path, e: &csv::Error) -> DataError {
    let line = e.position().map(|p| p.line() as usize);
    let msg = match e.kind() {
        csv::ErrorKind::UnequalLengths {
            expected_len, len, ..
        } => format!("{len} fields, expected {expected_len}"),
        _ => escape(&e.to_string()).into_owned(),
    };
    DataError::at(path, line, None, msg)
}

/// The face maps of a merged study, read back from the shards into a binary scratch file (one
/// fixed-size record per variant and grid row: the five launch components in SI units as
/// little-endian `f64`, then the validity bytes) and served a band at a time to
/// [`super::output::write_study`]: the merge's memory does not grow with the study. The scratch
/// file is removed when this is dropped.
pub struct DiskGrids {
    file: std::sync::Mutex<std::fs::File>,
    path: PathBuf,
    ny: usize,
    nz: usize,
}

impl DiskGrids {
    /// Bytes of one grid row's record.
    fn record(nz: usize) -> usize {
        nz * (5 * 8 + 1)
    }
}

impl Drop for DiskGrids {
    fn drop(&mut self) {
        let _ = std::fs::remove_file(&self.path);
    }
}

impl GridSource for DiskGrids {
    fn grid_rows(
        &self,
        variant: usize,
        rows: std::ops::Range<usize>,
        out: &mut LaunchGrid,
    ) -> std::io::Result<()> {
        use std::io::{Read, Seek, SeekFrom};
        let (nz, rec) = (self.nz, Self::record(self.nz));
        let mut bytes = vec![0u8; rows.len() * rec];
        {
            let mut f = self.file.lock().unwrap_or_else(|e| e.into_inner());
            f.seek(SeekFrom::Start(
                ((variant * self.ny + rows.start) * rec) as u64,
            ))
            .and_then(|_| f.read_exact(&mut bytes))
            .map_err(|e| {
                std::io::Error::new(
                    e.kind(),
                    format!("{}: cannot read back: {e}", self.path.display()),
                )
            })?;
        }
        *out = LaunchGrid::with_len(0);
        for r in bytes.chunks_exact(rec) {
            let comp = |k: usize| {
                r[k * 8 * nz..(k + 1) * 8 * nz]
                    .chunks_exact(8)
                    .map(|b| f64::from_le_bytes(b.try_into().expect("8 bytes")))
            };
            out.ball_speed_m_s.extend(comp(0));
            out.launch_angle_rad.extend(comp(1));
            out.azimuth_rad.extend(comp(2));
            out.backspin_rad_s.extend(comp(3));
            out.sidespin_rad_s.extend(comp(4));
            out.valid.extend(r[40 * nz..].iter().map(|&b| b == 1));
        }
        Ok(())
    }
}

/// Read the shard folders: the study, each variant's summary metrics, and the face maps into
/// the scratch file `scratch` (see [`DiskGrids`]; a few MB of memory whatever the study). The
/// shards must record the same study and club hashes, which must also match the study and club
/// files as they are now, and must cover the study's work items exactly once.
pub fn merge_shards(
    dirs: &[PathBuf],
    scratch: &Path,
) -> Result<(Prepared, Vec<Vec<f64>>, DiskGrids), StudyError> {
    let first = dirs
        .first()
        .ok_or_else(|| StudyError::Merge("no shard folders given".into()))?;
    let metas = dirs
        .iter()
        .map(|d| read_meta(&d.join("shard.toml")))
        .collect::<Result<Vec<_>, _>>()?;
    for (d, m) in dirs.iter().zip(&metas).skip(1) {
        for (what, a, b) in [
            ("studies", &metas[0].study_sha256, &m.study_sha256),
            ("club files", &metas[0].club_sha256, &m.club_sha256),
        ] {
            if a != b {
                return Err(StudyError::Merge(format!(
                    "{} and {} were computed with different {what} (SHA-256 {}… and {}… in \
                     their shard.toml); run all shards again with the same study and club",
                    first.display(),
                    d.display(),
                    &a[..12],
                    &b[..12]
                )));
            }
        }
    }
    let study_path = first.join("study.toml");
    let study_text = read_text(&study_path)?;
    for d in dirs {
        let t = read_text(&d.join("study.toml"))?;
        if sha256_hex(t.as_bytes()) != metas[0].study_sha256 {
            return Err(StudyError::Merge(format!(
                "{}: study.toml is not the study its shard.toml records (edited after the run?); \
                 run the shard again",
                d.display()
            )));
        }
    }
    let study = parse_study(&study_path, &study_text)?;
    let p = Prepared::new(study)?;
    let club_now = club_sha256(&p)?;
    if club_now != metas[0].club_sha256 {
        return Err(StudyError::Merge(format!(
            "the club file {} changed since the shards were computed (SHA-256 now {}…, in the \
             shards {}…); run the shards again",
            p.study.club_path.display(),
            &club_now[..12],
            &metas[0].club_sha256[..12]
        )));
    }
    let n = metas[0].shards;
    let mut seen: Vec<usize> = Vec::new();
    let names = metric_names(p.study.distribution.is_some());
    let (nv, ny, nz) = (p.variants.len(), p.ys_mm.len(), p.zs_mm.len());
    check_mergeable(&p)?;
    let per = p.items_per_variant();
    let mut seen_items = vec![false; p.work_len()];
    let mut metrics: Vec<Vec<f64>> = vec![Vec::new(); nv];
    // The scratch file, sized for every grid row; each row is written at its place.
    let scratch_err = |e: std::io::Error| DataError::file(scratch, format!("cannot write: {e}"));
    let mut guard = ScratchGuard(None);
    let file = std::fs::OpenOptions::new()
        .read(true)
        .write(true)
        .create(true)
        .truncate(true)
        .open(scratch)
        .map_err(scratch_err)?;
    guard.0 = Some(scratch.to_path_buf());
    let rec = DiskGrids::record(nz);
    file.set_len((nv * ny * rec) as u64).map_err(scratch_err)?;
    let mut scratch_file = std::io::BufWriter::with_capacity(1 << 20, file);
    let mut at_byte = 0u64;
    let mut record = Vec::with_capacity(rec);
    let mut put_row = |at: usize, g: &LaunchGrid| -> Result<(), StudyError> {
        use std::io::{Seek, SeekFrom};
        record.clear();
        for c in [
            &g.ball_speed_m_s,
            &g.launch_angle_rad,
            &g.azimuth_rad,
            &g.backspin_rad_s,
            &g.sidespin_rad_s,
        ] {
            for v in c {
                record.extend_from_slice(&v.to_le_bytes());
            }
        }
        record.extend(g.valid.iter().map(|&b| u8::from(b)));
        let pos = (at * rec) as u64;
        // Rows arrive in order within a shard: seek only when they jump.
        if at_byte != pos {
            scratch_file
                .seek(SeekFrom::Start(pos))
                .map_err(scratch_err)?;
        }
        scratch_file.write_all(&record).map_err(scratch_err)?;
        at_byte = pos + rec as u64;
        Ok(())
    };
    for (d, m) in dirs.iter().zip(&metas) {
        let mp = d.join("shard.toml");
        let k = m.shard;
        if m.shards != n {
            return Err(StudyError::Merge(format!(
                "{}: shard of {}, {} is of {n}",
                mp.display(),
                m.shards,
                first.display()
            )));
        }
        if seen.contains(&k) {
            return Err(StudyError::Merge(format!(
                "shard {k} is given twice ({})",
                d.display()
            )));
        }
        seen.push(k);
        let t = p.work_len() as u128;
        let want = (
            (k as u128 * t / n as u128),
            ((k as u128 + 1) * t / n as u128),
        );
        if (m.first_item as u128, m.end_item as u128) != want {
            return Err(StudyError::Merge(format!(
                "{}: work items {}..{} are not those of shard {k} of {n} ({}..{})",
                mp.display(),
                m.first_item,
                m.end_item,
                want.0,
                want.1
            )));
        }

        let rp = d.join("rows.csv");
        let rf = std::fs::File::open(&rp)
            .map_err(|e| DataError::file(&rp, format!("cannot read: {e}")))?;
        let mut reader = csv_records(
            &rp,
            std::io::BufReader::with_capacity(1 << 20, rf),
            ROWS_HEADER,
        )?;
        let mut current: Option<(usize, usize, LaunchGrid, usize)> = None;
        let mut flush = |cur: Option<(usize, usize, LaunchGrid, usize)>| -> Result<(), StudyError> {
            if let Some((variant, row, grid, filled)) = cur {
                if filled != nz {
                    return Err(StudyError::Merge(format!(
                        "{}: variant {variant} row {row} has {filled} of {nz} points",
                        rp.display()
                    )));
                }
                let idx = variant * per + row + 1;
                if seen_items[idx] {
                    return Err(StudyError::Merge(format!("work item {idx} appears twice")));
                }
                seen_items[idx] = true;
                put_row(variant * ny + row, &grid)?;
            }
            Ok(())
        };
        for rec in reader.records() {
            let f = rec.map_err(|e| csv_error(&rp, &e))?;
            let ln = f.position().map_or(0, csv::Position::line);
            let (v, r, c) = (
                index(&rp, ln, "variant", &f[0], nv, "variants")?,
                index(&rp, ln, "row", &f[1], ny, "grid rows")?,
                index(&rp, ln, "col", &f[2], nz, "grid columns")?,
            );
            if current.as_ref().is_none_or(|x| x.0 != v || x.1 != r) {
                flush(current.take())?;
                current = Some((v, r, LaunchGrid::with_len(nz), 0));
            }
            let cur = current.as_mut().expect("set above");
            if c != cur.3 {
                return Err(DataError::at(
                    &rp,
                    Some(ln as usize),
                    Some("column col".into()),
                    format!("expected column {} of {nz}, got {c}", cur.3),
                )
                .into());
            }
            let g = &mut cur.2;
            g.valid[c] = match &f[3] {
                "1" => true,
                "0" => false,
                other => {
                    return Err(DataError::at(
                        &rp,
                        Some(ln as usize),
                        Some("column valid".into()),
                        format!("must be 0 or 1, got '{}'", escape(other)),
                    )
                    .into())
                }
            };
            g.ball_speed_m_s[c] = num(&rp, ln, "ball_speed_m_s", &f[4])?;
            g.launch_angle_rad[c] = num(&rp, ln, "launch_angle_rad", &f[5])?;
            g.azimuth_rad[c] = num(&rp, ln, "azimuth_rad", &f[6])?;
            g.backspin_rad_s[c] = num(&rp, ln, "backspin_rad_s", &f[7])?;
            g.sidespin_rad_s[c] = num(&rp, ln, "sidespin_rad_s", &f[8])?;
            cur.3 += 1;
        }
        flush(current.take())?;

        let mp = d.join("metrics.csv");
        let mt = read_text(&mp)?;
        let mut reader = csv_records(&mp, mt.as_bytes(), "variant,metric,value")?;
        let mut cur: Option<(usize, Vec<f64>)> = None;
        let mut push = |cur: Option<(usize, Vec<f64>)>| -> Result<(), StudyError> {
            if let Some((variant, values)) = cur {
                if values.len() != names.len() {
                    return Err(StudyError::Merge(format!(
                        "{}: variant {variant} has {} of {} metrics",
                        mp.display(),
                        values.len(),
                        names.len()
                    )));
                }
                let idx = variant * per;
                if seen_items[idx] {
                    return Err(StudyError::Merge(format!("work item {idx} appears twice")));
                }
                seen_items[idx] = true;
                metrics[variant] = values;
            }
            Ok(())
        };
        for rec in reader.records() {
            let f = rec.map_err(|e| csv_error(&mp, &e))?;
            let ln = f.position().map_or(0, csv::Position::line);
            let v = index(&mp, ln, "variant", &f[0], nv, "variants")?;
            if cur.as_ref().is_none_or(|c| c.0 != v) {
                push(cur.take())?;
                cur = Some((v, Vec::new()));
            }
            let c = cur.as_mut().expect("set above");
            if names.get(c.1.len()).map(String::as_str) != Some(&f[1]) {
                return Err(DataError::at(
                    &mp,
                    Some(ln as usize),
                    Some("column metric".into()),
                    match names.get(c.1.len()) {
                        Some(want) => format!("expected metric {want}, got '{}'", escape(&f[1])),
                        None => format!(
                            "variant {v} has more than the study's {} metrics",
                            names.len()
                        ),
                    },
                )
                .into());
            }
            c.1.push(num(&mp, ln, "value", &f[2])?);
        }
        push(cur.take())?;
    }
    if seen.len() != n {
        let missing: Vec<String> = (0..n)
            .filter(|k| !seen.contains(k))
            .take(10)
            .map(|k| k.to_string())
            .collect();
        return Err(StudyError::Merge(format!(
            "shards {}{} of {n} are missing",
            missing.join(", "),
            if n - seen.len() > missing.len() {
                ", …"
            } else {
                ""
            }
        )));
    }
    if let Some(missing) = seen_items.iter().position(|s| !s) {
        return Err(StudyError::Merge(format!(
            "work item {missing} (variant {}) is missing: are all shards given?",
            missing / per
        )));
    }
    let file = scratch_file
        .into_inner()
        .map_err(|e| DataError::file(scratch, format!("cannot write: {}", e.error())))?;
    let grids = DiskGrids {
        file: std::sync::Mutex::new(file),
        path: guard.take(),
        ny,
        nz,
    };
    Ok((p, metrics, grids))
}

/// Removes a scratch file when dropped, unless taken.
struct ScratchGuard(Option<PathBuf>);

impl ScratchGuard {
    fn take(&mut self) -> PathBuf {
        self.0.take().expect("taken once")
    }
}

impl Drop for ScratchGuard {
    fn drop(&mut self) {
        if let Some(p) = &self.0 {
            let _ = std::fs::remove_file(p);
        }
    }
}

/// A sharded study may have at most [`super::MAX_MERGE_POINTS`] grid points.
pub fn check_mergeable(p: &Prepared) -> Result<(), StudyError> {
    crate::limits::count_product(
        "grid points of a sharded study",
        &[
            ("design variants", p.variants.len()),
            ("grid rows", p.ys_mm.len()),
            ("grid columns", p.zs_mm.len()),
        ],
        super::MAX_MERGE_POINTS as usize,
        "a merge's time and disk grow with the study; use a coarser [grid] or fewer [design] \
         values",
    )
    .map(|_| ())
    .map_err(|e| StudyError::Merge(e.to_string()))
}
