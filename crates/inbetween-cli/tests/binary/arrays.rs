//! `interp`'s NumPy output: `.npy` rows with translations and velocities (the CSV's numeric
//! columns), and the `.npz` archive of named arrays, read here by a small reader of our own and
//! by numpy (`fixtures/npz/check.py`) against the JSON output of the same command.

use crate::support::{bin, checker_python, python_json, stdout_of};
use std::collections::HashMap;
use std::path::Path;

/// One `.npy` array: dtype, shape, data bytes.
struct Array {
    descr: String,
    shape: Vec<u64>,
    data: Vec<u8>,
}

impl Array {
    fn f64s(&self) -> Vec<f64> {
        assert_eq!(self.descr, "<f8");
        self.data
            .chunks_exact(8)
            .map(|c| f64::from_le_bytes(c.try_into().unwrap()))
            .collect()
    }

    /// A `<U{n}` array's strings (UCS4 little-endian, NUL-padded).
    fn strings(&self) -> Vec<String> {
        let n: usize = self.descr.strip_prefix("<U").unwrap().parse().unwrap();
        self.data
            .chunks_exact(4 * n)
            .map(|s| {
                s.chunks_exact(4)
                    .map(|c| u32::from_le_bytes(c.try_into().unwrap()))
                    .take_while(|&c| c != 0)
                    .map(|c| char::from_u32(c).unwrap())
                    .collect()
            })
            .collect()
    }
}

/// Parses a `.npy` v1.0 file: its header dict's `descr` and `shape`, C order, 64-byte aligned.
fn npy(bytes: &[u8]) -> Array {
    assert_eq!(&bytes[..8], b"\x93NUMPY\x01\x00");
    let len = u16::from_le_bytes([bytes[8], bytes[9]]) as usize;
    assert_eq!((10 + len) % 64, 0);
    let dict = std::str::from_utf8(&bytes[10..10 + len]).unwrap();
    assert!(dict.ends_with('\n') && dict.contains("'fortran_order': False"));
    let descr = dict.split("'descr': '").nth(1).unwrap();
    let descr = descr[..descr.find('\'').unwrap()].to_string();
    let shape = dict.split("'shape': (").nth(1).unwrap();
    let shape: Vec<u64> = shape[..shape.find(')').unwrap()]
        .split(',')
        .map(str::trim)
        .filter(|s| !s.is_empty())
        .map(|s| s.parse().unwrap())
        .collect();
    let data = bytes[10 + len..].to_vec();
    let item: usize = match descr.as_str() {
        "|b1" => 1,
        d if d.starts_with("<U") => 4 * d[2..].parse::<usize>().unwrap(),
        _ => 8,
    };
    assert_eq!(
        data.len(),
        item * shape.iter().product::<u64>() as usize,
        "{descr} {shape:?}"
    );
    Array { descr, shape, data }
}

/// The entries of a zip of stored entries, in order, walked by their local headers, the
/// central directory checked to list the same.
fn npz(bytes: &[u8]) -> Vec<(String, Array)> {
    let u16_at = |i: usize| u16::from_le_bytes([bytes[i], bytes[i + 1]]) as usize;
    let u32_at = |i: usize| u32::from_le_bytes(bytes[i..i + 4].try_into().unwrap()) as usize;
    let (mut at, mut out, mut offsets) = (0, Vec::new(), Vec::new());
    while u32_at(at) == 0x0403_4b50 {
        assert_eq!(u16_at(at + 8), 0, "stored");
        let (size, name_len, extra) = (u32_at(at + 18), u16_at(at + 26), u16_at(at + 28));
        assert_eq!(u32_at(at + 22), size);
        let name = std::str::from_utf8(&bytes[at + 30..at + 30 + name_len]).unwrap();
        let start = at + 30 + name_len + extra;
        let array = npy(&bytes[start..start + size]);
        offsets.push(at);
        out.push((name.strip_suffix(".npy").unwrap().to_string(), array));
        at = start + size;
    }
    let end = bytes.len() - 22;
    assert_eq!(u32_at(end), 0x0605_4b50);
    assert_eq!(u16_at(end + 10), out.len());
    assert_eq!(u32_at(end + 16), at);
    let mut cd = at;
    for &offset in &offsets {
        assert_eq!(u32_at(cd), 0x0201_4b50);
        assert_eq!(u32_at(cd + 42), offset);
        cd += 46 + u16_at(cd + 28) + u16_at(cd + 30) + u16_at(cd + 32);
    }
    assert_eq!(cd, end);
    out
}

