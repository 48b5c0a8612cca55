#!/usr/bin/env python3
"""Reference launch values for the golden tests, from first principles.

An implementation of the impact model of docs/conventions.md that shares no code with the
Rust engine: plain Python (standard library only), and instead of the engine's reduced 3x3
solve `K P = ...` it writes the paper's impulse-momentum equations out as one 15x15 linear
system in the unknowns

    P (impulse on the ball), v_b', w_b' (ball after), v_c', w_c' (clubhead after)

and solves it by Gaussian elimination with partial pivoting:

    m_c (v_c' - v_c) = -P                  clubhead linear momentum
    I_c (w_c' - w_c) = -(r_c x P)          clubhead angular momentum about its CoM
    m_b v_b'         =  P                  ball linear momentum (ball at rest before)
    I_b w_b'         =  r_b x P            ball angular momentum about its centre
    u2 . n           = -e (u1 . n)         normal restitution
    u2 . t_k         = -e_t (u1 . t_k)     tangential restitution (e_t = 0: no slip), k = y, z

with u1, u2 the velocity of the clubhead's contact point relative to the ball's, before and
after. With the `friction` effect, when the no-slip impulse needs more than mu times its
normal part, the two tangential rows become the gross-slip law P . t_k = mu (P . n)(s . t_k),
s the unit tangential direction of u1.

Usage:
    python3 generate.py            write <case>.csv for every case below, beside this script
    python3 generate.py --check D  compare with the files in D, print the largest difference

Input deliveries come from deliveries.csv (beside this script); the club is the paper
driver (Danaei et al., Table 1), as in configs/clubs/paper_driver.toml.
"""

import csv
import math
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))

MPH = 0.44704  # m/s per mph (exact, international mile)
RPM = 2.0 * math.pi / 60.0  # rad/s per rpm
GCM2 = 1e-7  # kg m^2 per g cm^2
COR_SPEED_REFERENCE_M_S = 48.77  # reference normal speed of the cor_speed effect

# The paper driver (Danaei et al., Table 1) and the ball.
CLUB = {
    "mass_kg": 0.204,
    "com_mm": [-42.3, 2.9, 1.0],
    "inertia_gcm2": [[2843.0, -733.0, 530.2], [-733.0, 5679.0, 0.5], [530.2, 0.5, 4085.0]],
    "cor": 0.83,
    "bulge_mm": 305.0,
    "roll_mm": 305.0,
    "ball_mass_kg": 0.0459,
    "ball_radius_mm": 21.3,
    "ball_inertia_gcm2": 83.63,
}

# One effect per file: (file name, effect name, parameters).
CASES = [
    ("nominal", None, {}),
    ("added_mass", "added_mass", {"dm_g": 2.54}),
    ("ball_offset", "ball_offset", {"dy_mm": 0.48, "dz_mm": -0.07}),
    ("tangential_restitution", "tangential_restitution", {"et": -0.2}),
    ("friction", "friction", {"mu": 0.05}),
    ("cor_speed", "cor_speed", {"k_per_m_s": 0.002}),
    ("cor_radial", "cor_radial", {"c_per_mm2": 0.0002}),
    ("loft_bias", "loft_bias", {"deg": 1.0}),
    ("face_bias", "face_bias", {"deg": -1.5}),
    ("com_offset", "com_offset", {"dx_mm": -3.0, "dy_mm": -2.0, "dz_mm": 1.5}),
    ("inertia_scale", "inertia_scale", {"s": 1.2}),
]

INPUTS = [
    "shot_id",
    "club_speed_mph",
    "attack_angle_deg",
    "club_path_deg",
    "dynamic_loft_deg",
    "face_angle_deg",
    "lie_tilt_deg",
    "club_omega_x_rad_s",
    "club_omega_y_rad_s",
    "club_omega_z_rad_s",
    "impact_y_mm",
    "impact_z_mm",
]
OUTPUTS = [
    "pred_ball_speed_mph",
    "pred_launch_angle_deg",
    "pred_azimuth_deg",
    "pred_backspin_rpm",
    "pred_sidespin_rpm",
]


# --- small vector algebra -------------------------------------------------------------


def add(a, b):
    return [a[i] + b[i] for i in range(3)]


def sub(a, b):
    return [a[i] - b[i] for i in range(3)]


def scale(k, a):
    return [k * x for x in a]


def dot(a, b):
    return sum(a[i] * b[i] for i in range(3))


def cross(a, b):
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


def norm(a):
    return math.sqrt(dot(a, a))


def matvec(m, v):
    return [dot(m[i], v) for i in range(3)]


def cross_matrix(a):
    """[a]x such that [a]x b = a x b."""
    return [[0.0, -a[2], a[1]], [a[2], 0.0, -a[0]], [-a[1], a[0], 0.0]]


