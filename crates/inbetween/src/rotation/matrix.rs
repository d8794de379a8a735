//! Rotation matrices: validation and projection onto SO(3).
//!
//! ```text
//! row-major on the wire:  [[m00, m01, m02],      v' = M v  (column vectors)
//!                          [m10, m11, m12],      glam's DMat3 is column-major:
//!                          [m20, m21, m22]]      m{r}{c} = mat.col(c)[r]
//! ```

use crate::error::InputResult;
use crate::error::input_err;
use crate::rotation::magnitude::product_num;
use glam::{DMat3, DQuat, DVec3};

/// Largest accepted Frobenius norm of `RᵀR − I` before projection (docs/spec.md §2).
pub(crate) const ORTHONORMAL_TOL: f64 = 1e-3;

/// Builds the matrix from row-major entries.
pub(crate) fn from_rows(m: [[f64; 3]; 3]) -> DMat3 {
    DMat3::from_cols(
        DVec3::new(m[0][0], m[1][0], m[2][0]),
        DVec3::new(m[0][1], m[1][1], m[2][1]),
        DVec3::new(m[0][2], m[1][2], m[2][2]),
    )
}

/// Row-major entries of a matrix.
pub(crate) fn to_rows(m: &DMat3) -> [[f64; 3]; 3] {
    let t = m.transpose();
    [
        t.x_axis.to_array(),
        t.y_axis.to_array(),
        t.z_axis.to_array(),
    ]
}

/// Validates a (row-major) matrix and returns the rotation nearest to it, as a quaternion with
/// `w ≥ 0`. Errors: det < 0 (a reflection), `‖RᵀR − I‖_F > 1e-3` (not a rotation).
///
/// The projection is the orthogonal polar factor `U Vᵀ` of the SVD, computed by Newton's
/// iteration `R ← (R + R⁻ᵀ)/2`, which converges quadratically from a nearly orthonormal start.
///
/// A matrix with entries beyond 1e100 or all below 1e-100 is checked as `s·N` (`s` its largest
/// entry), so its determinant and `‖RᵀR − I‖` are computed without overflow and reported with
/// their digits even beyond f64's range (`1e200·I` has `‖RᵀR − I‖ = 1.732e400`).
pub(crate) fn to_quat(rows: [[f64; 3]; 3]) -> InputResult<DQuat> {
    let flat = [
        rows[0][0], rows[0][1], rows[0][2], rows[1][0], rows[1][1], rows[1][2], rows[2][0],
        rows[2][1], rows[2][2],
    ];
    // M = s·N; s = 1 for ordinary entries.
    let (s, n) = crate::rotation::magnitude::split(flat);
    let m = from_rows([[n[0], n[1], n[2]], [n[3], n[4], n[5]], [n[6], n[7], n[8]]]);
    let det = m.determinant();
    if det < 0.0 {
        return Err(input_err!(
            "expected a rotation matrix, found a reflection (determinant {})",
            product_num(&[det, s, s, s], None)
        ));
    }
    // ‖MᵀM − I‖ = s²·‖NᵀN − I/s²‖ (s ≥ 1); tiny entries (s < 1) cannot overflow as they are.
    let err = if s >= 1.0 {
        [deviation(&m, (s * s).recip()), s, s]
    } else {
        [orthonormality_error(&from_rows(rows)), 1.0, 1.0]
    };
    let value = err[0] * err[1] * err[2];
    if value.is_nan() || value > ORTHONORMAL_TOL {
        return Err(input_err!(
            "expected an orthonormal rotation matrix (‖RᵀR − I‖ ≤ 1e-3), found ‖RᵀR − I‖ = {}",
            product_num(&err, Some(3))
        ));
    }
    let r = project(from_rows(rows));
    Ok(crate::rotation::quat::canonical(
        DQuat::from_mat3(&r).normalize(),
    ))
}

/// Frobenius norm of `NᵀN − c·I`.
fn deviation(n: &DMat3, c: f64) -> f64 {
    let e = n.transpose() * *n - DMat3::IDENTITY * c;
    (e.x_axis.length_squared() + e.y_axis.length_squared() + e.z_axis.length_squared()).sqrt()
}

/// Frobenius norm of `RᵀR − I`.
pub(crate) fn orthonormality_error(m: &DMat3) -> f64 {
    deviation(m, 1.0)
}

/// Nearest rotation (polar factor) of a nearly orthonormal matrix with positive determinant.
fn project(mut r: DMat3) -> DMat3 {
    for _ in 0..8 {
        let next = (r + r.inverse().transpose()) * 0.5;
        let step = next - r;
        r = next;
        let d = step.x_axis.length_squared()
            + step.y_axis.length_squared()
            + step.z_axis.length_squared();
        if d < 1e-32 {
            break;
        }
    }
    r
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn exact_rotation_is_kept() {
        let q = DQuat::from_euler(glam::EulerRot::ZYX, 0.4, -0.3, 2.0);
        let rows = to_rows(&DMat3::from_quat(q));
        let back = to_quat(rows).unwrap();
        assert!((back - q).length() < 1e-15 || (back + q).length() < 1e-15);
    }

    #[test]
    fn slightly_scaled_matrix_is_projected() {
        let q = DQuat::from_rotation_y(0.9);
        let rows = to_rows(&(DMat3::from_quat(q) * 1.0002));
        let back = to_quat(rows).unwrap();
        assert!((back - q).length() < 1e-14);
    }

    #[test]
    fn reflection_and_shear_rejected() {
        let refl = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, -1.0]];
        assert!(to_quat(refl).unwrap_err().message().contains("reflection"));
        let shear = [[1.0, 0.1, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
        assert!(
            to_quat(shear)
                .unwrap_err()
                .message()
                .contains("orthonormal")
        );
    }
}
