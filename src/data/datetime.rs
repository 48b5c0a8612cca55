//! Dates and times as exports write them, read into one form (`YYYY-MM-DD HH:MM:SS`): ISO
//! (`2026-05-01T18:04:06`, `2026.05.01`), day-first or month-first with slashes, dots or
//! dashes (`5/1/2026 7:03:21 PM`, `01/05/2026 19:03`, two-digit years), and Excel serial day
//! numbers (`46143.79`, days since 1899-12-30). Whether `5/1/2026` is the 5th of January or
//! the 1st of May is settled once per column: day-first when some cell's first number is above
//! 12, month-first otherwise (the US apps' default).

/// A date (year, month, day) and the seconds since its midnight, when given.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DateTime {
    pub year: i32,
    pub month: u32,
    pub day: u32,
    pub seconds: Option<f64>,
}

impl DateTime {
    /// `YYYY-MM-DD` or `YYYY-MM-DD HH:MM:SS` (fractions of a second kept to milliseconds).
    pub fn format(&self) -> String {
        let date = format!("{:04}-{:02}-{:02}", self.year, self.month, self.day);
        match self.seconds {
            None => date,
            Some(s) => {
                let whole = s.floor();
                let (h, m, sec) = (
                    (whole / 3600.0) as u32,
                    ((whole % 3600.0) / 60.0) as u32,
                    (whole % 60.0) as u32,
                );
                let ms = ((s - whole) * 1000.0).round() as u32;
                if ms == 0 || ms >= 1000 {
                    format!("{date} {h:02}:{m:02}:{sec:02}")
                } else {
                    format!("{date} {h:02}:{m:02}:{sec:02}.{ms:03}")
                }
            }
        }
    }

    /// The date alone, `YYYY-MM-DD`.
    pub fn date(&self) -> String {
        format!("{:04}-{:02}-{:02}", self.year, self.month, self.day)
    }
}

/// Seconds since midnight of `h:mm[:ss[.fff]][ AM|PM]` (an ISO zone suffix `Z` or `±hh:mm` is
/// dropped: a shot's time of day is the export's own clock).
pub fn seconds_of_day(t: &str) -> Option<f64> {
    let mut lower = t.trim().to_ascii_lowercase();
    if let Some(s) = lower.strip_suffix('z') {
        lower = s.to_owned();
    }
    if let Some(i) = lower.rfind(['+', '-']).filter(|&i| i >= 5) {
        lower.truncate(i);
    }
    let (clock, pm) = match lower.strip_suffix("pm") {
        Some(c) => (c.trim(), Some(true)),
        None => match lower.strip_suffix("am") {
            Some(c) => (c.trim(), Some(false)),
            None => (lower.trim(), None),
        },
    };
    let mut parts = clock.split(':');
    // Hours and minutes are whole numbers (`7.5:00 PM` and `1e1:00` are no time of day).
    let whole = |p: &str| -> Option<f64> {
        (!p.is_empty() && p.len() <= 2 && p.bytes().all(|b| b.is_ascii_digit()))
            .then(|| p.parse::<f64>().ok())
            .flatten()
    };
    let h: f64 = whole(parts.next()?)?;
    let m: f64 = whole(parts.next()?)?;
    let s: f64 = match parts.next() {
        Some(s) => s.parse().ok()?,
        None => 0.0,
    };
    if parts.next().is_some() || !(0.0..24.0).contains(&h) || !(0.0..60.0).contains(&m) {
        return None;
    }
    // A 12-hour clock's hours are 1–12; a PM after a 24-hour clock's 13–23 (`13:00:28 PM`, a
    // spreadsheet's re-save of a Garmin export) says nothing more and is read as it stands.
    let hours = match pm {
        Some(true) => 1.0..=23.0,
        Some(false) => 1.0..=12.0,
        None => 0.0..=23.0,
    };
    if !(0.0..61.0).contains(&s) || !hours.contains(&h) {
        return None;
    }
    let h = match pm {
        Some(true) if h < 12.0 => h + 12.0,
        Some(false) if h == 12.0 => 0.0,
        _ => h,
    };
    Some(h * 3600.0 + m * 60.0 + s)
}

/// The three numbers of a date written with `/`, `.` or `-`, when it is one.
fn date_fields(d: &str) -> Option<[&str; 3]> {
    let sep = d.chars().find(|c| matches!(c, '/' | '.' | '-'))?;
    let f: Vec<&str> = d.split(sep).collect();
    if f.len() != 3
        || f.iter()
            .any(|x| x.is_empty() || !x.bytes().all(|b| b.is_ascii_digit()))
    {
        return None;
    }
    Some([f[0], f[1], f[2]])
}

/// Whether a column's slash dates are day-first: some cell's first number is above 12.
pub fn day_first<'a>(cells: impl IntoIterator<Item = &'a str>) -> bool {
    cells.into_iter().any(|c| {
        let d = c.trim().split([' ', 'T']).next().unwrap_or("");
        date_fields(d).is_some_and(|f| f[0].len() <= 2 && f[0].parse::<u32>().is_ok_and(|n| n > 12))
    })
}

fn days_in_month(y: i32, m: u32) -> u32 {
    match m {
        4 | 6 | 9 | 11 => 30,
        2 if (y % 4 == 0 && y % 100 != 0) || y % 400 == 0 => 29,
        2 => 28,
        _ => 31,
    }
}

