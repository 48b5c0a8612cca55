//! `smash whatif`: one design change answered in yards against the base head, for a stated
//! golfer and mishit pattern (a table on stdout, optionally a CSV and a one-page HTML report).

use std::fmt::Write as _;
use std::path::PathBuf;

use clap::Args;

use smash::data::club_file::read_club;
use smash::report::render::Render;
use smash::study::distribution::{Distribution, Method, SwingSpec};
use smash::study::report::whatif::WhatIfReport;
use smash::study::whatif::{
    carry_change_grid, carry_change_map, what_if, ChangePart, HeadChange, MassMove, WhatIf,
};
use smash::study::yards_variants::{rows_csv, YardRow, YardSetting};

/// Arguments of `smash whatif`.
#[derive(Debug, Args)]
#[command(
    after_help = "Example (5 g moved 10 mm back and 10 mm toward the heel, 95 mph golfer):\n  \
    smash whatif --club configs/clubs/paper_driver.toml --speed 95 --loft 13 \\\n    \
    --move-mass 5g:-70,-10,0:-80,-10,-10 --report whatif.html"
)]
pub struct WhatIfArgs {
    /// The base club (its nominal head; [[effect]] entries are not applied, as in a study's
    /// [yards]).
    #[arg(long, value_name = "CLUB.toml")]
    pub club: PathBuf,

    /// Move a mass within the head: MASSg:FROM:TO, positions x,y,z in mm in the face frame
    /// (x toward the face, y up, z toward the toe), e.g. 5g:-70,-10,0:-80,-10,-10.
    #[arg(long, value_name = "Mg:X,Y,Z:X,Y,Z", value_parser = parse_mass_move, allow_hyphen_values = true, help_heading = "Design change")]
    pub move_mass: Option<MassMove>,
    /// Shift the CoM (inertia about it unchanged): dx,dy,dz in mm.
    #[arg(long, value_name = "DX,DY,DZ", value_parser = parse_vec3, allow_hyphen_values = true, help_heading = "Design change")]
    pub com_shift_mm: Option<[f64; 3]>,
    /// Scale the inertia tensor about the CoM.
    #[arg(
        long,
        value_name = "S",
        allow_negative_numbers = true,
        help_heading = "Design change"
    )]
    pub moi_scale: Option<f64>,
    /// New bulge radius, mm.
    #[arg(long, value_name = "MM", help_heading = "Design change")]
    pub bulge_mm: Option<f64>,
    /// New roll radius, mm.
    #[arg(long, value_name = "MM", help_heading = "Design change")]
    pub roll_mm: Option<f64>,
    /// Loft change of the head, degrees (+ more loft; the same swing delivers that much more
    /// dynamic loft).
    #[arg(
        long,
        value_name = "DEG",
        allow_hyphen_values = true,
        help_heading = "Design change"
    )]
    pub loft_change_deg: Option<f64>,

    /// Club speed, mph.
    #[arg(long, value_name = "MPH", help_heading = "Golfer")]
    pub speed: f64,
    /// Dynamic loft of the base head, degrees.
    #[arg(
        long,
        value_name = "DEG",
        default_value_t = 13.0,
        help_heading = "Golfer"
    )]
    pub loft: f64,
    /// Attack angle, degrees (+ up).
    #[arg(
        long,
        value_name = "DEG",
        default_value_t = 0.0,
        allow_hyphen_values = true,
        help_heading = "Golfer"
    )]
    pub attack: f64,
    /// Club path, degrees (+ right of target).
    #[arg(
        long,
        value_name = "DEG",
        default_value_t = 0.0,
        allow_hyphen_values = true,
        help_heading = "Golfer"
    )]
    pub path: f64,
    /// Face angle, degrees (+ open).
    #[arg(
        long,
        value_name = "DEG",
        default_value_t = 0.0,
        allow_hyphen_values = true,
        help_heading = "Golfer"
    )]
    pub face: f64,
    /// Swing-to-swing spread of club speed (σ), mph.
    #[arg(
        long,
        value_name = "MPH",
        default_value_t = 0.0,
        allow_negative_numbers = true,
        help_heading = "Golfer"
    )]
    pub speed_sd: f64,
    /// Swing-to-swing spread of face angle (σ), degrees.
    #[arg(
        long,
        value_name = "DEG",
        default_value_t = 0.0,
        help_heading = "Golfer"
    )]
    pub face_sd: f64,

    /// Mishit pattern: σ of the impact location up the face and toward the toe, mm.
    #[arg(long, value_name = "SY,SZ", default_value = "4,9", value_parser = parse_pair, help_heading = "Mishits")]
    pub mishit_mm: [f64; 2],
    /// Centre of the mishit pattern (y up, z toward the toe), mm.
    #[arg(long, value_name = "Y,Z", default_value = "0,0", value_parser = parse_pair, allow_hyphen_values = true, help_heading = "Mishits")]
    pub centre_mm: [f64; 2],
    /// Gauss–Hermite nodes per scattered dimension (1–20).
    #[arg(long, value_name = "N", default_value_t = 5, value_parser = clap::value_parser!(u64).range(1..=20), help_heading = "Mishits")]
    pub nodes: u64,
    /// Confidence level of the dispersion ellipse, in (0, 1).
    #[arg(
        long,
        value_name = "P",
        default_value_t = 0.95,
        help_heading = "Mishits"
    )]
    pub confidence: f64,

    /// Flight options (model, atmosphere).
    #[command(flatten)]
    pub flight: crate::flight::FlightOptions,

    /// Also write the comparison as CSV (the columns of a study's yards/variants.csv).
    #[arg(long, value_name = "FILE.csv")]
    pub out: Option<PathBuf>,
    /// Also write a one-page HTML report.
    #[arg(long, value_name = "FILE.html")]
    pub report: Option<PathBuf>,
}

