//! The reader's bounds, one test each, on archives built here (stored as `np.savez` writes
//! them, deflated as `np.savez_compressed` does); the fixtures (fixtures/amass) are numpy's own.

use super::*;
use crate::write::npy::array_header;
use crate::write::zip::{ZipWriter, crc32};

fn npy(descr: &str, shape: &[u64], data: &[u8]) -> Vec<u8> {
    let mut b = array_header(descr, shape);
    b.extend_from_slice(data);
    b
}

fn f8(values: &[f64]) -> Vec<u8> {
    values.iter().flat_map(|x| x.to_le_bytes()).collect()
}

fn stored(entries: &[(&str, Vec<u8>)]) -> Vec<u8> {
    let mut z = ZipWriter::new(Vec::new());
    for (n, b) in entries {
        z.entry(&format!("{n}.npy"), &[b]).unwrap();
    }
    z.finish().unwrap()
}

/// A deflated archive (method 8) of the entries, with numpy's names.
fn deflated(entries: &[(&str, Vec<u8>)]) -> Vec<u8> {
    let (mut out, mut cd) = (Vec::new(), Vec::new());
    for (n, b) in entries {
        let name = format!("{n}.npy");
        let packed = miniz_oxide::deflate::compress_to_vec(b, 6);
        let mut head = Vec::new();
        head.extend_from_slice(&20u16.to_le_bytes());
        head.extend_from_slice(&0u16.to_le_bytes());
        head.extend_from_slice(&8u16.to_le_bytes());
        head.extend_from_slice(&[0; 4]);
        head.extend_from_slice(&crc32(0, b).to_le_bytes());
        head.extend_from_slice(&(packed.len() as u32).to_le_bytes());
        head.extend_from_slice(&(b.len() as u32).to_le_bytes());
        head.extend_from_slice(&(name.len() as u16).to_le_bytes());
        head.extend_from_slice(&0u16.to_le_bytes());
        cd.extend_from_slice(&0x0201_4b50u32.to_le_bytes());
        cd.extend_from_slice(&20u16.to_le_bytes());
        cd.extend_from_slice(&head);
        cd.extend_from_slice(&[0; 10]);
        cd.extend_from_slice(&(out.len() as u32).to_le_bytes());
        cd.extend_from_slice(name.as_bytes());
        out.extend_from_slice(&0x0403_4b50u32.to_le_bytes());
        out.extend_from_slice(&head);
        out.extend_from_slice(name.as_bytes());
        out.extend_from_slice(&packed);
    }
    let at = out.len() as u32;
    out.extend_from_slice(&cd);
    out.extend_from_slice(&0x0605_4b50u32.to_le_bytes());
    out.extend_from_slice(&[0; 4]);
    out.extend_from_slice(&(entries.len() as u16).to_le_bytes());
    out.extend_from_slice(&(entries.len() as u16).to_le_bytes());
    out.extend_from_slice(&(cd.len() as u32).to_le_bytes());
    out.extend_from_slice(&at.to_le_bytes());
    out.extend_from_slice(&0u16.to_le_bytes());
    out
}

/// Two frames of SMPL-H: joint 1 turned about x by 0.5 then 0.7 rad, trans, a rate, a gender.
fn smplh(rate: f64) -> Vec<(&'static str, Vec<u8>)> {
    let mut poses = vec![0.0; 2 * 156];
    poses[3] = 0.5;
    poses[156 + 3] = 0.7;
    vec![
        ("poses", npy("<f8", &[2, 156], &f8(&poses))),
        (
            "trans",
            npy("<f8", &[2, 3], &f8(&[0.0, 0.0, 1.0, 0.1, 0.0, 1.0])),
        ),
        ("gender", npy("<U6", &[], &[b'm', 0, 0, 0].repeat(6))),
        ("mocap_framerate", npy("<f8", &[], &f8(&[rate]))),
    ]
}

fn err(bytes: &[u8]) -> String {
    read(bytes, "a.npz", None).unwrap_err().message()
}