/// A BVH hierarchy's joints (ROOT and JOINT, in file order): each one's parent index (−1 for a
/// root) and its OFFSET numbers, from the text alone.
fn bvh_tree(text: &str) -> (Vec<i64>, Vec<f64>) {
    let (mut parents, mut offsets) = (Vec::new(), Vec::new());
    // The enclosing blocks: Some(joint index) for a joint's, None for an End Site's.
    let (mut stack, mut pending): (Vec<Option<i64>>, Option<Option<i64>>) = (Vec::new(), None);
    for line in text.lines().map(str::trim) {
        let word = line.split_whitespace().next().unwrap_or("");
        match word {
            "ROOT" | "JOINT" => {
                let parent = stack.iter().rev().flatten().next().copied().unwrap_or(-1);
                parents.push(parent);
                pending = Some(Some(parents.len() as i64 - 1));
            }
            "End" => pending = Some(None),
            "{" => stack.push(pending.take().expect("a block opens after its name")),
            "}" => {
                stack.pop();
            }
            "OFFSET" if matches!(stack.last(), Some(Some(_))) => offsets.extend(
                line.split_whitespace()
                    .skip(1)
                    .map(|x| x.parse::<f64>().unwrap()),
            ),
            "MOTION" => break,
            _ => {}
        }
    }
    (parents, offsets)
}

fn interp_to(args: &[&str], out: &Path) {
    stdout_of(bin().arg("interp").args(args).arg("-o").arg(out));
}

fn csv_rows(text: &str) -> Vec<Vec<String>> {
    let mut rdr = csv::Reader::from_reader(text.as_bytes());
    let mut rows = vec![rdr.headers().unwrap().iter().map(String::from).collect()];
    rows.extend(
        rdr.records()
            .map(|r| r.unwrap().iter().map(String::from).collect()),
    );
    rows
}

/// The npy of a BVH clip whose root alone has positions, with velocities: exactly the CSV's
/// numeric columns — track index, frame, time, w x y z, wx wy wz, tx ty tz — with zeros where
/// the CSV's translation cells are empty. It was refused ("npy output does not carry them").
#[test]
fn npy_with_translations_and_velocities_is_the_csv_as_numbers() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("f.npy");
    let clip = "fixtures/bvh/cmu_01_01.bvh";
    interp_to(&[clip, "--velocity"], &path);
    let csv = stdout_of(bin().args(["interp", clip, "--velocity", "--output-format", "csv"]));
    let rows = csv_rows(&csv);
    assert_eq!(
        rows[0][rows[0].len() - 6..],
        ["wx", "wy", "wz", "tx", "ty", "tz"]
    );
    let a = npy(&std::fs::read(&path).unwrap());
    let cols = rows[0].len();
    assert_eq!(a.shape, [rows.len() as u64 - 1, cols as u64]);
    let values = a.f64s();
    let mut names: Vec<&str> = Vec::new();
    let (mut empty, mut filled) = (0, 0);
    for (i, row) in rows[1..].iter().enumerate() {
        if names.last() != Some(&row[0].as_str()) {
            names.push(&row[0]);
        }
        let mut want = vec![(names.len() - 1) as f64];
        for cell in &row[1..] {
            want.push(if cell.is_empty() {
                0.0
            } else {
                cell.parse().unwrap()
            });
        }
        if row[cols - 1].is_empty() {
            empty += 1;
        } else {
            filled += 1;
        }
        assert_eq!(
            &values[i * cols..(i + 1) * cols],
            want.as_slice(),
            "row {i}"
        );
    }
    // Both kinds of track are there: the root with positions, the joints without.
    assert!(empty > 0 && filled > 0, "{empty} {filled}");
}

