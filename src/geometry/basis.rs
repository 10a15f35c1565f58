//! An orthonormal basis about a unit vector: the in-plane axes that faces, lids, views and
//! earthshine's beams are laid out in; and the angle between two unit vectors. It lives with the geometry, which needs it most,
//! so that the geometry imports nothing from the radiometry.

use glam::DVec3;

/// Two unit vectors completing `n` to a right-handed orthonormal basis.
pub fn orthonormal_basis(n: DVec3) -> (DVec3, DVec3) {
    // Duff et al. 2017, branchless ONB
    let sign = 1.0_f64.copysign(n.z);
    let a = -1.0 / (sign + n.z);
    let b = n.x * n.y * a;
    (
        DVec3::new(1.0 + sign * n.x * n.x * a, sign * b, -sign * n.x),
        DVec3::new(b, sign + n.y * n.y * a, -n.y),
    )
}

/// Angle between unit vectors, rad; atan2 keeps it accurate near 0 and π.
#[inline]
pub fn angle_between(a: DVec3, b: DVec3) -> f64 {
    a.cross(b).length().atan2(a.dot(b))
}