#[test]
fn stored_and_deflated_archives_read_alike() {
    for bytes in [stored(&smplh(120.0)), deflated(&smplh(120.0))] {
        let a = read(&bytes, "a.npz", None).unwrap();
        assert_eq!(
            (a.model(), a.frames(), a.fps()),
            (Model::SmplH, 2, Fps::new(120, 1).unwrap())
        );
        assert_eq!(a.rotvec(1, 1), [0.7, 0.0, 0.0]);
        let doc = a.document().unwrap();
        assert_eq!(doc.tracks.len(), 52);
        assert_eq!(doc.tracks[1].name.as_deref(), Some("left_hip"));
        let q = doc.tracks[1].keys[1].rot;
        assert!((q.w - (0.35f64).cos()).abs() < 1e-15 && (q.x - (0.35f64).sin()).abs() < 1e-15);
        assert_eq!(doc.tracks[0].translations.len(), 2);
        assert!(doc.tracks[1].translations.is_empty());
    }
}

#[test]
fn the_rate_is_read_as_the_frame_rate_flag_reads_it() {
    let a = read(&stored(&smplh(59.94)), "a.npz", None).unwrap();
    assert_eq!(a.fps(), Fps::new(60000, 1001).unwrap());
    let mut x = smplh(60.0);
    x[3].0 = "mocap_frame_rate";
    let a = read(&stored(&x), "a.npz", None).unwrap();
    assert_eq!(
        (a.fps().num(), a.rate_key()),
        (60, Some("mocap_frame_rate"))
    );
    x.pop();
    assert!(err(&stored(&x)).contains("no key \"mocap_framerate\" or \"mocap_frame_rate\""));
    let given = read(&stored(&x), "a.npz", Some(Fps::new(30, 1).unwrap())).unwrap();
    assert_eq!((given.fps().num(), given.rate_key()), (30, None));
    let e = read(
        &stored(&smplh(120.0)),
        "a.npz",
        Some(Fps::new(30, 1).unwrap()),
    )
    .unwrap_err();
    assert_eq!(
        e.message(),
        "a.npz declares \"mocap_framerate\": 120 but key rate says 30"
    );
}

#[test]
fn a_truncated_archive_is_refused() {
    let bytes = stored(&smplh(120.0));
    for cut in [0, 10, bytes.len() / 2, bytes.len() - 1] {
        let e = err(&bytes[..cut]);
        assert!(
            e.starts_with("a.npz: not a readable zip archive (.npz)"),
            "{cut}: {e}"
        );
    }
}

#[test]
fn a_directory_outside_the_file_is_refused() {
    let mut bytes = stored(&smplh(120.0));
    let n = bytes.len();
    bytes[n - 6..n - 2].copy_from_slice(&u32::MAX.to_le_bytes());
    assert!(
        err(&bytes).contains("its central directory"),
        "{}",
        err(&bytes)
    );
}

#[test]
fn more_entries_than_the_directory_holds_are_refused_before_allocating() {
    let mut bytes = stored(&smplh(120.0));
    let n = bytes.len();
    bytes[n - 12..n - 10].copy_from_slice(&0xFFFEu16.to_le_bytes());
    assert!(
        err(&bytes).contains("65534 entries declared"),
        "{}",
        err(&bytes)
    );
}

#[test]
fn an_entry_outside_the_file_is_refused() {
    let mut bytes = stored(&smplh(120.0));
    // The first central header's compressed size (offset 20 in it).
    let cd = u32::from_le_bytes(bytes[bytes.len() - 6..bytes.len() - 2].try_into().unwrap());
    let at = cd as usize + 20;
    bytes[at..at + 4].copy_from_slice(&0x7FFF_FFFFu32.to_le_bytes());
    assert!(
        err(&bytes).contains("its data is outside the file"),
        "{}",
        err(&bytes)
    );
}

#[test]
fn a_deflated_entry_claiming_too_much_is_refused_before_inflating() {
    let mut bytes = deflated(&smplh(120.0));
    let cd = u32::from_le_bytes(bytes[bytes.len() - 6..bytes.len() - 2].try_into().unwrap());
    let at = cd as usize + 24;
    bytes[at..at + 4].copy_from_slice(&u32::MAX.to_le_bytes());
    let e = err(&bytes);
    assert!(
        e.contains("declare more than 1073741824 bytes in all"),
        "{e}"
    );
}

#[test]
fn corrupt_bytes_fail_their_crc() {
    let mut bytes = stored(&smplh(120.0));
    bytes[200] ^= 1;
    let e = err(&bytes);
    assert!(e.contains("CRC-32 does not match"), "{e}");
}

