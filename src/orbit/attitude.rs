//! Attitude laws: the body → TEME rotation at each instant.
//!
//! Every law gives a unit quaternion q with v_TEME = q·v_body·q* — the same meaning as
//! an explicit epoch's `attitude` — so the engine sees the Sun, observer and Earth
//! vectors rotated into the body frame as it does for explicit epochs.

use glam::{DMat3, DQuat, DVec3};

/// What a law may need at one instant: the object's TEME position (m) and velocity
/// (m/s), the unit direction from the object to the Sun (TEME), and the seconds since
/// the window's start.
#[derive(Debug, Clone, Copy)]
pub struct State {
    pub r: DVec3,
    pub v: DVec3,
    pub sun: DVec3,
    pub t: f64,
}

/// An attitude law (all angles radians, rates rad/s, vectors TEME unless said).
#[derive(Debug, Clone)]
pub enum Law {
    /// Local vertical, local horizontal: body +z at the geocentre (nadir), +y along
    /// the negative orbit normal −(r×v), +x completing the right-handed set (along the
    /// velocity for a circular orbit); then turned by `yaw` about +z.
    Nadir { yaw: f64 },
    /// The unit body `axis` at the Sun, the body `secondary` (unit, perpendicular to
    /// `axis`) towards the TEME pole (z axis) projected across the Sun's direction (the
    /// TEME x axis if the Sun were at the pole). Default +z and +x.
    SunPointing { axis: DVec3, secondary: DVec3 },
    /// A fixed body → TEME quaternion.
    Inertial { q: DQuat },
    /// Rotation about the fixed TEME unit `axis` at `rate`, `phase` at the window's
    /// start, after the body → TEME quaternion `q0`: q(t) = R(axis, phase + rate·t)·q0.
    Spin {
        axis: DVec3,
        rate: f64,
        phase: f64,
        q0: DQuat,
    },
    /// Body → TEME quaternions at increasing times (s since the start), interpolated by
    /// SLERP along the shorter arc; requested times must lie within the series.
    Quaternions { series: Vec<(f64, DQuat)> },
    /// A torque-free rigid body.
    Tumble(Tumble),
}

impl Law {
    /// The body → TEME quaternions at the states (given in increasing time).
    pub fn quaternions(&self, states: &[State]) -> Vec<DQuat> {
        match self {
            Law::Tumble(t) => {
                let times: Vec<f64> = states.iter().map(|s| s.t).collect();
                t.at_times(&times)
            }
            _ => states.iter().map(|s| self.at(s)).collect(),
        }
    }

    fn at(&self, s: &State) -> DQuat {
        match self {
            Law::Nadir { yaw } => nadir(s.r, s.v, *yaw),
            Law::SunPointing { axis, secondary } => sun_pointing_axes(s.sun, *axis, *secondary),
            Law::Inertial { q } => *q,
            Law::Spin {
                axis,
                rate,
                phase,
                q0,
            } => (DQuat::from_axis_angle(*axis, phase + rate * s.t) * *q0).normalize(),
            Law::Quaternions { series } => slerp_series(series, s.t),
            Law::Tumble(t) => t.at_times(&[s.t])[0],
        }
    }
}

/// A unit vector perpendicular to unit `z`, as close as possible to `hint` (any other
/// perpendicular when `hint` is along `z`).
fn perpendicular(z: DVec3, hint: DVec3) -> DVec3 {
    let p = hint - z * hint.dot(z);
    if p.length_squared() > 1e-18 {
        return p.normalize();
    }
    z.any_orthonormal_vector()
}

/// The nadir (LVLH) attitude with `yaw` about +z.
pub fn nadir(r: DVec3, v: DVec3, yaw: f64) -> DQuat {
    let z = -r.normalize();
    let h = r.cross(v);
    // -(r×v) for an orbit; a purely radial state has no plane: any perpendicular
    let y = if h.length_squared() > 0.0 {
        perpendicular(z, -h.normalize())
    } else {
        z.any_orthonormal_vector()
    };
    let x = y.cross(z);
    let m = DMat3::from_cols(x, y, z) * DMat3::from_rotation_z(yaw);
    DQuat::from_mat3(&m).normalize()
}

