//! Write a synthetic shots file (`smash synth`) as a TrackMan export in its real 61-column
//! layout and TrackMan's conventions: the file of the guided real-format example
//! (configs/README.md, tests/data/README.md).
//!
//! `cargo run --example trackman_session -- WORLD.csv HEADER.csv CLUB.toml OUT.csv`
//!
//! - `HEADER.csv`: a TrackMan export whose header and units rows are copied (the layout of
//!   `cli/tests/fixtures/import/trackman_normalized.csv`);
//! - dynamic loft and face angle at the centre-point of contact
//!   ([`smash::conventions::contact_point_angles`] with the club's bulge and roll); club speed,
//!   attack angle and path the world's (TrackMan's geometric centre, which smash takes to be
//!   the CoM); spin as rate and axis; `Impact Offset` + toward the toe;
//! - each synth golfer is one day's session (`Date`), one player (`Player A`); the columns a
//!   monitor derives or models (carry, apex, …) are left empty: the world has no flight.

use std::path::Path;

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    assert_eq!(
        args.len(),
        4,
        "usage: WORLD.csv HEADER.csv CLUB.toml OUT.csv"
    );
    let club = smash::data::club_file::read_club(Path::new(&args[2])).expect("club");
    let face =
        smash::physics::FaceGeometry::new(club.nominal.bulge_m, club.nominal.roll_m).expect("face");
    let layout = std::fs::read_to_string(&args[1]).expect("header file");
    let mut lines = layout
        .lines()
        .filter(|l| !l.trim_start_matches('\u{feff}').starts_with("sep="));
    let header = lines.next().expect("header row");
    let units = lines.next().expect("units row");
    let names: Vec<&str> = header.split(',').collect();
    let mut out = format!("{header}\n{units}\n");
    let mut rdr = csv::Reader::from_path(&args[0]).expect("world");
    let h = rdr.headers().expect("world header").clone();
    let days = ["5/4/2026", "5/11/2026", "5/18/2026"];
    for (i, rec) in rdr.records().enumerate() {
        let r = rec.expect("record");
        let f = |c: &str| -> f64 { r[h.iter().position(|x| x == c).expect(c)].parse().expect(c) };
        let (loft, fa) = smash::conventions::contact_point_angles(
            &face,
            f("impact_y_mm") * 1e-3,
            f("impact_z_mm") * 1e-3,
            (
                f("dynamic_loft_deg").to_radians(),
                f("face_angle_deg").to_radians(),
            ),
            0.0,
        )
        .expect("on the face");
        let (back, side) = (f("backspin_rpm"), f("sidespin_rpm"));
        let golfer = &r[h.iter().position(|x| x == "golfer").expect("golfer")];
        let day = golfer[1..].parse::<usize>().expect("G01") - 1;
        let minute = i % 40;
        let cell = |name: &str| -> String {
            let v = match name {
                "Date" => format!("{} 6:{:02}:00 PM", days[day % days.len()], 10 + minute),
                "Player" => "Player A".into(),
                "Club" => "Driver".into(),
                "Ball" => "Premium".into(),
                "Club Speed" => f("club_speed_mph").to_string(),
                "Attack Angle" => f("attack_angle_deg").to_string(),
                "Club Path" => f("club_path_deg").to_string(),
                "Dyn. Loft" => loft.to_degrees().to_string(),
                "Face Angle" => fa.to_degrees().to_string(),
                "Face To Path" => (fa.to_degrees() - f("club_path_deg")).to_string(),
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
    std::fs::write(&args[3], out).expect("write");
}
