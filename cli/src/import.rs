//! `smash import`: a launch-monitor export to a shots file.

use std::path::PathBuf;

use clap::Args;

use smash::data::write_atomic;

/// Arguments of `smash import`.
#[derive(Debug, Args)]
#[command(
    after_help = "Examples:\n  smash import --format trackman session.csv --impact-offset-positive toe --out shots.csv\n  \
                  smash import --format my_monitor.toml export.csv --out shots.csv\n\n\
                  --format auto (the default) recognises the layout from the header or JSON keys.\n\
                  Presets: trackman, flightscope (mevo), foresight (gc3, gcquad, fsx),\n\
                  foresight-session (FSX .session JSON), uneekor, garmin-r10 (garmin, r10),\n\
                  rapsodo (mlm2pro), skytrak, awesome-golf, square-golf, gspro. A mapping\n\
                  file (TOML) describes any other export; see docs/import.md."
)]
pub struct ImportArgs {
    /// The export (CSV).
    #[arg(value_name = "IN.csv")]
    pub input: PathBuf,

    /// Shots file to write (CSV).
    #[arg(long, value_name = "SHOTS.csv")]
    pub out: PathBuf,

    /// How to read the export.
    #[command(flatten)]
    pub format: super::ShotsFormatArgs,
}

/// Run `smash import`.
pub fn run(args: ImportArgs) -> anyhow::Result<()> {
    let settings = smash::app::import::ImportSettings {
        shots: args.format.settings(),
    };
    if settings.shots.format.as_deref() != Some("shots") {
        smash::data::safe_write::refuse_inputs(
            &[("--out", &args.out, false)],
            &[("IN.csv", &args.input)],
        )?;
    }
    let smash::app::import::Converted { imported, table } =
        smash::app::import::run(&settings, &args.input, &mut smash::app::StderrNotes)?;
    let groups = table.as_ref().map_or(0, |t| t.groups().len());
    write_atomic(&args.out, &imported.csv)?;
    let n = imported.shots;
    let with_delivery = table.as_ref().map_or(0, |t| t.shots.len());
    // One sentence, wrapped to fit a terminal as the reports' prose is.
    eprint!(
        "{}",
        smash::report::text::wrap_long(&format!(
            "import: {n} shot{} ({with_delivery} with a complete delivery{}) from {} -> {}\n",
            if n == 1 { "" } else { "s" },
            if groups > 0 {
                format!(", {groups} group{}", if groups == 1 { "" } else { "s" })
            } else {
                String::new()
            },
            args.input.display(),
            args.out.display()
        ))
    );
    Ok(())
}