fn parse_numbers<const N: usize>(s: &str, what: &str) -> Result<[f64; N], String> {
    let v: Vec<f64> = s
        .split(',')
        .map(|x| x.trim().parse::<f64>())
        .collect::<Result<_, _>>()
        .map_err(|_| format!("'{s}': expected {what}, numbers separated by commas"))?;
    let arr: [f64; N] = v
        .try_into()
        .map_err(|_| format!("'{s}': expected {N} numbers ({what})"))?;
    if arr.iter().any(|x| !x.is_finite()) {
        return Err(format!("'{s}': the numbers must be finite"));
    }
    Ok(arr)
}

fn parse_pair(s: &str) -> Result<[f64; 2], String> {
    parse_numbers(s, "two values")
}

fn parse_vec3(s: &str) -> Result<[f64; 3], String> {
    parse_numbers(s, "x,y,z in mm")
}

/// `5g:-70,-10,0:-80,-10,-10`.
fn parse_mass_move(s: &str) -> Result<MassMove, String> {
    let parts: Vec<&str> = s.split(':').collect();
    let form = "the form is MASSg:X,Y,Z:X,Y,Z (e.g. 5g:-70,-10,0:-80,-10,-10)";
    let [m, from, to] = parts[..] else {
        return Err(format!("'{s}': {form}"));
    };
    let mass_g = m
        .trim()
        .strip_suffix('g')
        .and_then(|x| x.trim().parse::<f64>().ok())
        .filter(|x| x.is_finite() && *x > 0.0)
        .ok_or_else(|| {
            format!("'{m}': the mass must be a positive number of grams ending in g; {form}")
        })?;
    Ok(MassMove {
        mass_g,
        from_mm: parse_vec3(from)?,
        to_mm: parse_vec3(to)?,
    })
}

impl WhatIfArgs {
    fn change(&self) -> HeadChange {
        HeadChange {
            mass_move: self.move_mass,
            com_shift_mm: self.com_shift_mm,
            moi_scale: self.moi_scale,
            bulge_mm: self.bulge_mm,
            roll_mm: self.roll_mm,
            loft_change_deg: self.loft_change_deg,
        }
    }

    fn swing(&self) -> SwingSpec {
        SwingSpec {
            club_speed_mph: self.speed,
            dynamic_loft_deg: self.loft,
            attack_angle_deg: self.attack,
            club_path_deg: self.path,
            face_angle_deg: self.face,
            lie_tilt_deg: 0.0,
            club_omega_rad_s: [0.0; 3],
        }
    }

    fn distribution(&self) -> Distribution {
        Distribution {
            method: Method::Quadrature {
                nodes: self.nodes as usize,
            },
            impact_centre_mm: self.centre_mm,
            sigma_y_mm: self.mishit_mm[0],
            sigma_z_mm: self.mishit_mm[1],
            sigma_club_speed_mph: self.speed_sd,
            sigma_attack_angle_deg: 0.0,
            sigma_club_path_deg: 0.0,
            sigma_dynamic_loft_deg: 0.0,
            sigma_face_angle_deg: self.face_sd,
        }
    }

    /// Refuse what cannot be answered, each with one line.
    fn check(&self) -> anyhow::Result<()> {
        if self.change().is_empty() {
            anyhow::bail!(
                "no design change given: use --move-mass, --com-shift-mm, --moi-scale, \
                 --bulge-mm, --roll-mm or --loft-change-deg"
            );
        }
        if !(self.speed.is_finite() && self.speed > 0.0) {
            anyhow::bail!(
                "--speed: must be a club speed above 0 mph, got {}",
                self.speed
            );
        }
        let sds = [
            ("--mishit-mm", self.mishit_mm[0]),
            ("--mishit-mm", self.mishit_mm[1]),
            ("--speed-sd", self.speed_sd),
            ("--face-sd", self.face_sd),
        ];
        if let Some((k, v)) = sds.iter().find(|(_, v)| !(v.is_finite() && *v >= 0.0)) {
            anyhow::bail!("{k}: a spread (σ) must be 0 or more, got {v}");
        }
        if !(self.confidence > 0.0 && self.confidence < 1.0) {
            anyhow::bail!("--confidence: must be in (0, 1), got {}", self.confidence);
        }
        if self.flight.total {
            anyhow::bail!("--total: whatif reports carry, not total distance; leave it out");
        }
        Ok(())
    }

