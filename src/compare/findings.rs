//! The ranked findings of a comparison: a significant bias of a component, a strong trend with a
//! delivery variable, a difference between groups; each with the effects that produce such a
//! pattern (the library's table, and the user-defined effects whose measured signature can
//! cancel it).

use super::signatures::{hints_for, user_hint_text};
use super::tables::welch_t;
use super::user_hints::UserHints;
use super::{fmt_t, sig3, CompareOptions, CorrelationEntry, Finding, GroupBias, Pattern};
use crate::physics::LaunchComponent;

/// What the findings are drawn from.
pub(super) struct Evidence<'a> {
    /// Errors per shot, file units.
    pub errs: &'a [[f64; 5]],
    /// Group of each shot.
    pub group_of: &'a [&'a str],
    /// Distinct groups, sorted.
    pub groups: &'a [&'a str],
    /// Table 2 blocks: the groups', then `all`.
    pub table2: &'a [GroupBias],
    /// Every correlation.
    pub correlations: &'a [CorrelationEntry],
    /// Settings.
    pub o: &'a CompareOptions,
    /// Signatures of the user-defined effects.
    pub user: &'a UserHints,
}

impl Evidence<'_> {
    /// Every finding, strongest first.
    pub(super) fn findings(&self) -> Vec<Finding> {
        let mut findings = Vec::new();
        for c in LaunchComponent::ALL {
            let mut trends: Vec<&CorrelationEntry> = self
                .correlations
                .iter()
                .filter(|k| k.component == c.column() && k.strong)
                .collect();
            trends.sort_by(|a, b| b.t.abs().total_cmp(&a.t.abs()));
            findings.extend(self.bias(c, trends.first().copied()));
            findings.extend(trends.iter().map(|k| self.trend(c, k)));
            findings.extend(self.group_difference(c));
        }
        findings.sort_by(|a, b| b.strength.total_cmp(&a.strength));
        findings
    }

    /// The library's hints and the user-defined effects' for a finding whose sign is `sign`.
    fn hints(&self, c: LaunchComponent, pattern: &Pattern, sign: f64) -> Vec<String> {
        let mut h = hints_for(c, pattern);
        h.extend(self.user.hints(c, pattern, sign).iter().map(user_hint_text));
        h
    }

    /// A significant mean error of `c` over all shots (with its strongest trend, if any).
    fn bias(&self, c: LaunchComponent, trend: Option<&CorrelationEntry>) -> Option<Finding> {
        let all = self.table2.last().expect("all block");
        let ce = &all.components[c.index()];
        if !ce.significant {
            return None;
        }
        let (m, t, p) = (
            ce.summary.mean.unwrap_or(0.0),
            ce.summary.t.unwrap_or(0.0),
            ce.summary.p.unwrap_or(1.0),
        );
        let mut text = format!(
            "{} is {} {} too {} (t = {}, {})",
            c.label(),
            sig3(m.abs()),
            c.unit(),
            if m > 0.0 { "high" } else { "low" },
            fmt_t(t),
            fmt_p(p)
        );
        if let Some(k) = trend {
            text.push_str(&format!(
                ", {} (r = {:.2} with {})",
                direction(k.variable, k.r),
                k.r,
                k.variable
            ));
        }
        Some(Finding {
            component: c.column(),
            pattern: Pattern::Bias,
            strength: t.abs(),
            text,
            hints: self.hints(c, &Pattern::Bias, m),
        })
    }

    /// A strong trend of the error of `c` with a delivery variable.
    fn trend(&self, c: LaunchComponent, k: &CorrelationEntry) -> Finding {
        let pattern = Pattern::Trend(k.variable);
        Finding {
            component: c.column(),
            pattern,
            strength: k.t.abs(),
            text: format!(
                "{} error {} (r = {:.2}, t = {}, {})",
                c.label(),
                direction(k.variable, k.r),
                k.r,
                fmt_t(k.t),
                fmt_p(k.p)
            ),
            hints: self.hints(c, &pattern, k.r),
        }
    }

    /// Group differences of `c`: largest vs smallest group mean, Bonferroni over the pairs.
    fn group_difference(&self, c: LaunchComponent) -> Option<Finding> {
        let groups = self.groups;
        if groups.len() < 2 {
            return None;
        }
        let block = |g: &str| {
            self.table2
                .iter()
                .find(|b| b.group == g)
                .expect("group block")
        };
        let mean_of = |g: &str| block(g).components[c.index()].summary.mean.unwrap_or(0.0);
        let lo = groups
            .iter()
            .copied()
            .min_by(|a, b| mean_of(a).total_cmp(&mean_of(b)))?;
        let hi = groups
            .iter()
            .copied()
            .max_by(|a, b| mean_of(a).total_cmp(&mean_of(b)))?;
        let xs = |g: &str| -> Vec<f64> {
            self.errs
                .iter()
                .zip(self.group_of)
                .filter(|(_, sg)| **sg == g)
                .map(|(e, _)| e[c.index()])
                .collect()
        };
        let pairs = groups.len() * (groups.len() - 1) / 2;
        let (t, p) = welch_t(&xs(hi), &xs(lo))?;
        if !(p * (pairs as f64) < self.o.alpha) {
            return None;
        }
        let list: Vec<String> = groups
            .iter()
            .map(|g| format!("{g} {}", sig3(mean_of(g))))
            .collect();
        Some(Finding {
            component: c.column(),
            pattern: Pattern::GroupBias,
            strength: t.abs(),
            text: format!(
                "{} error differs between groups: {} {} (Welch t = {} for {hi} vs {lo}, {})",
                c.label(),
                list.join(", "),
                c.unit(),
                fmt_t(t),
                fmt_p(p)
            ),
            hints: self.hints(c, &Pattern::GroupBias, 0.0),
        })
    }
}

fn direction(variable: &str, r: f64) -> String {
    let up = r > 0.0;
    match variable {
        "impact_y_mm" => if up {
            "rises toward the crown"
        } else {
            "rises toward the sole"
        }
        .into(),
        "impact_z_mm" => if up {
            "rises toward the toe"
        } else {
            "rises toward the heel"
        }
        .into(),
        "impact_r_mm" => if up {
            "rises off-centre"
        } else {
            "falls off-centre"
        }
        .into(),
        v => format!("{} with {v}", if up { "rises" } else { "falls" }),
    }
}

fn fmt_p(p: f64) -> String {
    if p < 1e-16 {
        "p < 1e-16".into()
    } else {
        format!("p = {p:.1e}")
    }
}