/// Body +z at the Sun, +x towards the TEME pole.
pub fn sun_pointing(sun: DVec3) -> DQuat {
    let z = sun.normalize();
    let x = perpendicular(z, DVec3::Z);
    let y = z.cross(x);
    DQuat::from_mat3(&DMat3::from_cols(x, y, z)).normalize()
}

/// Unit body `axis` at the Sun, unit body `secondary` (perpendicular to it) towards the
/// TEME pole: the rotation taking (axis, secondary, axis × secondary) onto (Sun, pole
/// across it, their cross product).
pub fn sun_pointing_axes(sun: DVec3, axis: DVec3, secondary: DVec3) -> DQuat {
    let p = sun.normalize();
    let s = perpendicular(p, DVec3::Z);
    let target = DMat3::from_cols(p, s, p.cross(s));
    let body = DMat3::from_cols(axis, secondary, axis.cross(secondary));
    DQuat::from_mat3(&(target * body.transpose())).normalize()
}

/// SLERP in a series of (time, quaternion), times increasing; clamped at the ends.
pub fn slerp_series(series: &[(f64, DQuat)], t: f64) -> DQuat {
    let Some(first) = series.first() else {
        return DQuat::IDENTITY;
    };
    if t <= first.0 || series.len() == 1 {
        return first.1;
    }
    let k = series.partition_point(|(ti, _)| *ti <= t);
    if k >= series.len() {
        return series[series.len() - 1].1;
    }
    let (t0, q0) = series[k - 1];
    let (t1, mut q1) = series[k];
    // times strictly increase (validated), so t1 − t0 > 0
    let s = ((t - t0) / (t1 - t0)).clamp(0.0, 1.0);
    if q0.dot(q1) < 0.0 {
        q1 = -q1;
    }
    q0.slerp(q1, s).normalize()
}

/// A torque-free rigid body: principal moments, the principal axes in the body frame,
/// the initial body → TEME attitude and the initial body-frame angular velocity.
#[derive(Debug, Clone)]
pub struct Tumble {
    /// Principal moments of inertia, kg·m² (all positive).
    pub moments: DVec3,
    /// Columns: the principal axes in body coordinates (a proper rotation).
    pub axes: DMat3,
    /// Body → TEME at the start.
    pub q0: DQuat,
    /// Angular velocity at the start, body frame, rad/s.
    pub omega0: DVec3,
}

/// Largest rotation angle |ω|·h of one integration step, rad: the 6th-order splitting's
/// energy error per step is ~(|ω|h)⁷, so 0.05 rad keeps it near 1e-12 over 10⁴ periods.
pub const MAX_STEP_ANGLE: f64 = 0.05;

impl Tumble {
    /// From a symmetric inertia tensor (body frame, kg·m²): its principal moments and
    /// axes by Jacobi's method.
    pub fn new(inertia: DMat3, q0: DQuat, omega0: DVec3) -> Tumble {
        let (moments, axes) = symmetric_eigen(inertia);
        Tumble {
            moments,
            axes,
            q0,
            omega0,
        }
    }

    /// Integration steps a window of `span_s` seconds takes (0 in closed form).
    pub fn steps_for(&self, span_s: f64) -> f64 {
        if self.symmetry_axis().is_some() {
            return 0.0;
        }
        let (l, _) = self.initial();
        // moments validated positive
        l.length() / self.moments.min_element() * span_s.abs() / MAX_STEP_ANGLE
    }

    /// Principal-frame angular momentum and the principal → TEME attitude at the start.
    fn initial(&self) -> (DVec3, DQuat) {
        let w = self.axes.transpose() * self.omega0;
        let qp = (self.q0 * DQuat::from_mat3(&self.axes)).normalize();
        (self.moments * w, qp)
    }

    /// The axis of symmetry (index) when two principal moments are equal (to 1e-12
    /// relative), for the closed form.
    fn symmetry_axis(&self) -> Option<usize> {
        let m = self.moments;
        let eq = |a: f64, b: f64| (a - b).abs() <= 1e-12 * a.max(b);
        if eq(m.x, m.y) {
            Some(2)
        } else if eq(m.y, m.z) {
            Some(0)
        } else if eq(m.x, m.z) {
            Some(1)
        } else {
            None
        }
    }