    /// The flag that gave `part` of the change, with its value (`--bulge-mm 0`).
    fn flag_value(&self, part: ChangePart) -> String {
        let f = smash::limits::fmt_value;
        let v3 = |v: [f64; 3]| format!("{},{},{}", f(v[0]), f(v[1]), f(v[2]));
        let value = |x: Option<f64>| x.map(f).unwrap_or_default();
        match part {
            ChangePart::MassMove => self.move_mass.map_or("--move-mass".into(), |m| {
                format!(
                    "--move-mass {}g:{}:{}",
                    f(m.mass_g),
                    v3(m.from_mm),
                    v3(m.to_mm)
                )
            }),
            ChangePart::ComShift => {
                format!(
                    "--com-shift-mm {}",
                    self.com_shift_mm.map(v3).unwrap_or_default()
                )
            }
            ChangePart::MoiScale => format!("--moi-scale {}", value(self.moi_scale)),
            ChangePart::Bulge => format!("--bulge-mm {}", value(self.bulge_mm)),
            ChangePart::Roll => format!("--roll-mm {}", value(self.roll_mm)),
            ChangePart::LoftChange => {
                format!("--loft-change-deg {}", value(self.loft_change_deg))
            }
        }
    }

    /// The golfer and mishit pattern in words.
    fn setting_text(&self) -> String {
        let d = self.distribution();
        format!(
            "golfer: {} mph (σ {}), dynamic loft {} deg, attack {} deg, path {} deg, face {} deg \
             (σ {}); mishits: σ {} mm up the face, {} mm heel-toe about ({}, {}) mm; \
             {}-node Gauss–Hermite quadrature ({} impacts), {} % dispersion ellipse",
            self.speed,
            self.speed_sd,
            self.loft,
            self.attack,
            self.path,
            self.face,
            self.face_sd,
            self.mishit_mm[0],
            self.mishit_mm[1],
            self.centre_mm[0],
            self.centre_mm[1],
            self.nodes,
            d.point_count(),
            100.0 * self.confidence
        )
    }
}

fn rows(w: &WhatIf, change: &HeadChange) -> Vec<YardRow> {
    vec![
        YardRow {
            variant_id: None,
            label: "base".into(),
            design: "base".into(),
            head: w.base,
        },
        YardRow {
            variant_id: None,
            label: "what-if".into(),
            design: change.describe().join("; "),
            head: w.changed,
        },
    ]
}

/// Run `smash whatif`.
pub fn run(args: WhatIfArgs) -> anyhow::Result<()> {
    args.check()?;
    let club = read_club(&args.club)?;
    let flight = args.flight.config()?;
    let (swing, dist) = (args.swing(), args.distribution());
    let setting = YardSetting {
        swing: &swing,
        dist: &dist,
        flight: &flight,
        confidence: args.confidence,
    };
    let change = args.change();
    let w = what_if(&club.nominal, &change, &setting).map_err(|e| {
        use smash::study::whatif::WhatIfError as E;
        use smash::study::yards::YardsError as Y;
        match &e {
            // A launch the flight model does not take comes from the swing the flags give, not
            // from the club file.
            E::BaseYards(Y::Flight(_)) | E::ChangedYards(Y::Flight(_)) => anyhow::anyhow!(
                "the swing of --speed {} mph, --loft {} deg: {e}; give a slower or more lofted \
                 swing",
                args.speed,
                args.loft
            ),
            // A part of the change is the flag's value, not the club file's.
            E::Part { part, problem } => {
                anyhow::anyhow!("{}: {problem}", args.flag_value(*part))
            }
            _ => anyhow::anyhow!("{}: {e}", args.club.display()),
        }
    })?;
    let inputs = [("--club", args.club.as_path())];
    let setting_text = args.setting_text();
    if let Some(out) = &args.out {
        smash::data::safe_write::refuse_inputs(&[("--out", out, false)], &inputs)?;
        smash::data::write_atomic(out, &rows_csv(&w.base, &rows(&w, &change)))?;
    }
    if let Some(path) = &args.report {
        smash::data::safe_write::refuse_inputs(&[("--report", path, false)], &inputs)?;
    }
    let map = args.report.as_ref().and_then(|_| {
        let grid = carry_change_grid(args.centre_mm, args.mishit_mm, 21);
        carry_change_map(
            &w.base_params,
            &w.changed_params,
            &change,
            &swing,
            &flight,
            &grid,
        )
        .ok()
        .map(|m| (m, args.centre_mm))
    });
    let report = WhatIfReport {
        club: club.name.clone(),
        change,
        setting: setting_text,
        whatif: w,
        map,
    };
    if let Some(path) = &args.report {
        if let Some(html) = report.html(&()) {
            smash::data::write_atomic(path, html?.as_bytes())?;
        }
    }
    let mut text = report.text(&());
    for (flag, path) in [("csv", &args.out), ("report", &args.report)] {
        if let Some(p) = path {
            let _ = writeln!(text, "{flag} -> {}", p.display());
        }
    }
    crate::stdout::print(text)?;
    Ok(())
}