#[test]
fn missing_poses_wrong_shapes_and_objects_name_the_key() {
    let x = smplh(120.0);
    assert!(err(&stored(&x[1..])).starts_with("a.npz: no key \"poses\""));
    let mut y = x.clone();
    y[0].1 = npy("<f8", &[1, 72], &f8(&[0.0; 72]));
    let e = err(&stored(&y));
    assert!(
        e.starts_with("a.npz: key \"poses\": expected float rotation vectors of shape"),
        "{e}"
    );
    let mut y = x.clone();
    y[1].1 = npy("<f8", &[3, 3], &f8(&[0.0; 9]));
    assert!(err(&stored(&y)).starts_with("a.npz: key \"trans\": expected floats of shape (2, 3)"));
    let mut y = x.clone();
    y[2].1 = npy("|O", &[], &[]);
    assert!(err(&stored(&y)).starts_with("a.npz: key \"gender\": an object array"));
    let mut y = x;
    y[0].1.truncate(200);
    assert!(err(&stored(&y)).contains("key \"poses\": not a readable .npy array"));
}

#[test]
fn resampled_at_half_rate_keeps_every_other_row_exactly() {
    let mut x = smplh(120.0);
    let mut poses = vec![0.0; 3 * 156];
    for (i, v) in [0.1, 0.2, 0.3].iter().enumerate() {
        poses[i * 156 + 3] = *v;
    }
    x[0].1 = npy("<f8", &[3, 156], &f8(&poses));
    x[1].1 = npy(
        "<f8",
        &[3, 3],
        &f8(&[0.0, 0.0, 0.0, 1.0, 2.0, 3.0, 2.0, 4.0, 6.0]),
    );
    let a = read(&stored(&x), "a.npz", None).unwrap();
    let doc = a.document().unwrap();
    let at = |j: usize, t: f64| doc.tracks[j].keys[(t * 120.0).round() as usize].rot;
    let out = a.resample(Fps::new(60, 1).unwrap(), &at).unwrap();
    assert_eq!(out.frames(), 2);
    let back = read(&out.write(Vec::new()).unwrap(), "b.npz", None).unwrap();
    assert_eq!(back.fps(), Fps::new(60, 1).unwrap());
    assert!((back.rotvec(1, 1)[0] - 0.3).abs() < 1e-15);
    let trans = back.arrays().iter().find(|(k, _)| k == "trans").unwrap();
    assert_eq!(
        trans.1.floats().unwrap(),
        vec![0.0, 0.0, 0.0, 2.0, 4.0, 6.0]
    );
    let gender = back.arrays().iter().find(|(k, _)| k == "gender").unwrap();
    assert_eq!(gender.1.bytes, x[2].1);
}

/// A per-frame array of integers (flags, labels) cannot be blended: each new frame takes the
/// nearest source frame's row; in Fortran order it is refused, naming the key.
#[test]
fn per_frame_integers_take_the_nearest_row() {
    let mut x = smplh(120.0);
    x[0].1 = npy("<f8", &[3, 156], &f8(&[0.0; 3 * 156]));
    x[1].1 = npy("<f8", &[3, 3], &f8(&[0.0; 9]));
    let ints: Vec<u8> = [10i32, 11, 20, 21, 30, 31]
        .iter()
        .flat_map(|v| v.to_le_bytes())
        .collect();
    x.push(("contact", npy("<i4", &[3, 2], &ints)));
    let a = read(&stored(&x), "a.npz", None).unwrap();
    let doc = a.document().unwrap();
    let at = |j: usize, t: f64| doc.tracks[j].keys[(t * 120.0).round() as usize].rot;
    // 120 → 80 fps: new frames at source positions 0 and 1.5 (→ row 1, a tie goes down).
    let out = a.resample(Fps::new(80, 1).unwrap(), &at).unwrap();
    assert_eq!(out.frames(), 2);
    let back = read(&out.write(Vec::new()).unwrap(), "b.npz", None).unwrap();
    let contact = back.arrays().iter().find(|(k, _)| k == "contact").unwrap();
    assert_eq!(contact.1.shape, vec![2, 2]);
    let data = &contact.1.bytes[contact.1.data_at..];
    let rows: Vec<i32> = data
        .chunks_exact(4)
        .map(|b| i32::from_le_bytes([b[0], b[1], b[2], b[3]]))
        .collect();
    assert_eq!(rows, vec![10, 11, 20, 21]);
    // 120 → 70: positions 0 and 12/7 ≈ 1.71 → row 2.
    let out = a.resample(Fps::new(70, 1).unwrap(), &at).unwrap();
    let back = read(&out.write(Vec::new()).unwrap(), "c.npz", None).unwrap();
    let contact = back.arrays().iter().find(|(k, _)| k == "contact").unwrap();
    let last = &contact.1.bytes[contact.1.bytes.len() - 8..];
    assert_eq!(
        last,
        [30i32, 31]
            .iter()
            .flat_map(|v| v.to_le_bytes())
            .collect::<Vec<u8>>()
    );
    let mut fortran = npy("<i4", &[3, 2], &ints);
    let (from, to) = (b"'fortran_order': False", b"'fortran_order': True ");
    let at_flag = fortran.windows(from.len()).position(|w| w == from).unwrap();
    fortran[at_flag..at_flag + to.len()].copy_from_slice(to);
    x[4].1 = fortran;
    let a = read(&stored(&x), "f.npz", None).unwrap();
    let e = a
        .resample(Fps::new(80, 1).unwrap(), &at)
        .err()
        .unwrap()
        .message()
        .to_string();
    assert!(e.contains("\"contact\"") && e.contains("Fortran"), "{e}");
}

