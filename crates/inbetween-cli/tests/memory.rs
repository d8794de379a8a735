//! Memory of `reduce` on a BVH clip (issue 24), in a test binary of its own: a child's peak
//! resident memory (`wait4`'s `ru_maxrss`) starts from its parent's at the fork, so the parent
//! must be small when it spawns — this binary runs this one test and nothing else.

/// A clip of `joints` joints in a chain (the root with positions, every joint `ZXY` rotations),
/// `frames` rows at 120 fps, smooth motion with 6 decimals: the benchmark clip's shape
/// (`benches/compare/bvh/gen_clip.py`), smaller.
fn chain_clip(joints: usize, frames: usize) -> String {
    let mut text = String::from("HIERARCHY\n");
    for j in 0..joints {
        let kind = if j == 0 { "ROOT" } else { "JOINT" };
        let channels = if j == 0 {
            "CHANNELS 6 Xposition Yposition Zposition Zrotation Xrotation Yrotation"
        } else {
            "CHANNELS 3 Zrotation Xrotation Yrotation"
        };
        text += &format!("{kind} j{j}\n{{\nOFFSET 0 1 0\n{channels}\n");
    }
    text += "End Site\n{\nOFFSET 0 1 0\n}\n";
    text += &"}\n".repeat(joints);
    text += &format!("MOTION\nFrames: {frames}\nFrame Time: 0.008333\n");
    let mut row = Vec::new();
    for i in 0..frames {
        let t = i as f64 / 120.0;
        row.clear();
        row.extend([3.0 * t, 90.0 + (2.0 * t).sin(), -t]);
        for j in 0..joints {
            let p = j as f64 * 0.37;
            row.extend([
                40.0 * (0.9 * t + p).sin(),
                25.0 * (1.7 * t + 2.0 * p).cos(),
                30.0 * (0.6 * t - p).sin(),
            ]);
        }
        let cells: Vec<String> = row.iter().map(|x| format!("{x:.6}")).collect();
        text += &(cells.join(" ") + "\n");
    }
    text
}

/// The peak resident memory (bytes) of `inbetween ARGS`, run on one core so that one joint at a
/// time is being reduced (the binary's threads follow its CPU affinity): `wait4`'s own figure for
/// that child, whatever else the test process runs.
fn peak_rss(args: &[&std::ffi::OsStr]) -> u64 {
    use std::os::unix::process::CommandExt;
    let mut cmd = std::process::Command::new(env!("CARGO_BIN_EXE_inbetween"));
    cmd.args(args);
    // SAFETY: only async-signal-safe calls between fork and exec (sched_getaffinity,
    // sched_setaffinity on the child itself, CPU_* bit operations).
    unsafe {
        cmd.pre_exec(|| {
            let mut set: libc::cpu_set_t = std::mem::zeroed();
            let size = std::mem::size_of::<libc::cpu_set_t>();
            if libc::sched_getaffinity(0, size, &mut set) == 0 {
                let first = (0..libc::CPU_SETSIZE as usize).find(|&c| libc::CPU_ISSET(c, &set));
                if let Some(c) = first {
                    libc::CPU_ZERO(&mut set);
                    libc::CPU_SET(c, &mut set);
                    libc::sched_setaffinity(0, size, &set);
                }
            }
            Ok(())
        });
    }
    // Waited for by wait4 below, which gives the child's own resource usage.
    #[allow(clippy::zombie_processes)]
    let child = cmd.stderr(std::process::Stdio::null()).spawn().unwrap();
    let mut status = 0;
    // SAFETY: a zeroed rusage is valid; the child is ours and waited for once.
    let mut usage: libc::rusage = unsafe { std::mem::zeroed() };
    let pid = child.id() as libc::pid_t;
    let got = unsafe { libc::wait4(pid, &mut status, 0, &mut usage) };
    assert_eq!(got, pid);
    assert!(libc::WIFEXITED(status) && libc::WEXITSTATUS(status) == 0);
    // Linux gives ru_maxrss in KiB.
    u64::try_from(usage.ru_maxrss).unwrap() * 1024
}

