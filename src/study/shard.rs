//! Shards: a part of a study's work list written to disk, and their merge.
//!
//! A shard folder holds `study.toml` (the resolved study, identical for every shard and for the
//! unsharded run), `shard.toml` (`shard`, `shards`, `first_item`, `end_item`), `rows.csv` (the
//! shard's grid rows: `variant,row,col,valid` and the five launch components in SI units) and
//! `metrics.csv` (`variant,metric,value`). Values are written in their shortest round-trip
//! decimal form, so reading them back gives the same bits; invalid values are empty cells.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use crate::data::{read_text, DataError};
use crate::sweep::kernel::LaunchGrid;

use super::metrics::metric_names;
use super::output::{cell, Files};
use super::spec::{parse_study, resolved_toml};
use super::sweep::{ItemResult, Prepared};
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

/// Files of shard `k` of `n` holding `items`.
pub fn shard_files(p: &Prepared, k: usize, n: usize, items: &[ItemResult]) -> Files {
    let range = p.shard_range(k, n);
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
    vec![
        ("study.toml".into(), resolved_toml(&p.study).into_bytes()),
        ("shard.toml".into(), meta.into_bytes()),
        ("rows.csv".into(), rows.into_bytes()),
        ("metrics.csv".into(), metrics.into_bytes()),
    ]
}

fn meta_value(path: &Path, text: &str, key: &str) -> Result<usize, DataError> {
    let table: toml::Table = toml::from_str(text)
        .map_err(|e| DataError::file(path, format!("not a shard.toml: {}", e.message())))?;
    match table.get(key) {
        Some(toml::Value::Integer(i)) if *i >= 0 => Ok(*i as usize),
        _ => Err(DataError::file(
            path,
            format!("missing or bad `{key}` (a non-negative integer)"),
        )),
    }
}

fn num(path: &Path, line: usize, col: &str, s: &str) -> Result<f64, DataError> {
    if s.is_empty() {
        return Ok(f64::NAN);
    }
    s.parse::<f64>()
        .ok()
        .filter(|v| v.is_finite())
        .ok_or_else(|| {
            DataError::at(
                path,
                Some(line),
                Some(format!("column {col}")),
                format!("not a finite number: '{s}'"),
            )
        })
}

fn index(path: &Path, line: usize, col: &str, s: &str) -> Result<usize, DataError> {
    s.parse::<usize>().map_err(|_| {
        DataError::at(
            path,
            Some(line),
            Some(format!("column {col}")),
            format!("not an index: '{s}'"),
        )
    })
}