    /// Body → TEME quaternions at `times` (s since the start, increasing, ≥ 0): in
    /// closed form for an axisymmetric body, else by the splitting integrator.
    pub fn at_times(&self, times: &[f64]) -> Vec<DQuat> {
        let to_body = DQuat::from_mat3(&self.axes).inverse();
        let principal: Vec<DQuat> = match self.symmetry_axis() {
            Some(k) => times.iter().map(|&t| self.closed_form(k, t).1).collect(),
            None => self.integrate(times).into_iter().map(|(_, q)| q).collect(),
        };
        principal
            .into_iter()
            .map(|q: DQuat| (q * to_body).normalize())
            .collect()
    }

    /// The axisymmetric solution about principal axis `k`: (principal-frame L,
    /// principal → TEME) at `t`. The body turns about the fixed inertial L at |L|/I_t
    /// while turning about its own axis at λ = L_k (1/I_k − 1/I_t):
    /// q(t) = R(L̂, |L| t / I_t) · q(0) · R(e_k, λ t).
    pub fn closed_form(&self, k: usize, t: f64) -> (DVec3, DQuat) {
        let (l, q) = self.initial();
        let it = self.moments[(k + 1) % 3];
        let ia = self.moments[k];
        let e = DVec3::AXES[k];
        let lambda = l[k] * (1.0 / ia - 1.0 / it);
        let spin = DQuat::from_axis_angle(e, lambda * t);
        let l_inertial = q * l;
        let norm = l_inertial.length();
        let precession = if norm > 0.0 {
            DQuat::from_axis_angle(l_inertial / norm, norm * t / it)
        } else {
            DQuat::IDENTITY
        };
        ((spin.inverse() * l), (precession * q * spin).normalize())
    }

    /// Integrates Euler's equations and the attitude by the free rigid body's exact
    /// splitting into rotations about the principal axes (McLachlan 1993; Dullweber,
    /// Leimkuhler & McLachlan 1997), composed to 6th order by Yoshida's triple jump:
    /// |L| and the inertial L are conserved to rounding, the energy to O((|ω|h)⁶) with
    /// no drift. Returns (principal-frame L, principal → TEME) at each time.
    pub fn integrate(&self, times: &[f64]) -> Vec<(DVec3, DQuat)> {
        let (mut l, mut q) = self.initial();
        // |ω| ≤ |L| / I_min bounds every sub-rotation's rate
        let i_min = self.moments.min_element();
        let w_max = l.length() / i_min;
        let h_max = if w_max > 0.0 {
            MAX_STEP_ANGLE / w_max
        } else {
            f64::INFINITY
        };
        let mut now = 0.0;
        let mut out = Vec::with_capacity(times.len());
        for &t in times {
            while now < t {
                let h = (t - now).min(h_max);
                step6(&self.moments, &mut l, &mut q, h);
                q = q.normalize();
                now = if h == t - now { t } else { now + h };
            }
            out.push((l, q));
        }
        out
    }

    /// Rotational kinetic energy (J) and the inertial angular momentum (TEME, N·m·s)
    /// of a principal-frame state.
    pub fn invariants(&self, l: DVec3, q: DQuat) -> (f64, DVec3) {
        let e = 0.5 * (l * l / self.moments).element_sum();
        (e, q * l)
    }

    /// The initial energy and inertial angular momentum.
    pub fn initial_invariants(&self) -> (f64, DVec3) {
        let (l, q) = self.initial();
        self.invariants(l, q)
    }
}

/// The exact flow of the part L_i²/(2 I_i) of the energy for time `tau`: the body turns
/// by φ = L_i τ / I_i about principal axis i, so L's body components turn by −φ.
fn rotate_about(i: usize, moments: &DVec3, l: &mut DVec3, q: &mut DQuat, tau: f64) {
    let phi = l[i] * tau / moments[i];
    let (s, c) = phi.sin_cos();
    let (a, b) = ((i + 1) % 3, (i + 2) % 3);
    let (la, lb) = (l[a], l[b]);
    l[a] = c * la + s * lb;
    l[b] = -s * la + c * lb;
    let (sh, ch) = (0.5 * phi).sin_cos();
    let mut v = DVec3::ZERO;
    v[i] = sh;
    *q *= DQuat::from_xyzw(v.x, v.y, v.z, ch);
}

