//! A synthetic shots file (`smash synth`) written as a TrackMan export in its real 61-column
//! layout and TrackMan's conventions: the writer of `examples/trackman_session.rs` (the file
//! of the guided real-format example) and of the real-format diagnose bench.
//!
//! - dynamic loft and face angle at the centre-point of contact
//!   ([`smash::conventions::contact_point_angles`] with the club's bulge and roll); club speed,
//!   attack angle and path the world's (TrackMan's geometric centre, which smash takes to be
//!   the CoM); spin as rate and axis; `Impact Offset` + toward the toe;
//! - with `radar_face`, the face angle is not the world's but derived from the measured launch
//!   direction and club path as some radar units do ([`radar_face_angle_deg`]);
//! - each synth golfer is one day's session (`Date`: golfer `G01` on Monday 4 May 2026, each
//!   next one a week later, shots a minute apart from 6:10 PM), one player (`Player A`), the
//!   club (`Club`) the world's group (`Driver` when it has none); the
//!   columns a monitor derives or models (carry, apex, …) are left empty: the world has no
//!   flight.

use smash::physics::FaceGeometry;

/// The export of the shots file `world` (its CSV bytes) in the layout of `layout` (a TrackMan
/// export whose header and units rows are copied), on a face of geometry `face`.
pub fn trackman_export(
    world: &[u8],
    layout: &str,
    face: &FaceGeometry,
    radar_face: bool,
) -> String {
    let mut lines = layout
        .lines()
        .filter(|l| !l.trim_start_matches('\u{feff}').starts_with("sep="));
    let header = lines.next().expect("header row");
    let units = lines.next().expect("units row");
    let names: Vec<&str> = header.split(',').collect();
    let mut out = format!("{header}\n{units}\n");
    let mut rdr = csv::Reader::from_reader(world);
    let h = rdr.headers().expect("world header").clone();
    let mut shots_of_day: Vec<usize> = Vec::new();
    for rec in rdr.records() {
        let r = rec.expect("record");
        let f = |c: &str| -> f64 { r[h.iter().position(|x| x == c).expect(c)].parse().expect(c) };
        let (loft, fa) = smash::conventions::contact_point_angles(
            face,
            f("impact_y_mm") * 1e-3,
            f("impact_z_mm") * 1e-3,
            (
                f("dynamic_loft_deg").to_radians(),
                f("face_angle_deg").to_radians(),
            ),
            0.0,
        )
        .expect("on the face");
        let (loft_deg, mut face_deg) = (loft.to_degrees(), fa.to_degrees());
        if radar_face {
            face_deg = radar_face_angle_deg(f("azimuth_deg"), f("club_path_deg"));
        }
        let (back, side) = (f("backspin_rpm"), f("sidespin_rpm"));
        let golfer = &r[h.iter().position(|x| x == "golfer").expect("golfer")];
        // The club under test: the world's group (a fitter names each shaft as a club).
        let group = h
            .iter()
            .position(|x| x == "group")
            .map_or("Driver", |i| &r[i]);
        let day = golfer[1..].parse::<usize>().expect("G01") - 1;
        if shots_of_day.len() <= day {
            shots_of_day.resize(day + 1, 0);
        }
        let minute = shots_of_day[day];
        shots_of_day[day] += 1;
        let cell = |name: &str| -> String {
            let v = match name {
                "Date" => format!("{} {}", session_date(day), clock(minute)),
                "Player" => "Player A".into(),
                "Club" => group.to_owned(),
                "Ball" => "Premium".into(),
                "Club Speed" => f("club_speed_mph").to_string(),
                "Attack Angle" => f("attack_angle_deg").to_string(),
                "Club Path" => f("club_path_deg").to_string(),
                "Dyn. Loft" => loft_deg.to_string(),
                "Face Angle" => face_deg.to_string(),
                "Face To Path" => (face_deg - f("club_path_deg")).to_string(),
                "Ball Speed" => f("ball_speed_mph").to_string(),
                "Smash Factor" => (f("ball_speed_mph") / f("club_speed_mph")).to_string(),
                "Launch Angle" => f("launch_angle_deg").to_string(),
                "Launch Direction" => f("azimuth_deg").to_string(),
                "Spin Rate" => back.hypot(side).to_string(),
                "Spin Rate Type" => "Measured".into(),
                "Spin Axis" => side.atan2(back).to_degrees().to_string(),
                "Impact Offset" => f("impact_z_mm").to_string(),
                "Impact Height" => f("impact_y_mm").to_string(),
                _ => String::new(),
            };
            if v.is_empty() {
                v
            } else {
                format!("\"{v}\"")
            }
        };
        let row: Vec<String> = names.iter().map(|n| cell(n)).collect();
        out.push_str(&row.join(","));
        out.push('\n');
    }
    out
}

/// The face angle a radar unit reports when it derives it from the launch: the inverse of the
/// linear fit `azimuth = 0.82 × face + 0.16 × path` (R² 0.992) that 2,239 real TrackMan drives
/// from public repositories follow (issue 28 of this project).
pub fn radar_face_angle_deg(azimuth_deg: f64, path_deg: f64) -> f64 {
    // The coefficients of that fit (issue 28).
    const FACE_SHARE: f64 = 0.82;
    const PATH_SHARE: f64 = 0.16;
    (azimuth_deg - PATH_SHARE * path_deg) / FACE_SHARE
}

/// The date of session `day` (0 = Monday 4 May 2026, then one a week) as TrackMan writes it,
/// `M/D/YYYY`.
fn session_date(day: usize) -> String {
    // Days in each month of 2026 (not a leap year), January first.
    const MONTH_DAYS: [usize; 12] = [31, 28, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31];
    let (mut year, mut month, mut date) = (2026, 4, 4 + 7 * day); // month 4: May, 0-based
    while date > MONTH_DAYS[month] {
        date -= MONTH_DAYS[month];
        month += 1;
        if month == 12 {
            (month, year) = (0, year + 1);
        }
    }
    format!("{}/{date}/{year}", month + 1)
}

/// The time of a session's `minute`-th shot, one a minute from 6:10 PM, as TrackMan writes it
/// (a session of at most 350 shots stays before midnight).
fn clock(minute: usize) -> String {
    let after_6pm = 10 + minute;
    let hour = 6 + after_6pm / 60;
    format!("{}:{:02}:00 PM", hour, after_6pm % 60)
}
