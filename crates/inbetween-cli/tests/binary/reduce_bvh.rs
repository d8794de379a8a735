//! The lean BVH path of `reduce` (a BVH file read in pieces, one joint at a time reduced): the
//! same bytes, warnings and `-v` lines as the general path (standard input takes the general
//! path), and the same errors with nothing written.

use super::bvh_stream::{both_of, clip};

#[test]
fn the_lean_path_writes_what_the_general_path_writes() {
    // A Frames count that disagrees with the rows: a parser warning, given once.
    let text = clip(400).replace("Frames: 400", "Frames: 401");
    let tol = ["--tolerance", "0.5", "--translation-tolerance", "0.1"];
    for (extra, name) in [
        (&[][..], "keys.json"),
        (&[], "keys"),
        (&["-v"], "keys.csv"),
        (&["--scheme", "slerp"], "keys.json"),
        (&["--scheme", "hermite", "--method", "optimal"], "keys.json"),
        (&["--method", "optimal", "-v"], "keys.json"),
        (&["--no-velocities", "--scheme", "squad"], "keys.csv"),
        (&["--distance", "20", "--to", "euler:ZYX"], "keys.json"),
        (&["--scheme", "minaccel", "--fps", "60"], "keys.json"),
    ] {
        let args: Vec<&str> = tol.iter().chain(extra).copied().collect();
        let [lean, general] = both_of("reduce", &text, &args, name);
        assert_eq!(lean.0, Some(0), "{args:?}: {}", lean.1);
        assert!(lean.2.as_ref().is_some_and(|o| !o.is_empty()), "{args:?}");
        assert_eq!(lean, general, "{args:?}");
        assert_eq!(lean.1.matches("\"Frames: 401\"").count(), 1, "{}", lean.1);
        if extra.contains(&"-v") {
            assert_eq!(lean.1.matches("inbetween: reduce: track").count(), 3);
        }
    }
}

#[test]
fn errors_are_the_general_paths_and_nothing_is_written() {
    let good = clip(50);
    let tol = ["--tolerance", "0.5", "--translation-tolerance", "0.1"];
    let cases = [
        (good.replace("0.000000 35.000000", "0.000000 nan"), &tol[..]),
        (good.clone(), &tol[..2]),
        (
            good.clone(),
            &["--tolerance", "1e-12", "--translation-tolerance", "0.1"],
        ),
        (good.replace("JOINT Leg", "JOINT"), &tol[..]),
    ];
    for (text, args) in cases {
        for name in ["keys.json", "keys.csv", "keys.npy"] {
            let [lean, general] = both_of("reduce", &text, args, name);
            assert_eq!(lean.0, Some(2), "{args:?} {name}: {}", lean.1);
            assert_eq!(lean.2, None, "nothing written");
            assert_eq!(lean, general, "{args:?} {name}");
        }
    }
}
