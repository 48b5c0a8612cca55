//! Swings and distributions of swings and impact locations.
//!
//! A [`Distribution`] is independent Gaussians on the impact location (centre and σ per axis)
//! and on the swing (club speed, attack, path, dynamic loft, face angle; σ = 0 keeps a quantity
//! fixed at the study's swing). Expectations are evaluated either by deterministic tensor-product
//! Gauss–Hermite quadrature over the dimensions with σ > 0 (`nodes` per dimension; exact for
//! polynomials of degree up to `2·nodes − 1` in each variable), or by `samples` fixed-seed
//! pseudo-random draws (ChaCha8, `seed`), each of weight `1/samples`.

use nalgebra::{DMatrix, Vector3};
use rand::SeedableRng;
use rand_distr::{Distribution as _, StandardNormal};

use crate::physics::Delivery;
use crate::units::{deg, mm, mph};

/// A swing in file units (impact location not included).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SwingSpec {
    /// Clubhead CoM speed, mph (> 0).
    pub club_speed_mph: f64,
    /// Dynamic loft, deg.
    pub dynamic_loft_deg: f64,
    /// Attack angle, deg (+ up).
    pub attack_angle_deg: f64,
    /// Club path, deg (+ right of target).
    pub club_path_deg: f64,
    /// Face angle, deg (+ open).
    pub face_angle_deg: f64,
    /// Lie tilt, deg (+ toe up).
    pub lie_tilt_deg: f64,
    /// Clubhead angular velocity in G, rad/s.
    pub club_omega_rad_s: [f64; 3],
}

impl SwingSpec {
    /// The delivery of this swing at impact location `(y, z)` (mm up, toward the toe).
    pub fn delivery(&self, y_mm: f64, z_mm: f64) -> Delivery {
        let w = self.club_omega_rad_s;
        Delivery {
            club_speed_m_s: mph(self.club_speed_mph),
            attack_angle_rad: deg(self.attack_angle_deg),
            club_path_rad: deg(self.club_path_deg),
            dynamic_loft_rad: deg(self.dynamic_loft_deg),
            face_angle_rad: deg(self.face_angle_deg),
            lie_tilt_rad: deg(self.lie_tilt_deg),
            club_omega_rad_s: Vector3::new(w[0], w[1], w[2]),
            impact_y_m: mm(y_mm),
            impact_z_m: mm(z_mm),
            shaft_mass_g: None,
        }
    }
}

/// How expectations are evaluated.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Method {
    /// Tensor-product Gauss–Hermite quadrature, `nodes` per dimension with σ > 0.
    Quadrature {
        /// Nodes per dimension (1–20).
        nodes: usize,
    },
    /// Fixed-seed random samples.
    Samples {
        /// Number of draws.
        samples: usize,
        /// Seed of the ChaCha8 generator.
        seed: u64,
    },
}

/// Independent Gaussian scatter of impact location and swing.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Distribution {
    /// Evaluation method.
    pub method: Method,
    /// Mean impact location `[y, z]`, mm.
    pub impact_centre_mm: [f64; 2],
    /// σ of the impact height, mm.
    pub sigma_y_mm: f64,
    /// σ of the heel–toe impact location, mm.
    pub sigma_z_mm: f64,
    /// σ of club speed, mph.
    pub sigma_club_speed_mph: f64,
    /// σ of attack angle, deg.
    pub sigma_attack_angle_deg: f64,
    /// σ of club path, deg.
    pub sigma_club_path_deg: f64,
    /// σ of dynamic loft, deg.
    pub sigma_dynamic_loft_deg: f64,
    /// σ of face angle, deg.
    pub sigma_face_angle_deg: f64,
}

/// Impacts that share one swing, with their weights (all weights of a distribution sum to 1).
#[derive(Debug, Clone, PartialEq)]
pub struct SwingGroup {
    /// The swing.
    pub swing: SwingSpec,
    /// Impact heights, m.
    pub ys_m: Vec<f64>,
    /// Impact heel–toe locations, m.
    pub zs_m: Vec<f64>,
    /// Weights.
    pub weights: Vec<f64>,
}