/// Issue 24: `reduce` of a BVH file peaks below twice the file plus 8 MiB (the budget,
/// 64 MiB, scaled to a small file): the clip's values (about the file's size) plus one joint's
/// frames at a time. The general path held the text, the clip, a document of every key and
/// the tracks at once: about 6 times the file (33 MiB here, against 10 to 12 MiB). Memory, not time: not load-bound.
#[test]
fn a_bvh_clip_is_reduced_in_bounded_memory() {
    let dir = tempfile::tempdir().unwrap();
    let (src, out) = (dir.path().join("clip.bvh"), dir.path().join("keys.json"));
    // Written and dropped before the child is spawned (the child's peak starts from ours).
    std::fs::write(&src, chain_clip(60, 3000)).unwrap();
    let size = std::fs::metadata(&src).unwrap().len();
    let peak = peak_rss(&[
        "reduce".as_ref(),
        src.as_os_str(),
        "--tolerance".as_ref(),
        "0.5".as_ref(),
        "--translation-tolerance".as_ref(),
        "0.1".as_ref(),
        "-o".as_ref(),
        out.as_os_str(),
    ]);
    let budget = 2 * size + (8 << 20);
    assert!(
        peak <= budget,
        "peak {:.1} MiB, file {:.1} MiB, budget {:.1} MiB",
        peak as f64 / 1048576.0,
        size as f64 / 1048576.0,
        budget as f64 / 1048576.0
    );
    assert!(std::fs::metadata(&out).unwrap().len() > 0);
}

/// Issue 48: `interp` of a BVH file to npz peaks below twice the archive plus 16 MiB (the
/// issue's 64 MiB scaled to a small clip; 8 MiB was exceeded by 0.7 MiB in a debug build once
/// the spline tangent's window logs were added): the arrays (the archive's size) and the clip's
/// values, nothing else. The general path held the text, a document of every key, the tracks
/// and their curves, and the writer copied the largest array whole: about 68 MiB here.
/// `--tracks` never raises the peak (it sent CSV output to the general path: 4× the peak).
#[test]
fn a_bvh_clip_is_interpolated_to_npz_in_memory_of_the_output() {
    let dir = tempfile::tempdir().unwrap();
    let src = dir.path().join("clip.bvh");
    std::fs::write(&src, chain_clip(60, 3000)).unwrap();
    let out = |name: &str| dir.path().join(name);
    let interp = |extra: &[&str], name: &str| {
        let mut args = vec!["interp".as_ref(), src.as_os_str()];
        args.extend(extra.iter().map(std::ffi::OsStr::new));
        let path = out(name);
        args.extend(["-o".as_ref(), path.as_os_str()]);
        let peak = peak_rss(&args);
        (peak, std::fs::metadata(&path).unwrap().len())
    };
    let mib = |b: u64| b as f64 / 1048576.0;
    let (peak, size) = interp(&[], "all.npz");
    let budget = 2 * size + (16 << 20);
    assert!(
        peak <= budget,
        "npz: peak {:.1} MiB, archive {:.1} MiB, budget {:.1} MiB",
        mib(peak),
        mib(size),
        mib(budget)
    );
    let (few, few_size) = interp(&["--tracks", "j0,j1*"], "few.npz");
    assert!(few_size < size / 4);
    assert!(
        few <= peak,
        "--tracks: {:.1} MiB > {:.1} MiB",
        mib(few),
        mib(peak)
    );
    let (csv, _) = interp(&[], "all.csv");
    let (few_csv, _) = interp(&["--tracks", "j0,j1*"], "few.csv");
    assert!(
        few_csv <= csv,
        "csv --tracks: {:.1} MiB > {:.1} MiB",
        mib(few_csv),
        mib(csv)
    );
}
