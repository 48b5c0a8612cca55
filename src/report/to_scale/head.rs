//! A clubhead seen from above or from behind, to scale in the face frame F (mm from the face
//! centre): the face, the hosel, the CoM before and after a change and the moved mass's
//! places. A CoM shift too short to see at the head's scale is drawn again, magnified by a
//! stated factor, beside the true one.

use std::fmt::Write as _;

use super::{arrow, fin, Frame, BASE_COLOUR, CHANGED_COLOUR};
use crate::report::html::esc;

/// Which way the head is seen.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum View {
    /// From above: toward the toe across, toward the face up (the face on top).
    Above,
    /// From behind, looking toward the face: toward the toe across, up up.
    Behind,
}

/// A mass moved within the head.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MovedMass {
    /// Its mass, g.
    pub mass_g: f64,
    /// Where it was, mm (F frame: x toward the face, y up, z toward the toe).
    pub from_mm: [f64; 3],
    /// Where it is moved to, mm.
    pub to_mm: [f64; 3],
}

/// What a head view shows, mm in the F frame.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HeadPoints {
    /// The base head's CoM, mm.
    pub com_before_mm: [f64; 3],
    /// The changed head's CoM, mm.
    pub com_after_mm: [f64; 3],
    /// The hosel (top of the bore on the shaft axis), mm.
    pub hosel_mm: [f64; 3],
    /// The mass moved, if one was.
    pub mass: Option<MovedMass>,
}

impl View {
    /// `(across, up)` of a point of F, mm.
    fn plane(self, p: [f64; 3]) -> (f64, f64) {
        match self {
            View::Above => (fin(p[2]), fin(p[0])),
            View::Behind => (fin(p[2]), fin(p[1])),
        }
    }

    fn title(self) -> &'static str {
        match self {
            View::Above => "The head from above (face on top)",
            View::Behind => "The head from behind (looking at the face)",
        }
    }

    fn kind(self) -> &'static str {
        match self {
            View::Above => "head-above",
            View::Behind => "head-behind",
        }
    }

    fn y_label(self) -> &'static str {
        match self {
            View::Above => "x, mm (toward the face)",
            View::Behind => "y, mm (up)",
        }
    }
}

/// The head seen from `view`.
pub fn head_view_svg(h: &HeadPoints, view: View) -> String {
    let mut pts = vec![
        (0.0, 0.0),
        view.plane(h.com_before_mm),
        view.plane(h.com_after_mm),
        view.plane(h.hosel_mm),
    ];
    if let Some(m) = &h.mass {
        pts.extend([view.plane(m.from_mm), view.plane(m.to_mm)]);
    }
    let f = Frame::holding(&pts, 12.0, 60.0, 340.0);
    let mut s = String::new();
    f.open(&mut s, view.title(), view.kind());
    f.axes(&mut s, "z, mm (toward the toe)", view.y_label());
    draw_face(&mut s, &f, view);
    let (hx, hy) = view.plane(h.hosel_mm);
    let (hx, hy) = (f.px(hx), f.py(hy));
    let _ = writeln!(
        s,
        r##"<g class="hosel"><rect x="{:.2}" y="{:.2}" width="10" height="10" fill="#777"/><text x="{:.2}" y="{:.2}" fill="#555">hosel</text></g>"##,
        hx - 5.0,
        hy - 5.0,
        hx + 9.0,
        hy - 7.0
    );
    if let Some(m) = &h.mass {
        draw_mass(&mut s, &f, view, m);
    }
    draw_com(&mut s, &f, view, h);
    let mut legend = vec![
        (dot(BASE_COLOUR, true), "CoM before".to_owned()),
        (dot(CHANGED_COLOUR, true), "CoM after".to_owned()),
    ];
    if h.mass.is_some() {
        legend.push((dot("#333", false), "mass from".to_owned()));
        legend.push((dot("#333", true), "to".to_owned()));
    }
    f.legend(&mut s, &legend);
    s.push_str("</svg>\n");
    s
}