/// Probabilists' Gauss–Hermite rule for the standard normal (Golub–Welsch): nodes ascending,
/// weights summing to 1.
pub fn gauss_hermite(n: usize) -> (Vec<f64>, Vec<f64>) {
    assert!(n >= 1);
    let j = DMatrix::from_fn(n, n, |i, k| {
        if k == i + 1 || i == k + 1 {
            (i.max(k) as f64).sqrt()
        } else {
            0.0
        }
    });
    let eig = j.symmetric_eigen();
    let mut pairs: Vec<(f64, f64)> = (0..n)
        .map(|i| (eig.eigenvalues[i], eig.eigenvectors[(0, i)].powi(2)))
        .collect();
    pairs.sort_by(|a, b| a.0.total_cmp(&b.0));
    // Symmetrise: the exact rule is symmetric about 0.
    let mut nodes: Vec<f64> = pairs.iter().map(|p| p.0).collect();
    let mut weights: Vec<f64> = pairs.iter().map(|p| p.1).collect();
    for i in 0..n / 2 {
        let (a, b) = (i, n - 1 - i);
        let x = 0.5 * (nodes[b] - nodes[a]);
        let w = 0.5 * (weights[a] + weights[b]);
        nodes[a] = -x;
        nodes[b] = x;
        weights[a] = w;
        weights[b] = w;
    }
    if n % 2 == 1 {
        nodes[n / 2] = 0.0;
    }
    let sum: f64 = weights.iter().sum();
    weights.iter_mut().for_each(|w| *w /= sum);
    (nodes, weights)
}

impl Distribution {
    fn swing_sigmas(&self) -> [f64; 5] {
        [
            self.sigma_club_speed_mph,
            self.sigma_attack_angle_deg,
            self.sigma_club_path_deg,
            self.sigma_dynamic_loft_deg,
            self.sigma_face_angle_deg,
        ]
    }

    fn perturbed(base: &SwingSpec, sigmas: &[f64; 5], z: &[f64; 5]) -> SwingSpec {
        SwingSpec {
            club_speed_mph: base.club_speed_mph + sigmas[0] * z[0],
            attack_angle_deg: base.attack_angle_deg + sigmas[1] * z[1],
            club_path_deg: base.club_path_deg + sigmas[2] * z[2],
            dynamic_loft_deg: base.dynamic_loft_deg + sigmas[3] * z[3],
            face_angle_deg: base.face_angle_deg + sigmas[4] * z[4],
            ..*base
        }
    }

    /// Number of impacts the distribution evaluates.
    pub fn point_count(&self) -> usize {
        match self.method {
            Method::Samples { samples, .. } => samples,
            Method::Quadrature { nodes } => {
                let dims = self
                    .swing_sigmas()
                    .iter()
                    .chain([self.sigma_y_mm, self.sigma_z_mm].iter())
                    .filter(|s| **s > 0.0)
                    .count();
                nodes.saturating_pow(dims as u32)
            }
        }
    }