def solve(a, b):
    """Solve a x = b (square, dense) by Gaussian elimination with partial pivoting."""
    n = len(b)
    m = [row[:] + [b[i]] for i, row in enumerate(a)]
    for col in range(n):
        piv = max(range(col, n), key=lambda r: abs(m[r][col]))
        if abs(m[piv][col]) < 1e-300:
            raise ValueError("singular impact system")
        m[col], m[piv] = m[piv], m[col]
        for r in range(col + 1, n):
            f = m[r][col] / m[col][col]
            if f != 0.0:
                for c in range(col, n + 1):
                    m[r][c] -= f * m[col][c]
    x = [0.0] * n
    for r in range(n - 1, -1, -1):
        x[r] = (m[r][n] - sum(m[r][c] * x[c] for c in range(r + 1, n))) / m[r][r]
    return x


# --- geometry -------------------------------------------------------------------------


def face_axes(loft, face, lie):
    """Columns x_F, y_F, z_F of the face frame in the ground frame."""
    xf = [math.cos(loft) * math.cos(face), math.sin(loft), math.cos(loft) * math.sin(face)]
    z0 = [-math.sin(face), 0.0, math.cos(face)]
    y0 = cross(z0, xf)
    yf = sub(scale(math.cos(lie), y0), scale(math.sin(lie), z0))
    zf = add(scale(math.sin(lie), y0), scale(math.cos(lie), z0))
    return xf, yf, zf


def to_ground(axes, v):
    """Components v in the frame whose axes (in G) are `axes` -> components in G."""
    return [sum(axes[k][i] * v[k] for k in range(3)) for i in range(3)]


def contact(bulge, roll, y, z):
    """Contact point and impact-frame axes (x_I, y_I, z_I) in the face frame, lengths in m.

    The face is a torus with heel-toe radius `bulge` and crown-sole radius `roll` at the
    centre of face; the point is found from its two radii of curvature geometrically: the
    vertical section at height y is a circle of radius rho = (bulge - roll) + sqrt(roll^2 - y^2)
    about the axis x = -bulge, z = 0 (parallel to y_F).
    """
    major = bulge - roll
    s = math.sqrt(roll * roll - y * y)
    rho = major + s
    big_x = math.sqrt(rho * rho - z * z)
    p = [big_x - bulge, y, z]
    # Normal: from the nearest point of the tube's centre circle to p, normalised.
    centre = [-bulge + major * big_x / rho, 0.0, major * z / rho]
    n = sub(p, centre)
    n = scale(1.0 / norm(n), n)
    tz = scale(1.0 / rho, [-z, 0.0, big_x])
    ty = cross(tz, n)
    return p, n, ty, tz


# --- the impact -----------------------------------------------------------------------