/// The npz of the same clip: every array named and shaped as documented, in order, and equal to
/// the npy's columns (track-major there, frame-major here).
#[test]
fn npz_holds_the_documented_arrays() {
    let dir = tempfile::tempdir().unwrap();
    let (z, y) = (dir.path().join("f.npz"), dir.path().join("f.npy"));
    let clip = "fixtures/bvh/cmu_01_01.bvh";
    interp_to(&[clip, "--velocity"], &z);
    interp_to(&[clip, "--velocity"], &y);
    let rows = npy(&std::fs::read(&y).unwrap());
    let (n, cols) = (rows.shape[0] as usize, rows.shape[1] as usize);
    let rows = rows.f64s();
    let arrays = npz(&std::fs::read(&z).unwrap());
    let names: Vec<&str> = arrays.iter().map(|(n, _)| n.as_str()).collect();
    assert_eq!(
        names,
        [
            "times",
            "frames",
            "names",
            "rotations",
            "velocities",
            "translations",
            "has_translation",
            "parents",
            "offsets",
            "fps",
            "rotation",
            "angles"
        ]
    );
    let get: HashMap<&str, &Array> = arrays.iter().map(|(n, a)| (n.as_str(), a)).collect();
    let tracks = get["names"].strings();
    let (j, t) = (tracks.len(), n / tracks.len());
    assert_eq!(
        (tracks[0].as_str(), tracks[1].as_str()),
        ("Hips", "LHipJoint")
    );
    assert_eq!(get["names"].shape, [j as u64]);
    assert_eq!(get["times"].shape, [t as u64]);
    assert_eq!(get["frames"].descr, "<i8");
    for (name, width) in [("rotations", 4), ("velocities", 3), ("translations", 3)] {
        assert_eq!(get[name].shape, [t as u64, j as u64, width], "{name}");
    }
    // The tree, against the file's text read here: every ROOT/JOINT in order, its parent the
    // joint whose block encloses it, its OFFSET (End Sites are no tracks).
    let (parents, offsets) = bvh_tree(
        &std::fs::read_to_string(crate::support::fixtures().join("bvh/cmu_01_01.bvh")).unwrap(),
    );
    assert_eq!(
        (get["parents"].descr.as_str(), get["parents"].shape.clone()),
        ("<i8", vec![j as u64])
    );
    let got_parents: Vec<i64> = get["parents"]
        .data
        .chunks_exact(8)
        .map(|c| i64::from_le_bytes(c.try_into().unwrap()))
        .collect();
    assert_eq!(got_parents, parents);
    assert_eq!(get["offsets"].shape, [j as u64, 3]);
    assert_eq!(get["offsets"].f64s(), offsets);
    let has: Vec<u8> = get["has_translation"].data.clone();
    assert_eq!(get["has_translation"].descr, "|b1");
    assert_eq!(has[0], 1);
    assert!(has[1..].iter().all(|&b| b == 0));
    let text = |name: &str| {
        assert!(get[name].shape.is_empty(), "{name} is 0-d");
        get[name].strings().remove(0)
    };
    assert_eq!(
        (text("fps"), text("rotation"), text("angles")),
        ("120".into(), "quat".into(), "deg".into())
    );
    let (times, rot, vel, pos) = (
        get["times"].f64s(),
        get["rotations"].f64s(),
        get["velocities"].f64s(),
        get["translations"].f64s(),
    );
    let frames: Vec<i64> = get["frames"]
        .data
        .chunks_exact(8)
        .map(|c| i64::from_le_bytes(c.try_into().unwrap()))
        .collect();
    for jj in 0..j {
        for tt in 0..t {
            let row = &rows[(jj * t + tt) * cols..(jj * t + tt + 1) * cols];
            let cell = tt * j + jj;
            assert_eq!(row[0], jj as f64);
            assert_eq!((row[1], row[2]), (frames[tt] as f64, times[tt]));
            assert_eq!(&row[3..7], &rot[4 * cell..4 * cell + 4], "{jj} {tt}");
            assert_eq!(&row[7..10], &vel[3 * cell..3 * cell + 3]);
            assert_eq!(&row[10..13], &pos[3 * cell..3 * cell + 3]);
        }
    }
}