/// `archive` with its end record moved to ZIP64 (as a writer does past 65 535 entries or
/// 4 GiB): a ZIP64 end record and locator, and the classic end record's fields saturated.
fn as_zip64(archive: &[u8]) -> Vec<u8> {
    let eocd = archive.len() - 22;
    let u16_at = |i: usize| u16::from_le_bytes([archive[i], archive[i + 1]]);
    let u32_at = |i: usize| u32::from_le_bytes(archive[i..i + 4].try_into().unwrap());
    let (entries, size, offset) = (
        u64::from(u16_at(eocd + 10)),
        u64::from(u32_at(eocd + 12)),
        u64::from(u32_at(eocd + 16)),
    );
    let mut out = archive[..eocd].to_vec();
    let record = out.len() as u64;
    out.extend_from_slice(&0x0606_4b50u32.to_le_bytes());
    out.extend_from_slice(&44u64.to_le_bytes());
    out.extend_from_slice(&45u16.to_le_bytes());
    out.extend_from_slice(&45u16.to_le_bytes());
    out.extend_from_slice(&[0; 8]);
    for v in [entries, entries, size, offset] {
        out.extend_from_slice(&v.to_le_bytes());
    }
    out.extend_from_slice(&0x0706_4b50u32.to_le_bytes());
    out.extend_from_slice(&0u32.to_le_bytes());
    out.extend_from_slice(&record.to_le_bytes());
    out.extend_from_slice(&1u32.to_le_bytes());
    out.extend_from_slice(&archive[eocd..eocd + 8]);
    out.extend_from_slice(&[0xff; 4]);
    out.extend_from_slice(&[0xff; 8]);
    out.extend_from_slice(&0u16.to_le_bytes());
    out
}

/// An archive whose directory is found through its ZIP64 end record reads as the classic one.
#[test]
fn a_zip64_end_record_reads_as_the_classic_one() {
    let classic = stored(&smplh(120.0));
    let zip64 = as_zip64(&classic);
    assert_ne!(zip64, classic);
    let (a, b) = (
        read(&classic, "a.npz", None).unwrap(),
        read(&zip64, "b.npz", None).unwrap(),
    );
    assert_eq!(a.frames(), b.frames());
    assert_eq!(a.rotvec(1, 1), b.rotvec(1, 1));
    // The locator pointing outside the file is refused.
    let mut bad = zip64.clone();
    let at = bad.len() - 22 - 20 + 8;
    bad[at..at + 8].copy_from_slice(&u64::MAX.to_le_bytes());
    assert!(err(&bad).contains("ZIP64"), "{}", err(&bad));
}

/// AMASS's other per-frame arrays must have poses' row count: a short `dmpls` is a broken
/// file, refused naming the key (it was copied with its own rows).
#[test]
fn a_per_frame_array_of_another_length_is_refused() {
    let mut x = smplh(120.0);
    x.push(("dmpls", npy("<f8", &[1, 8], &f8(&[0.0; 8]))));
    let e = err(&stored(&x));
    assert!(
        e.contains("key \"dmpls\": expected one row per frame of poses (2), found shape (1, 8)"),
        "{e}"
    );
}
