//! The mappings of docs/conventions.md: each package's own formula, built here independently,
//! against what `inbetween convert --from euler:SEQ --to quat` makes of the same numbers.

use crate::support::{bin, rot_angle, stdout_of};
use glam::{DQuat, DVec3};

/// Angles (degrees) sampled away from gimbal lock, one triple per row.
const TRIPLES: [[f64; 3]; 4] = [
    [30.0, -20.0, 75.0],
    [-120.0, 40.0, 10.0],
    [170.0, -65.0, -100.0],
    [5.0, 80.0, 200.0],
];

/// `inbetween convert` of the rows `e1,e2,e3` (degrees) under `--from euler:SEQ`: quaternions.
fn convert(seq: &str, rows: &[[f64; 3]]) -> Vec<DQuat> {
    let mut csv = String::from("time,e1,e2,e3\n");
    for (i, r) in rows.iter().enumerate() {
        csv += &format!("{i},{:?},{:?},{:?}\n", r[0], r[1], r[2]);
    }
    stdout_of(
        bin()
            .args([
                "convert",
                "-",
                "--from",
                &format!("euler:{seq}"),
                "--to",
                "quat",
            ])
            .write_stdin(csv),
    )
    .lines()
    .skip(1)
    .map(|l| {
        let v: Vec<f64> = l.split(',').map(|x| x.parse().unwrap()).collect();
        DQuat::from_xyzw(v[2], v[3], v[4], v[1])
    })
    .collect()
}

fn rx(deg: f64) -> DQuat {
    DQuat::from_axis_angle(DVec3::X, deg.to_radians())
}
fn ry(deg: f64) -> DQuat {
    DQuat::from_axis_angle(DVec3::Y, deg.to_radians())
}
fn rz(deg: f64) -> DQuat {
    DQuat::from_axis_angle(DVec3::Z, deg.to_radians())
}

/// Same rotation (q and −q alike) within 1e-12 rad.
fn same(a: DQuat, b: DQuat, what: &str) {
    assert!(rot_angle(a, b) < 1e-12, "{what}: {a} vs {b}");
}

#[test]
fn maya_and_blender_rotate_order_xyz_is_extrinsic_xyz() {
    // Rotate order xyz (Maya) / XYZ Euler (Blender): X first, about fixed axes: R = Rz·Ry·Rx.
    let got = convert("xyz", &TRIPLES);
    for (t, q) in TRIPLES.iter().zip(got) {
        same(q, rz(t[2]) * ry(t[1]) * rx(t[0]), "maya xyz");
    }
    // Every other rotate order: the same letters, lower case; zxy is R = Ry·Rx·Rz.
    let rows: Vec<[f64; 3]> = TRIPLES.iter().map(|t| [t[2], t[0], t[1]]).collect();
    let got = convert("zxy", &rows);
    for (t, q) in TRIPLES.iter().zip(got) {
        same(q, ry(t[1]) * rx(t[0]) * rz(t[2]), "maya zxy");
    }
}

#[test]
fn unity_euler_angles_are_intrinsic_yxz_with_y_x_z() {
    // Quaternion.Euler(x, y, z): z, then x, then y about the fixed axes = Ry·Rx·Rz.
    let rows: Vec<[f64; 3]> = TRIPLES.iter().map(|t| [t[1], t[0], t[2]]).collect();
    let got = convert("YXZ", &rows);
    for (t, q) in TRIPLES.iter().zip(got) {
        let (x, y, z) = (t[0], t[1], t[2]);
        same(q, ry(y) * rx(x) * rz(z), "unity");
    }
}

#[test]
fn unreal_rotator_is_intrinsic_zyx_with_yaw_minus_pitch_minus_roll() {
    // Unreal's FRotator::Quaternion(), component by component (half angles, degrees).
    let unreal = |pitch: f64, yaw: f64, roll: f64| {
        let h = |d: f64| (d.to_radians() / 2.0).sin_cos();
        let ((sp, cp), (sy, cy), (sr, cr)) = (h(pitch), h(yaw), h(roll));
        DQuat::from_xyzw(
            cr * sp * sy - sr * cp * cy,
            -cr * sp * cy - sr * cp * sy,
            cr * cp * sy - sr * sp * cy,
            cr * cp * cy + sr * sp * sy,
        )
    };
    let rows: Vec<[f64; 3]> = TRIPLES.iter().map(|t| [t[1], -t[0], -t[2]]).collect();
    let got = convert("ZYX", &rows);
    for (t, q) in TRIPLES.iter().zip(got) {
        // FRotator(Pitch, Yaw, Roll) = (t[0], t[1], t[2]); the components agree exactly.
        let u = unreal(t[0], t[1], t[2]);
        let u = if u.dot(q) < 0.0 { -u } else { u };
        assert!((q - u).length() < 1e-15, "unreal: {q} vs {u}");
    }
}

#[test]
fn bvh_channels_zxy_are_intrinsic_zxy_as_listed() {
    // CHANNELS 3 Zrotation Xrotation Yrotation: R = Rz·Rx·Ry, angles in channel order.
    let got = convert("ZXY", &TRIPLES);
    for (t, q) in TRIPLES.iter().zip(got) {
        same(q, rz(t[0]) * rx(t[1]) * ry(t[2]), "bvh");
    }
}

#[test]
fn intrinsic_zyx_is_extrinsic_xyz_reversed() {
    let rev: Vec<[f64; 3]> = TRIPLES.iter().map(|t| [t[2], t[1], t[0]]).collect();
    for (a, b) in convert("ZYX", &TRIPLES)
        .into_iter()
        .zip(convert("xyz", &rev))
    {
        same(a, b, "ZYX vs xyz reversed");
    }
}

#[test]
fn gltf_quaternions_are_xyzw_in_json() {
    let out = bin()
        .args([
            "convert",
            "-",
            "--quat-order",
            "xyzw",
            "--output-format",
            "csv",
        ])
        .write_stdin(r#"{"keys": [{"time": 0, "quat": [0.6, 0, 0, 0.8]}]}"#)
        .output()
        .unwrap();
    assert!(out.status.success());
    // 0.8 is the scalar: w = 0.8, x = 0.6 (a turn of 2·atan2(0.6, 0.8) ≈ 73.7° about x).
    assert_eq!(
        String::from_utf8(out.stdout).unwrap(),
        "time,w,x,y,z\n0.0,0.8,0.6,0.0,0.0\n"
    );
}
