//! A shot's own mass and geometry, on one shot or on lanes of shots: what the pre-solve terms
//! of user-defined effects (and the library's `shaft_fraction`, written as one) set shot by
//! shot: the clubhead mass, CoM and inertia and the ball's contact offsets. The one definition
//! the scalar solve ([`ImpactModel::shot`]) and the fits' lanes both run, so a lane gets the
//! bits of its shot.

use super::{ImpactModel, Real};
use crate::lanes::LaneMask;
use crate::physics::laws::CollisionLanes;
use crate::physics::user_terms::{PreSolve, NV};

/// The constants of the contact solve that a shot may have of its own ([`ImpactModel::solve_contact_shot`]).
#[derive(Debug, Clone, Copy)]
pub struct ShotConsts<R> {
    /// Collision constants with the shot's clubhead mass and inertia.
    pub collision: CollisionLanes<R>,
    /// Clubhead CoM, F, m.
    pub club_com_m: [R; 3],
    /// Ball contact offsets `dy`, `dz` along `y_I`, `z_I`, m.
    pub ball_offset_m: [R; 2],
    /// Clubhead mass, kg.
    pub club_mass_kg: R,
}

/// `a ≠ b` lane by lane, for finite values (the values a pre-solve term may give).
#[inline(always)]
fn differs<R: Real>(a: R, b: R) -> R::Mask {
    a.gt(b) | b.gt(a)
}

impl ImpactModel {
    /// The model's own constants on every lane.
    #[inline(always)]
    pub fn shot_consts<R: Real>(&self) -> ShotConsts<R> {
        let p = &self.params;
        let s = R::splat;
        let com = &p.club_com_m;
        ShotConsts {
            collision: self.laws.collision.lanes(),
            club_com_m: [s(com.x), s(com.y), s(com.z)],
            ball_offset_m: [s(self.laws.ball.offset_y_m), s(self.laws.ball.offset_z_m)],
            club_mass_kg: s(p.club_mass_kg),
        }
    }

    /// The constants of shots whose delivery variables are `vars`
    /// ([`crate::physics::user_terms::delivery_vars`], one shot a lane) with the mass and
    /// geometry terms of the model's user-defined effects evaluated
    /// ([`crate::physics::user_terms::UserTerms::pre_solve_lanes`]). A quantity no term changed
    /// keeps the model's own value, bit for bit. Lanes where a term's value is not allowed, or
    /// the ball's contact offset leaves the ball, are cleared from `valid` (the scalar
    /// [`ImpactModel::shot`] names the cause). Loft and face-angle terms are not applied here:
    /// they turn the face, which [`ImpactModel::shot`] does.
    // Index loops, not iterators, in lane code (see `crate::lanes::each2`).
    #[allow(clippy::needless_range_loop)]
    #[inline(always)]
    pub fn shot_consts_of<R: Real>(
        &self,
        vars: &mut [R; NV],
        valid: &mut R::Mask,
    ) -> ShotConsts<R> {
        let p = &self.params;
        let s = R::splat;
        let mut c = self.shot_consts::<R>();
        let base = PreSolve {
            club_mass_g: s(p.club_mass_kg * 1e3),
            ball_d_mm: [s(p.ball_offset_y_m * 1e3), s(p.ball_offset_z_m * 1e3)],
            com_d_mm: [s(0.0); 3],
            inertia_scale: s(1.0),
            loft_deg: s(0.0),
            face_deg: s(0.0),
        };
        let pre = self.laws.user.pre_solve_lanes(vars, base, valid);
        let mass = differs(pre.club_mass_g, base.club_mass_g);
        if mass.any() {
            let m = pre.club_mass_g * 1e-3;
            let ims = s(1.0) / m + 1.0 / p.ball_mass_kg;
            c.club_mass_kg = R::select(mass, m, c.club_mass_kg);
            c.collision.inv_mass_sum = R::select(mass, ims, c.collision.inv_mass_sum);
        }
        let scale = differs(pre.inertia_scale, base.inertia_scale);
        if scale.any() {
            let j = &mut c.collision.club_inv_inertia;
            for k in 0..6 {
                j[k] = R::select(scale, j[k] / pre.inertia_scale, j[k]);
            }
        }
        let [dx, dy, dz] = pre.com_d_mm;
        let com = differs(dx, s(0.0)) | differs(dy, s(0.0)) | differs(dz, s(0.0));
        if com.any() {
            let [cx, cy, cz] = c.club_com_m;
            c.club_com_m = [
                R::select(com, cx + dx * 1e-3, cx),
                R::select(com, cy + dy * 1e-3, cy),
                R::select(com, cz + dz * 1e-3, cz),
            ];
        }
        let [by, bz] = pre.ball_d_mm;
        let ball = differs(by, base.ball_d_mm[0]) | differs(bz, base.ball_d_mm[1]);
        if ball.any() {
            let (oy, oz) = (by * 1e-3, bz * 1e-3);
            let inside = s(p.ball_radius_m).gt(oy.zip_map(oz, f64::hypot));
            *valid = *valid & ball.select_mask(inside, !R::no());
            c.ball_offset_m = [
                R::select(ball, oy, c.ball_offset_m[0]),
                R::select(ball, oz, c.ball_offset_m[1]),
            ];
        }
        c
    }
}