/// A legend swatch: a dot, filled or hollow.
fn dot(colour: &str, filled: bool) -> String {
    let fill = if filled { colour } else { "white" };
    format!(r#"<circle cx="0" cy="0" r="5" fill="{fill}" stroke="{colour}" stroke-width="2"/>"#)
}

/// The face: from above, its plane (x = 0) across the picture; from behind, a cross at the
/// face centre. Both views mark the face centre.
fn draw_face(s: &mut String, f: &Frame, view: View) {
    let (cx, cy) = (f.px(0.0), f.py(0.0));
    if view == View::Above {
        let _ = writeln!(
            s,
            r##"<g class="face"><line x1="{}" y1="{cy:.2}" x2="{}" y2="{cy:.2}" stroke="#444" stroke-width="3"/><text x="{}" y="{:.2}" fill="#444">face (x = 0)</text></g>"##,
            f.left,
            f.left + f.plot_w,
            f.left + 4.0,
            cy - 6.0
        );
    }
    let _ = writeln!(
        s,
        r##"<g class="face-centre" stroke="#444" stroke-width="1.5" fill="none"><circle cx="{cx:.2}" cy="{cy:.2}" r="5"/><line x1="{:.2}" y1="{cy:.2}" x2="{:.2}" y2="{cy:.2}"/><line x1="{cx:.2}" y1="{:.2}" x2="{cx:.2}" y2="{:.2}"/></g><text x="{:.2}" y="{:.2}" fill="#444">face centre</text>"##,
        cx - 9.0,
        cx + 9.0,
        cy - 9.0,
        cy + 9.0,
        cx + 8.0,
        cy + 18.0
    );
}

/// The moved mass: a hollow dot where it was, a filled one where it goes, an arrow between and
/// its mass beside the arrow.
fn draw_mass(s: &mut String, f: &Frame, view: View, m: &MovedMass) {
    let (a, b) = (view.plane(m.from_mm), view.plane(m.to_mm));
    let (a, b) = ((f.px(a.0), f.py(a.1)), (f.px(b.0), f.py(b.1)));
    arrow(s, "mass-move", a, b, "#333");
    let _ = writeln!(
        s,
        r##"<circle class="mass from" cx="{:.2}" cy="{:.2}" r="6" fill="white" stroke="#333" stroke-width="2"/><circle class="mass to" cx="{:.2}" cy="{:.2}" r="6" fill="#333"/><text x="{:.2}" y="{:.2}" fill="#333">{} g</text>"##,
        a.0,
        a.1,
        b.0,
        b.1,
        b.0 + 9.0,
        b.1 + 16.0,
        crate::limits::fmt_value(m.mass_g)
    );
}

/// The CoM before and after, the true shift between them and, when that is shorter than
/// 20 px, the shift again magnified by a round factor to about 45 px, labelled.
fn draw_com(s: &mut String, f: &Frame, view: View, h: &HeadPoints) {
    let (a, b) = (view.plane(h.com_before_mm), view.plane(h.com_after_mm));
    let (pa, pb) = ((f.px(a.0), f.py(a.1)), (f.px(b.0), f.py(b.1)));
    let shift_px = (pb.0 - pa.0).hypot(pb.1 - pa.1);
    let shift_mm = (b.0 - a.0).hypot(b.1 - a.1);
    arrow(s, "com-shift", pa, pb, CHANGED_COLOUR);
    if shift_px > 0.0 && shift_px < 20.0 {
        let k = [2.0, 5.0, 10.0, 20.0, 50.0, 100.0, 200.0, 500.0, 1000.0]
            .into_iter()
            .find(|k| k * shift_px >= 30.0)
            .unwrap_or(1000.0);
        let end = (pa.0 + k * (pb.0 - pa.0), pa.1 + k * (pb.1 - pa.1));
        arrow(s, "com-shift-magnified", pa, end, CHANGED_COLOUR);
        // The label beyond the arrow's tip, on the side it points to.
        let (anchor, dx) = if end.0 < pa.0 {
            ("end", -6.0)
        } else {
            ("start", 6.0)
        };
        let dy = if end.1 < pa.1 { -6.0 } else { 16.0 };
        let _ = writeln!(
            s,
            r##"<text x="{:.2}" y="{:.2}" text-anchor="{anchor}" fill="{CHANGED_COLOUR}">shift ×{k} ({shift_mm:.2} mm)</text>"##,
            end.0 + dx,
            end.1 + dy
        );
    }
    for (class, p, colour, r) in [
        ("com before", pa, BASE_COLOUR, 7.0),
        ("com after", pb, CHANGED_COLOUR, 4.5),
    ] {
        let _ = writeln!(
            s,
            r#"<circle class="{class}" cx="{:.2}" cy="{:.2}" r="{r}" fill="{colour}" stroke="white" stroke-width="1"/>"#,
            p.0, p.1
        );
    }
    let _ = writeln!(
        s,
        r#"<text x="{:.2}" y="{:.2}" text-anchor="middle">{}</text>"#,
        pa.0,
        pa.1 - 13.0,
        esc("CoM")
    );
}
