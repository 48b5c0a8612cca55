//! What `smash predict` reports for one delivery given on the command line, as one value:
//! [`OneShotReport`], the delivery, the launch and smash factor of its impact, and under
//! `--flight` the ball's flight. Its text ([`crate::report::render::Render`]) is a table of
//! labelled values in the file units.

use std::fmt::Write as _;

use crate::flight::Flight;
use crate::limits::fmt_value;
use crate::model::{DeliveryVar, N_DELIVERY};
use crate::physics::{ImpactOutcome, LaunchComponent};
use crate::report::render::Render;

/// One delivery's impact (and flight).
pub struct OneShotReport {
    /// The club's name.
    pub club: String,
    /// The group whose model struck.
    pub group: String,
    /// The delivery, file units, in [`DeliveryVar::ALL`] order.
    pub delivery: [f64; N_DELIVERY],
    /// The impact.
    pub outcome: ImpactOutcome,
    /// The ball's flight and where the ball started (`Ball start`), under `--flight`.
    pub flight: Option<(Flight, String)>,
}

impl Render for OneShotReport {
    type Context = ();

    fn text(&self, _: &()) -> String {
        let value = |v: DeliveryVar| fmt_value(self.delivery[v.index()]);
        let launch = self.outcome.launch();
        let mut text = format!("{} (group {})\n", self.club, self.group);
        // Writing to a String cannot fail.
        let _ = writeln!(
            text,
            "delivery: {} mph, loft {} deg, attack {} deg, path {} deg, face {} deg, lie {} deg, \
             impact ({} mm up, {} mm toe)",
            value(DeliveryVar::ClubSpeed),
            value(DeliveryVar::DynamicLoft),
            value(DeliveryVar::AttackAngle),
            value(DeliveryVar::ClubPath),
            value(DeliveryVar::FaceAngle),
            value(DeliveryVar::LieTilt),
            value(DeliveryVar::ImpactY),
            value(DeliveryVar::ImpactZ),
        );
        for c in LaunchComponent::ALL {
            let _ = writeln!(
                text,
                "{:<14} {:>10.2} {}",
                c.label(),
                launch.get_file(c),
                c.unit()
            );
        }
        let _ = writeln!(
            text,
            "{:<14} {:>10.4}",
            "Smash factor",
            self.outcome.smash_factor()
        );
        if let Some((f, start)) = &self.flight {
            let _ = writeln!(text, "{:<14} {:>13}", "Ball start", start);
            let _ = writeln!(text, "{:<14} {:>10.1} yd", "Carry", f.carry_yd());
            let _ = writeln!(text, "{:<14} {:>10.1} yd", "Offline", f.offline_yd());
            let _ = writeln!(text, "{:<14} {:>10.1} yd", "Apex", f.apex_yd());
            let _ = writeln!(text, "{:<14} {:>10.2} s", "Flight time", f.flight_time_s);
            let _ = writeln!(
                text,
                "{:<14} {:>10.1} deg",
                "Land angle",
                f.land_angle_deg()
            );
            if let Some(t) = f.total_yd() {
                let _ = writeln!(text, "{:<14} {:>10.1} yd", "Total", t);
            }
        }
        text
    }
}