def launch(row, effect, par):
    c = CLUB
    m_c = c["mass_kg"]
    com = [x * 1e-3 for x in c["com_mm"]]
    inertia_f = [[x * GCM2 for x in r] for r in c["inertia_gcm2"]]
    cor = c["cor"]
    m_b = c["ball_mass_kg"]
    radius = c["ball_radius_mm"] * 1e-3
    i_b = c["ball_inertia_gcm2"] * GCM2
    rb_i = [-radius, 0.0, 0.0]
    e_t = 0.0
    mu = None

    speed = float(row["club_speed_mph"]) * MPH
    attack = math.radians(float(row["attack_angle_deg"]))
    path = math.radians(float(row["club_path_deg"]))
    loft = math.radians(float(row["dynamic_loft_deg"]))
    face = math.radians(float(row["face_angle_deg"]))
    lie = math.radians(float(row["lie_tilt_deg"]))
    w_c = [float(row[f"club_omega_{a}_rad_s"]) for a in "xyz"]
    y_mm = float(row["impact_y_mm"])
    z_mm = float(row["impact_z_mm"])

    if effect == "added_mass":
        m_c += par["dm_g"] * 1e-3
    elif effect == "ball_offset":
        rb_i = [-radius, par["dy_mm"] * 1e-3, par["dz_mm"] * 1e-3]
    elif effect == "tangential_restitution":
        e_t = par["et"]
    elif effect == "friction":
        mu = par["mu"]
    elif effect == "cor_radial":
        cor = cor - par["c_per_mm2"] * (y_mm * y_mm + z_mm * z_mm)
    elif effect == "loft_bias":
        loft += math.radians(par["deg"])
    elif effect == "face_bias":
        face += math.radians(par["deg"])
    elif effect == "com_offset":
        com = add(com, [par["dx_mm"] * 1e-3, par["dy_mm"] * 1e-3, par["dz_mm"] * 1e-3])
    elif effect == "inertia_scale":
        inertia_f = [[par["s"] * x for x in r] for r in inertia_f]

    axes_f = face_axes(loft, face, lie)
    p_f, n_f, ty_f, tz_f = contact(c["bulge_mm"] * 1e-3, c["roll_mm"] * 1e-3, y_mm * 1e-3, z_mm * 1e-3)
    n = to_ground(axes_f, n_f)
    ty = to_ground(axes_f, ty_f)
    tz = to_ground(axes_f, tz_f)
    r_c = to_ground(axes_f, sub(p_f, com))
    # Ball centre -> contact point, given in the impact frame I.
    r_b = to_ground((n, ty, tz), rb_i)
    # Clubhead inertia in G: R I_F R^T.
    rot = [[axes_f[k][i] for k in range(3)] for i in range(3)]  # rot[i][k] = axes_f[k][i]
    i_c = [
        [sum(rot[i][a] * inertia_f[a][b] * rot[j][b] for a in range(3) for b in range(3)) for j in range(3)]
        for i in range(3)
    ]

    v_c = [speed * math.cos(attack) * math.cos(path), speed * math.sin(attack), speed * math.cos(attack) * math.sin(path)]
    u1 = sub(add(v_c, cross(w_c, r_c)), [0.0, 0.0, 0.0])  # ball at rest
    u1n = dot(u1, n)
    if u1n <= 0.0:
        raise ValueError(f"shot {row['shot_id']}: club does not approach the ball")
    e = cor
    if effect == "cor_speed":
        e = cor - par["k_per_m_s"] * (u1n - COR_SPEED_REFERENCE_M_S)

    def system(tangential_rows):
        # Unknowns: P 0..2, v_b' 3..5, w_b' 6..8, v_c' 9..11, w_c' 12..14.
        a = [[0.0] * 15 for _ in range(15)]
        b = [0.0] * 15
        rcx = cross_matrix(r_c)
        rbx = cross_matrix(r_b)
        for i in range(3):
            # m_c v_c' + P = m_c v_c
            a[i][9 + i] = m_c
            a[i][i] = 1.0
            b[i] = m_c * v_c[i]
            # I_c w_c' + r_c x P = I_c w_c
            for j in range(3):
                a[3 + i][12 + j] = i_c[i][j]
                a[3 + i][j] = rcx[i][j]
            b[3 + i] = dot(i_c[i], w_c)
            # m_b v_b' - P = 0
            a[6 + i][3 + i] = m_b
            a[6 + i][i] = -1.0
            # I_b w_b' - r_b x P = 0
            a[9 + i][6 + i] = i_b
            for j in range(3):
                a[9 + i][j] = -rbx[i][j]

        # u2 = v_c' + w_c' x r_c - v_b' - w_b' x r_b, linear in the unknowns:
        # (w x r) . d = w . (r x d)
        def u2_row(d):
            row = [0.0] * 15
            rcd = cross(r_c, d)
            rbd = cross(r_b, d)
            for j in range(3):
                row[9 + j] = d[j]
                row[12 + j] = rcd[j]
                row[3 + j] = -d[j]
                row[6 + j] = -rbd[j]
            return row

        a[12] = u2_row(n)
        b[12] = -e * u1n
        for k, t in enumerate((ty, tz)):
            a[13 + k], b[13 + k] = tangential_rows(t, u2_row)
        return solve(a, b)

    def no_slip(t, u2_row):
        return u2_row(t), -e_t * dot(u1, t)

    x = system(no_slip)
    p = x[0:3]
    if mu is not None:
        pn = dot(p, n)
        pt = sub(p, scale(pn, n))
        if norm(pt) > mu * pn:
            ut = sub(u1, scale(u1n, n))
            s_hat = scale(1.0 / norm(ut), ut)

            def slip(t, _u2_row):
                row = [0.0] * 15
                for j in range(3):
                    row[j] = t[j] - mu * dot(s_hat, t) * n[j]
                return row, 0.0

            x = system(slip)
    v_b = x[3:6]
    w_b = x[6:9]
    return [
        norm(v_b) / MPH,
        math.degrees(math.atan2(v_b[1], math.hypot(v_b[0], v_b[2]))),
        math.degrees(math.atan2(v_b[2], v_b[0])),
        w_b[2] / RPM,
        -w_b[1] / RPM,
    ]


def read_rows(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def main():
    rows = read_rows(os.path.join(HERE, "deliveries.csv"))
    if len(sys.argv) == 3 and sys.argv[1] == "--check":
        worst = 0.0
        for name, effect, par in CASES:
            ref = read_rows(os.path.join(sys.argv[2], f"{name}.csv"))
            assert len(ref) == len(rows), name
            for row, want in zip(rows, ref):
                assert all(row[c] == want[c] for c in INPUTS), (name, row["shot_id"])
                got = launch(row, effect, par)
                for col, g in zip(OUTPUTS, got):
                    w = float(want[col])
                    worst = max(worst, abs(g - w) / max(abs(w), 1.0))
        print(f"largest difference (relative, or absolute below 1): {worst:.3e}")
        return 0 if worst <= 1e-9 else 1
    if len(sys.argv) != 1:
        print(__doc__, file=sys.stderr)
        return 2
    for name, effect, par in CASES:
        with open(os.path.join(HERE, f"{name}.csv"), "w", newline="") as f:
            w = csv.writer(f, lineterminator="\n")
            w.writerow(INPUTS + OUTPUTS)
            for row in rows:
                w.writerow([row[c] for c in INPUTS] + [repr(v) for v in launch(row, effect, par)])
    return 0


if __name__ == "__main__":
    sys.exit(main())