/// The civil date `days` after 1970-01-01 (Howard Hinnant's algorithm).
fn civil_from_days(days: i64) -> (i32, u32, u32) {
    let z = days + 719_468;
    let era = z.div_euclid(146_097);
    let doe = z.rem_euclid(146_097);
    let yoe = (doe - doe / 1460 + doe / 36_524 - doe / 146_096) / 365;
    let y = yoe + era * 400;
    let doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    let mp = (5 * doy + 2) / 153;
    let d = (doy - (153 * mp + 2) / 5 + 1) as u32;
    let m = if mp < 10 { mp + 3 } else { mp - 9 } as u32;
    ((if m <= 2 { y + 1 } else { y }) as i32, m, d)
}

/// Read one cell: a date with or without a time of day, or an Excel serial day number
/// (from 1 = 1900-01-01 to 109,572 = 2199-12-31). `day_first` settles `a/b/yyyy`.
pub fn parse(cell: &str, day_first: bool) -> Option<DateTime> {
    let cell = cell.trim();
    if cell.is_empty() {
        return None;
    }
    if let Ok(serial) = cell.parse::<f64>() {
        if !(1.0..109_573.0).contains(&serial) {
            return None;
        }
        // Excel's day 0 is 1899-12-30 (its 1900 leap-year bug is absorbed by the offset).
        let days = serial.floor() as i64 - 25_569;
        let (year, month, day) = civil_from_days(days);
        let frac = serial - serial.floor();
        let seconds = (frac > 0.0).then(|| (frac * 86_400.0 * 1000.0).round() / 1000.0);
        return Some(DateTime {
            year,
            month,
            day,
            seconds,
        });
    }
    let (date, time) = match cell.split_once([' ', 'T']) {
        Some((d, t)) => (d, Some(t.trim())),
        None => (cell, None),
    };
    let f = date_fields(date)?;
    let n = |s: &str| s.parse::<i64>().ok();
    let (y, m, d) = if f[0].len() == 4 {
        (n(f[0])?, n(f[1])?, n(f[2])?)
    } else {
        let y = n(f[2])?;
        let y = if f[2].len() == 2 { 2000 + y } else { y };
        if day_first {
            (y, n(f[1])?, n(f[0])?)
        } else {
            (y, n(f[0])?, n(f[1])?)
        }
    };
    let (y, m, d) = (
        i32::try_from(y).ok()?,
        u32::try_from(m).ok()?,
        u32::try_from(d).ok()?,
    );
    if !(1900..2200).contains(&y) || !(1..=12).contains(&m) || d == 0 || d > days_in_month(y, m) {
        return None;
    }
    let seconds = match time.filter(|t| !t.is_empty()) {
        Some(t) => Some(seconds_of_day(t)?),
        None => None,
    };
    Some(DateTime {
        year: y,
        month: m,
        day: d,
        seconds,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn iso(cell: &str, day_first: bool) -> Option<String> {
        parse(cell, day_first).map(|d| d.format())
    }

    #[test]
    fn every_way_an_export_writes_a_date() {
        assert_eq!(iso("2026-05-01", false).unwrap(), "2026-05-01");
        assert_eq!(iso("5/1/2026", false).unwrap(), "2026-05-01");
        assert_eq!(
            iso("01/05/2026 19:03:21", true).unwrap(),
            "2026-05-01 19:03:21"
        );
        assert_eq!(
            iso("5/1/26 7:03:21 PM", false).unwrap(),
            "2026-05-01 19:03:21"
        );
        // A 24-hour clock with a redundant PM (a re-saved Garmin export); AM cannot follow 13.
        assert_eq!(
            iso("06/19/25 13:00:28 PM", false).unwrap(),
            "2025-06-19 13:00:28"
        );
        assert_eq!(
            iso("06/19/25 1:00:28 PM", false).unwrap(),
            "2025-06-19 13:00:28"
        );
        assert!(iso("06/19/25 13:00:28 AM", false).is_none());
        assert!(iso("06/19/25 0:10 PM", false).is_none());
        assert!(iso("06/19/25 7.5:00 PM", false).is_none());
        assert!(iso("06/19/25 1e1:00 PM", false).is_none());
        assert_eq!(
            iso("2024.01.29T14:02:11", false).unwrap(),
            "2024-01-29 14:02:11"
        );
        assert_eq!(
            iso("2022-10-25T18:48:08Z", false).unwrap(),
            "2022-10-25 18:48:08"
        );
        assert_eq!(
            iso("2026-05-01T18:04:06.396460", false).unwrap(),
            "2026-05-01 18:04:06.396"
        );
        // Excel serials: 46143 is 2026-05-01; .75 is 18:00.
        assert_eq!(iso("46143", false).unwrap(), "2026-05-01");
        assert_eq!(iso("46143.75", false).unwrap(), "2026-05-01 18:00:00");
        assert!(iso("13/13/2026", true).is_none());
        assert!(iso("2026-02-30", false).is_none());
        assert!(iso("Driver", false).is_none());
        assert!(day_first(["5/1/2026", "13/1/2026 10:00"]));
        assert!(!day_first(["5/1/2026", "2026-05-13"]));
    }
}