/// Read the shard folders and assemble the full study result.
pub fn merge_shards(
    dirs: &[PathBuf],
) -> Result<(Prepared, Vec<super::sweep::VariantResult>), StudyError> {
    let first = dirs
        .first()
        .ok_or_else(|| StudyError::Merge("no shard folders given".into()))?;
    let study_path = first.join("study.toml");
    let study_text = read_text(&study_path)?;
    for d in &dirs[1..] {
        let t = read_text(&d.join("study.toml"))?;
        if t != study_text {
            return Err(StudyError::Merge(format!(
                "{} and {} are shards of different studies (their study.toml differ)",
                first.display(),
                d.display()
            )));
        }
    }
    let study = parse_study(&study_path, &study_text)?;
    let p = Prepared::new(study)?;
    let mut total = None;
    let mut seen = Vec::new();
    let mut items = Vec::new();
    let names = metric_names(p.study.distribution.is_some());
    let nz = p.zs_mm.len();
    for d in dirs {
        let mp = d.join("shard.toml");
        let mt = read_text(&mp)?;
        let (k, n) = (
            meta_value(&mp, &mt, "shard")?,
            meta_value(&mp, &mt, "shards")?,
        );
        if k >= n {
            return Err(StudyError::Merge(format!(
                "{}: shard {k} of {n}",
                mp.display()
            )));
        }
        if *total.get_or_insert(n) != n {
            return Err(StudyError::Merge(format!(
                "{}: shard of {n}, the others are of {}",
                mp.display(),
                total.unwrap_or(0)
            )));
        }
        if seen.contains(&k) {
            return Err(StudyError::Merge(format!(
                "shard {k} is given twice ({})",
                d.display()
            )));
        }
        seen.push(k);

        let rp = d.join("rows.csv");
        let rt = read_text(&rp)?;
        let mut lines = rt.lines().enumerate();
        match lines.next() {
            Some((_, h)) if h == ROWS_HEADER => {}
            _ => {
                return Err(DataError::at(
                    &rp,
                    Some(1),
                    None,
                    format!("header must be {ROWS_HEADER}"),
                )
                .into())
            }
        }
        let mut current: Option<(usize, usize, LaunchGrid, usize)> = None;
        let flush = |cur: Option<(usize, usize, LaunchGrid, usize)>,
                     items: &mut Vec<ItemResult>|
         -> Result<(), StudyError> {
            if let Some((variant, row, grid, filled)) = cur {
                if filled != nz {
                    return Err(StudyError::Merge(format!(
                        "{}: variant {variant} row {row} has {filled} of {nz} points",
                        rp.display()
                    )));
                }
                items.push(ItemResult::Row { variant, row, grid });
            }
            Ok(())
        };
        for (i, line) in lines {
            let ln = i + 1;
            let f: Vec<&str> = line.split(',').collect();
            if f.len() != 9 {
                return Err(DataError::at(&rp, Some(ln), None, "expected 9 fields").into());
            }
            let (v, r, c) = (
                index(&rp, ln, "variant", f[0])?,
                index(&rp, ln, "row", f[1])?,
                index(&rp, ln, "col", f[2])?,
            );
            if current.as_ref().is_none_or(|x| x.0 != v || x.1 != r) {
                flush(current.take(), &mut items)?;
                current = Some((v, r, LaunchGrid::with_len(nz), 0));
            }
            let cur = current.as_mut().expect("set above");
            if c != cur.3 || c >= nz {
                return Err(DataError::at(
                    &rp,
                    Some(ln),
                    Some("column col".into()),
                    format!("expected column {} of {nz}", cur.3),
                )
                .into());
            }
            let g = &mut cur.2;
            g.valid[c] = match f[3] {
                "1" => true,
                "0" => false,
                other => {
                    return Err(DataError::at(
                        &rp,
                        Some(ln),
                        Some("column valid".into()),
                        format!("must be 0 or 1, got '{other}'"),
                    )
                    .into())
                }
            };
            g.ball_speed_m_s[c] = num(&rp, ln, "ball_speed_m_s", f[4])?;
            g.launch_angle_rad[c] = num(&rp, ln, "launch_angle_rad", f[5])?;
            g.azimuth_rad[c] = num(&rp, ln, "azimuth_rad", f[6])?;
            g.backspin_rad_s[c] = num(&rp, ln, "backspin_rad_s", f[7])?;
            g.sidespin_rad_s[c] = num(&rp, ln, "sidespin_rad_s", f[8])?;
            cur.3 += 1;
        }
        flush(current.take(), &mut items)?;

        let mp = d.join("metrics.csv");
        let mt = read_text(&mp)?;
        let mut cur: Option<(usize, Vec<f64>)> = None;
        let push = |cur: Option<(usize, Vec<f64>)>,
                    items: &mut Vec<ItemResult>|
         -> Result<(), StudyError> {
            if let Some((variant, values)) = cur {
                if values.len() != names.len() {
                    return Err(StudyError::Merge(format!(
                        "{}: variant {variant} has {} of {} metrics",
                        mp.display(),
                        values.len(),
                        names.len()
                    )));
                }
                items.push(ItemResult::Metrics { variant, values });
            }
            Ok(())
        };
        for (i, line) in mt.lines().enumerate().skip(1) {
            let ln = i + 1;
            let f: Vec<&str> = line.split(',').collect();
            if f.len() != 3 {
                return Err(
                    DataError::at(&mp, Some(ln), None, "expected variant,metric,value").into(),
                );
            }
            let v = index(&mp, ln, "variant", f[0])?;
            if cur.as_ref().is_none_or(|c| c.0 != v) {
                push(cur.take(), &mut items)?;
                cur = Some((v, Vec::new()));
            }
            let c = cur.as_mut().expect("set above");
            if names.get(c.1.len()).map(String::as_str) != Some(f[1]) {
                return Err(DataError::at(
                    &mp,
                    Some(ln),
                    Some("column metric".into()),
                    format!("expected metric {:?}", names.get(c.1.len())),
                )
                .into());
            }
            c.1.push(num(&mp, ln, "value", f[2])?);
        }
        push(cur.take(), &mut items)?;
    }
    let n = total.unwrap_or(0);
    if seen.len() != n {
        let missing: Vec<String> = (0..n)
            .filter(|k| !seen.contains(k))
            .map(|k| k.to_string())
            .collect();
        return Err(StudyError::Merge(format!(
            "shards {} of {n} are missing",
            missing.join(", ")
        )));
    }
    let results = p.assemble(items)?;
    Ok((p, results))
}