/// A clip with positions on every joint (`cmu_01_01_positions.bvh`: each joint's position
/// channels at its OFFSET, the root's captured): its npz marks every joint as translated, and
/// each joint's translation on every frame is what the file says, read here from its text — the
/// OFFSET of every joint but the root, and the root's first three numbers of each motion row.
/// With the checkers' Python, the file is also what `make_all_positions.py` makes of
/// `cmu_01_01.bvh`.
#[test]
fn npz_of_a_clip_with_positions_on_every_joint() {
    if let Some(python) = checker_python("cmu_01_01_positions.bvh regeneration check") {
        let script = crate::support::fixtures().join("bvh/make_all_positions.py");
        let o = std::process::Command::new(python)
            .arg(script)
            .arg("--check")
            .output()
            .unwrap();
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    }
    let dir = tempfile::tempdir().unwrap();
    let z = dir.path().join("f.npz");
    let clip = "fixtures/bvh/cmu_01_01_positions.bvh";
    interp_to(&[clip], &z);
    let text =
        std::fs::read_to_string(crate::support::fixtures().join("bvh/cmu_01_01_positions.bvh"))
            .unwrap();
    let (hierarchy, motion) = text.split_once("MOTION\n").unwrap();
    let numbers =
        |s: &str| -> Vec<f64> { s.split_whitespace().map(|x| x.parse().unwrap()).collect() };
    // Each joint's name and OFFSET, in file order (an End Site's OFFSET follows "End Site").
    let (mut joints, mut name, mut end_site) = (Vec::new(), String::new(), false);
    for line in hierarchy.lines().map(str::trim) {
        if let Some(n) = line.strip_prefix("ROOT ").or(line.strip_prefix("JOINT ")) {
            name = n.to_string();
        } else if line == "End Site" {
            end_site = true;
        } else if let Some(o) = line.strip_prefix("OFFSET ")
            && !std::mem::take(&mut end_site)
        {
            joints.push((name.clone(), numbers(o)));
        }
    }
    let rows: Vec<Vec<f64>> = motion.lines().skip(2).map(numbers).collect();
    assert_eq!((joints.len(), rows.len()), (31, 61));
    let arrays = npz(&std::fs::read(&z).unwrap());
    let get: HashMap<&str, &Array> = arrays.iter().map(|(n, a)| (n.as_str(), a)).collect();
    let names: Vec<String> = joints.iter().map(|(n, _)| n.clone()).collect();
    assert_eq!(get["names"].strings(), names);
    assert!(get["has_translation"].data.iter().all(|&b| b == 1));
    assert_eq!(get["translations"].shape, [61, 31, 3]);
    let pos = get["translations"].f64s();
    for (t, row) in rows.iter().enumerate() {
        for (j, (name, offset)) in joints.iter().enumerate() {
            let want = if j == 0 { &row[..3] } else { &offset[..] };
            let cell = 3 * (t * 31 + j);
            assert_eq!(&pos[cell..cell + 3], want, "frame {t} {name}");
        }
    }
}

/// The rate as the tool spells it, the `--to` representation's values and names, an unnamed
/// track's empty name, and no velocity or translation arrays when there are none.
#[test]
fn npz_spells_the_rate_and_representation() {
    let dir = tempfile::tempdir().unwrap();
    let z = dir.path().join("f.npz");
    interp_to(
        &[
            "fixtures/interp/uniform.json",
            "--fps",
            "29.97",
            "--to",
            "euler:zyx",
            "--angles",
            "rad",
        ],
        &z,
    );
    let arrays = npz(&std::fs::read(&z).unwrap());
    let get: HashMap<&str, &Array> = arrays.iter().map(|(n, a)| (n.as_str(), a)).collect();
    assert!(!get.contains_key("velocities") && !get.contains_key("translations"));
    assert_eq!(get["fps"].strings(), ["30000/1001"]);
    assert_eq!(get["rotation"].strings(), ["euler:zyx"]);
    assert_eq!(get["angles"].strings(), ["rad"]);
    assert_eq!(get["names"].strings(), [""]);
    assert_eq!(get["names"].descr, "<U1");
    let t = get["times"].shape[0];
    assert_eq!(get["rotations"].shape, [t, 1, 3]);
}

/// convert and reduce write keys: npz is refused as npy is (exit 2, nothing written).
#[test]
fn npz_is_for_interp_only() {
    let dir = tempfile::tempdir().unwrap();
    let z = dir.path().join("keys.npz");
    for (args, want) in [
        (
            vec!["convert", "fixtures/interp/uniform.json"],
            format!(
                "inbetween: error: -o {}: convert writes keyframe documents (csv or json); npz is \
                 for interp's frames\n",
                z.display()
            ),
        ),
        (
            vec!["reduce", "fixtures/interp/uniform.json", "--tolerance", "1"],
            "inbetween: error: reduce writes keys: csv, json, or glTF for a glTF input, not npz\n"
                .to_string(),
        ),
    ] {
        let out = bin().args(&args).arg("-o").arg(&z).output().unwrap();
        assert_eq!(out.status.code(), Some(2), "{args:?}");
        assert_eq!(String::from_utf8_lossy(&out.stderr), want);
        assert!(!z.exists());
    }
}