/// Strang's symmetric 2nd-order step: x(h/2) y(h/2) z(h) y(h/2) x(h/2).
fn step2(m: &DVec3, l: &mut DVec3, q: &mut DQuat, h: f64) {
    rotate_about(0, m, l, q, 0.5 * h);
    rotate_about(1, m, l, q, 0.5 * h);
    rotate_about(2, m, l, q, h);
    rotate_about(1, m, l, q, 0.5 * h);
    rotate_about(0, m, l, q, 0.5 * h);
}

fn triple_jump(order: u32) -> (f64, f64) {
    let r = 2f64.powf(1.0 / (order as f64 + 1.0));
    let w1 = 1.0 / (2.0 - r);
    (w1, -r * w1)
}

fn step4(m: &DVec3, l: &mut DVec3, q: &mut DQuat, h: f64) {
    let (w1, w0) = triple_jump(2);
    step2(m, l, q, w1 * h);
    step2(m, l, q, w0 * h);
    step2(m, l, q, w1 * h);
}

fn step6(m: &DVec3, l: &mut DVec3, q: &mut DQuat, h: f64) {
    let (w1, w0) = triple_jump(4);
    step4(m, l, q, w1 * h);
    step4(m, l, q, w0 * h);
    step4(m, l, q, w1 * h);
}

/// Eigenvalues and eigenvectors (columns, a proper rotation) of a symmetric 3×3
/// matrix by cyclic Jacobi rotations.
pub fn symmetric_eigen(a: DMat3) -> (DVec3, DMat3) {
    let mut m = [
        [a.x_axis.x, a.y_axis.x, a.z_axis.x],
        [a.x_axis.y, a.y_axis.y, a.z_axis.y],
        [a.x_axis.z, a.y_axis.z, a.z_axis.z],
    ];
    let mut v = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
    for _sweep in 0..50 {
        let off = m[0][1].abs() + m[0][2].abs() + m[1][2].abs();
        let scale = m[0][0].abs() + m[1][1].abs() + m[2][2].abs();
        if off <= 1e-17 * scale || off == 0.0 {
            break;
        }
        for (p, r) in [(0, 1), (0, 2), (1, 2)] {
            if m[p][r] == 0.0 {
                continue;
            }
            // the angle that zeroes m[p][r]: tan 2θ = 2 m_pr / (m_rr − m_pp)
            let theta = 0.5 * (2.0 * m[p][r]).atan2(m[r][r] - m[p][p]);
            let (s, c) = theta.sin_cos();
            for row in m.iter_mut() {
                let (x, y) = (row[p], row[r]);
                row[p] = c * x - s * y;
                row[r] = s * x + c * y;
            }
            let (mp, mr) = (m[p], m[r]);
            m[p] = std::array::from_fn(|k| c * mp[k] - s * mr[k]);
            m[r] = std::array::from_fn(|k| s * mp[k] + c * mr[k]);
            for row in v.iter_mut() {
                let (x, y) = (row[p], row[r]);
                row[p] = c * x - s * y;
                row[r] = s * x + c * y;
            }
        }
    }
    let col = |k: usize| DVec3::new(v[0][k], v[1][k], v[2][k]);
    let mut axes = DMat3::from_cols(col(0), col(1), col(2));
    if axes.determinant() < 0.0 {
        axes.z_axis = -axes.z_axis;
    }
    (DVec3::new(m[0][0], m[1][1], m[2][2]), axes)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Jacobi recovers a rotated diagonal tensor: A·v = λ·v to 1e-12 relative (a few
    /// ulps of the tensor's scale after ~10 rotations).
    #[test]
    fn eigen_of_a_rotated_tensor() {
        let r = DMat3::from_quat(DQuat::from_euler(glam::EulerRot::ZYX, 0.3, -0.7, 1.1));
        let a = r * DMat3::from_diagonal(DVec3::new(1.0, 2.5, 4.0)) * r.transpose();
        let (l, v) = symmetric_eigen(a);
        for k in 0..3 {
            let x = v.col(k);
            assert!((a * x - l[k] * x).length() < 1e-12 * 4.0, "{k}");
        }
        assert!((v.determinant() - 1.0).abs() < 1e-12);
    }
}