    /// The impacts and weights, grouped by swing, in a fixed order.
    pub fn groups(&self, base: &SwingSpec) -> Vec<SwingGroup> {
        let sig = self.swing_sigmas();
        let [cy, cz] = self.impact_centre_mm;
        match self.method {
            Method::Quadrature { nodes } => {
                let (x, w) = gauss_hermite(nodes);
                let rule = |s: f64| -> Vec<(f64, f64)> {
                    if s > 0.0 {
                        x.iter().copied().zip(w.iter().copied()).collect()
                    } else {
                        vec![(0.0, 1.0)]
                    }
                };
                let mut swings: Vec<([f64; 5], f64)> = vec![([0.0; 5], 1.0)];
                for (d, s) in sig.iter().enumerate() {
                    let r = rule(*s);
                    swings = swings
                        .into_iter()
                        .flat_map(|(z, wz)| {
                            r.iter().map(move |(xi, wi)| {
                                let mut z2 = z;
                                z2[d] = *xi;
                                (z2, wz * wi)
                            })
                        })
                        .collect();
                }
                let (ry, rz) = (rule(self.sigma_y_mm), rule(self.sigma_z_mm));
                swings
                    .into_iter()
                    .map(|(z, ws)| {
                        let mut g = SwingGroup {
                            swing: Self::perturbed(base, &sig, &z),
                            ys_m: Vec::new(),
                            zs_m: Vec::new(),
                            weights: Vec::new(),
                        };
                        for (uy, wy) in &ry {
                            for (uz, wz) in &rz {
                                g.ys_m.push(mm(cy + self.sigma_y_mm * uy));
                                g.zs_m.push(mm(cz + self.sigma_z_mm * uz));
                                g.weights.push(ws * wy * wz);
                            }
                        }
                        g
                    })
                    .collect()
            }
            Method::Samples { samples, seed } => {
                let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(seed);
                let w = 1.0 / samples as f64;
                let swing_varies = sig.iter().any(|s| *s > 0.0);
                let mut groups: Vec<SwingGroup> = Vec::new();
                for _ in 0..samples {
                    let mut z = [0.0; 7];
                    for zi in z.iter_mut() {
                        *zi = StandardNormal.sample(&mut rng);
                    }
                    let swing = Self::perturbed(base, &sig, &[z[0], z[1], z[2], z[3], z[4]]);
                    if groups.is_empty() || swing_varies {
                        groups.push(SwingGroup {
                            swing,
                            ys_m: Vec::new(),
                            zs_m: Vec::new(),
                            weights: Vec::new(),
                        });
                    }
                    let g = groups.last_mut().expect("one group");
                    g.ys_m.push(mm(cy + self.sigma_y_mm * z[5]));
                    g.zs_m.push(mm(cz + self.sigma_z_mm * z[6]));
                    g.weights.push(w);
                }
                groups
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    #[test]
    fn gauss_hermite_integrates_normal_moments() {
        for n in 1..=10 {
            let (x, w) = gauss_hermite(n);
            let m = |k: i32| x.iter().zip(&w).map(|(x, w)| w * x.powi(k)).sum::<f64>();
            assert_relative_eq!(m(0), 1.0, epsilon = 1e-13);
            if n >= 2 {
                assert_relative_eq!(m(2), 1.0, epsilon = 1e-12);
                assert!(m(1).abs() < 1e-13);
            }
            if n >= 3 {
                assert_relative_eq!(m(4), 3.0, epsilon = 1e-11);
            }
        }
    }

    #[test]
    fn quadrature_weights_sum_to_one_over_all_dimensions() {
        let base = SwingSpec {
            club_speed_mph: 100.0,
            dynamic_loft_deg: 12.0,
            attack_angle_deg: 0.0,
            club_path_deg: 0.0,
            face_angle_deg: 0.0,
            lie_tilt_deg: 0.0,
            club_omega_rad_s: [0.0; 3],
        };
        let d = Distribution {
            method: Method::Quadrature { nodes: 3 },
            impact_centre_mm: [1.0, 2.0],
            sigma_y_mm: 4.0,
            sigma_z_mm: 6.0,
            sigma_club_speed_mph: 2.0,
            sigma_attack_angle_deg: 0.0,
            sigma_club_path_deg: 0.0,
            sigma_dynamic_loft_deg: 0.0,
            sigma_face_angle_deg: 1.0,
        };
        let g = d.groups(&base);
        assert_eq!(g.len(), 9);
        let n: usize = g.iter().map(|g| g.weights.len()).sum();
        assert_eq!(n, d.point_count());
        let total: f64 = g.iter().flat_map(|g| g.weights.iter()).sum();
        assert_relative_eq!(total, 1.0, epsilon = 1e-13);
        let mean_z: f64 = g
            .iter()
            .flat_map(|g| g.zs_m.iter().zip(&g.weights).map(|(z, w)| z * w))
            .sum();
        assert_relative_eq!(mean_z, 0.002, epsilon = 1e-15);
    }
}