/// numpy's reading (`np.load`, no pickles; Python's zipfile checking every CRC) of the npz and
/// the npy of one command, against its JSON output, value for value: a BVH clip (the root alone
/// with positions; all its tracks and some), the same clip with positions on every joint (as Bandai Namco's captures and
/// Blender's exports have them), glTF assets (translations on one channel, STEP and CUBICSPLINE
/// samplers; RiggedSimple; CesiumMan at 30 fps, a translation on each of its 19 joints), plain
/// and with velocities in another representation and unit; and, so that the check cannot pass
/// by reading nothing, a JSON of other digits (`--precision 6`) fails it.
#[test]
fn numpy_reads_npz_and_npy_as_the_json_says() {
    let Some(python) = checker_python("npz/npy check against numpy") else {
        return;
    };
    let dir = tempfile::tempdir().unwrap();
    let (j, z, y) = (
        dir.path().join("f.json"),
        dir.path().join("f.npz"),
        dir.path().join("f.npy"),
    );
    let check = |python: &Path| {
        let args = [j.as_os_str(), z.as_os_str(), y.as_os_str()];
        python_json(python, "fixtures/npz/check.py", &args)
    };
    // (input, its options, how many tracks have a translation on every frame)
    for (input, options, translated) in [
        ("fixtures/bvh/cmu_01_01.bvh", &[][..], 1),
        // Some tracks, the others' values never kept (issue 48).
        ("fixtures/bvh/cmu_01_01.bvh", &["--tracks", "Left*,Hips"], 1),
        ("fixtures/bvh/cmu_01_01_positions.bvh", &[], 31),
        ("fixtures/gltf/samplers.glb", &[], 1),
        ("fixtures/gltf/real/RiggedSimple.gltf", &[], 2),
        ("fixtures/gltf/real/CesiumMan.glb", &["--fps", "30"], 19),
    ] {
        for extra in [
            &[][..],
            &["--velocity", "--to", "euler:ZXY", "--angles", "rad"],
        ] {
            for path in [&j, &z, &y] {
                let mut c = bin();
                c.args(["interp", input]).args(options).args(extra);
                c.arg("-o").arg(path).assert().success();
            }
            let summary = check(&python);
            assert_eq!(summary["translations"], true, "{input} {extra:?}");
            assert_eq!(summary["velocity"], !extra.is_empty(), "{input} {extra:?}");
            assert!(summary["frames"].as_u64().unwrap() > 10, "{summary}");
            assert_eq!(summary["tracks_with_translation"], translated, "{summary}");
        }
    }
    // The control: rounded JSON digits differ from the arrays' exact values.
    let input = "fixtures/gltf/real/RiggedSimple.gltf";
    bin()
        .args(["interp", input, "--precision", "6", "-o"])
        .arg(&j)
        .assert()
        .success();
    for path in [&z, &y] {
        bin()
            .args(["interp", input, "-o"])
            .arg(path)
            .assert()
            .success();
    }
    let o = std::process::Command::new(&python)
        .arg("fixtures/npz/check.py")
        .args([&j, &z, &y])
        .current_dir(concat!(env!("CARGO_MANIFEST_DIR"), "/../.."))
        .output()
        .unwrap();
    assert!(!o.status.success());
    assert!(
        String::from_utf8_lossy(&o.stderr).contains("rotations"),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
}

/// One 150 000-character track name among 200 tracks: names.npy stores every name at the
/// longest's width (120 MB of padding), refused before anything is held or written (it
/// allocated gigabytes and aborted, leaving the temporary file); shorter names are written.
#[test]
fn npz_names_of_absurd_width_are_refused_up_front() {
    let dir = tempfile::tempdir().unwrap();
    let doc = |long: usize| {
        let tracks: Vec<serde_json::Value> = (0..200)
            .map(|i| {
                let name = if i == 0 {
                    "n".repeat(long)
                } else {
                    format!("t{i}")
                };
                serde_json::json!({"name": name, "keys": [
                    {"time": 0, "quat": [1, 0, 0, 0]}, {"time": 1, "quat": [1, 0, 0, 0]}]})
            })
            .collect();
        serde_json::json!({ "tracks": tracks }).to_string()
    };
    let input = dir.path().join("long.json");
    let out = dir.path().join("out.npz");
    std::fs::write(&input, doc(150_000)).unwrap();
    let err = crate::support::stderr_of(
        bin()
            .arg("interp")
            .arg(&input)
            .args(["--fps", "30", "-o"])
            .arg(&out),
        2,
    );
    assert!(
        err.contains("at the longest name's width (150000 characters)"),
        "{err}"
    );
    assert!(err.len() < 400, "{err}");
    let left: Vec<_> = std::fs::read_dir(dir.path()).unwrap().collect();
    assert_eq!(left.len(), 1, "only the input: {left:?}");
    std::fs::write(&input, doc(1_000)).unwrap();
    bin()
        .arg("interp")
        .arg(&input)
        .args(["--fps", "30", "-o"])
        .arg(&out)
        .assert()
        .success();
}
