//! `-o PATH` onto whatever `PATH` is (issue 11): a file or nothing is replaced atomically with
//! the right mode, a symbolic link's target is replaced and the link kept, a device or FIFO is
//! written in place, a directory or a missing directory is an input error; and SIGINT, SIGTERM
//! or SIGHUP during a run remove the temporary file.

use std::os::unix::fs::{FileTypeExt, PermissionsExt};
use std::os::unix::process::ExitStatusExt;
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Output, Stdio};
use std::time::{Duration, Instant};

const BIN: &str = env!("CARGO_BIN_EXE_inbetween");

fn fixture() -> PathBuf {
    crate::support::fixtures().join("interp/uniform.json")
}

/// `inbetween interp uniform.json -o <target>`, run in `dir`.
fn interp_to(dir: &Path, target: &str) -> Output {
    Command::new(BIN)
        .current_dir(dir)
        .arg("interp")
        .arg(fixture())
        .args(["-o", target])
        .output()
        .unwrap()
}

/// What the same run writes to standard output.
fn expected() -> Vec<u8> {
    let out = Command::new(BIN)
        .arg("interp")
        .arg(fixture())
        .output()
        .unwrap();
    assert!(out.status.success());
    out.stdout
}

fn names(dir: &Path) -> Vec<String> {
    let mut v: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    v.sort();
    v
}

#[track_caller]
fn assert_ok(out: &Output) {
    assert!(
        out.status.success(),
        "{:?}: {}",
        out.status,
        String::from_utf8_lossy(&out.stderr)
    );
}

fn mode(path: &Path) -> u32 {
    std::fs::metadata(path).unwrap().permissions().mode() & 0o777
}

/// The umask this process (and so the binary it starts) runs under.
fn umask() -> u32 {
    let out = Command::new("sh").args(["-c", "umask"]).output().unwrap();
    u32::from_str_radix(String::from_utf8(out.stdout).unwrap().trim(), 8).unwrap()
}

fn is_root() -> bool {
    Command::new("id")
        .arg("-u")
        .output()
        .is_ok_and(|o| o.stdout.trim_ascii() == b"0")
}

#[test]
fn a_new_file_gets_0666_less_the_umask_and_a_replaced_file_keeps_its_mode() {
    let dir = tempfile::tempdir().unwrap();
    let new = dir.path().join("new.json");
    assert_ok(&interp_to(dir.path(), "new.json"));
    assert_eq!(mode(&new), 0o666 & !umask());
    assert_eq!(std::fs::read(&new).unwrap(), expected());
    let old = dir.path().join("old.json");
    std::fs::write(&old, "precious\n").unwrap();
    std::fs::set_permissions(&old, std::fs::Permissions::from_mode(0o640)).unwrap();
    assert_ok(&interp_to(dir.path(), "old.json"));
    assert_eq!(mode(&old), 0o640);
    assert_eq!(std::fs::read(&old).unwrap(), expected());
    assert_eq!(names(dir.path()), ["new.json", "old.json"]);
}

/// `mkfifo f; reader < f & inbetween … -o f`: the bytes go through the FIFO, which stays one
/// (it used to be replaced by a regular file, and the reader waited forever).
#[test]
fn a_fifo_is_written_through_and_stays_a_fifo() {
    let dir = tempfile::tempdir().unwrap();
    let fifo = dir.path().join("f");
    assert!(
        Command::new("mkfifo")
            .arg(&fifo)
            .status()
            .unwrap()
            .success()
    );
    let reader = {
        let fifo = fifo.clone();
        std::thread::spawn(move || std::fs::read(fifo).unwrap())
    };
    let out = interp_to(dir.path(), "f");
    assert_ok(&out);
    let kind = std::fs::symlink_metadata(&fifo).unwrap().file_type();
    assert!(kind.is_fifo(), "{kind:?}");
    assert_eq!(reader.join().unwrap(), expected());
    assert_eq!(names(dir.path()), ["f"]);
}

/// `-o /dev/null` as root used to replace the device node by a regular file. Tried on a node of
/// its own (made with mknod, the numbers of /dev/null), never on the real one.
#[test]
fn a_character_device_is_written_in_place() {
    if !is_root() {
        eprintln!("skipped: making a device node with mknod needs root");
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let dev = dir.path().join("null");
    let made = Command::new("mknod")
        .arg(&dev)
        .args(["c", "1", "3"])
        .stderr(Stdio::null())
        .status()
        .unwrap();
    if !made.success() {
        eprintln!("skipped: mknod failed (no CAP_MKNOD here?)");
        return;
    }
    let out = interp_to(dir.path(), "null");
    assert_ok(&out);
    let kind = std::fs::symlink_metadata(&dev).unwrap().file_type();
    assert!(kind.is_char_device(), "{kind:?}");
    assert_eq!(names(dir.path()), ["null"]);
}

/// A symbolic link stays a link; the file it points to (here in another directory, so the
/// temporary file must go there) is replaced and keeps its mode. A dangling link gets its
/// target created.
#[test]
fn a_symbolic_link_stays_and_its_target_is_replaced() {
    let dir = tempfile::tempdir().unwrap();
    let sub = dir.path().join("sub");
    std::fs::create_dir(&sub).unwrap();
    let real = sub.join("real.json");
    std::fs::write(&real, "precious\n").unwrap();
    std::fs::set_permissions(&real, std::fs::Permissions::from_mode(0o640)).unwrap();
    std::os::unix::fs::symlink("sub/real.json", dir.path().join("link")).unwrap();
    // A chain: link2 -> link -> sub/real.json.
    std::os::unix::fs::symlink("link", dir.path().join("link2")).unwrap();
    for name in ["link", "link2"] {
        std::fs::write(&real, "precious\n").unwrap();
        assert_ok(&interp_to(dir.path(), name));
        let link = dir.path().join(name);
        assert!(
            std::fs::symlink_metadata(&link)
                .unwrap()
                .file_type()
                .is_symlink()
        );
        assert_eq!(std::fs::read(&real).unwrap(), expected(), "{name}");
        assert_eq!(mode(&real), 0o640);
    }
    assert_eq!(
        std::fs::read_link(dir.path().join("link")).unwrap(),
        Path::new("sub/real.json")
    );
    assert_eq!(names(&sub), ["real.json"]);
    // Dangling: the target is created, beside where the link points.
    std::os::unix::fs::symlink("sub/new.json", dir.path().join("dangling")).unwrap();
    assert_ok(&interp_to(dir.path(), "dangling"));
    assert_eq!(std::fs::read(sub.join("new.json")).unwrap(), expected());
    assert_eq!(names(&sub), ["new.json", "real.json"]);
    assert_eq!(names(dir.path()), ["dangling", "link", "link2", "sub"]);
}

/// What cannot be written: exit 2, a message naming the user's path, nothing created.
#[test]
fn a_directory_or_a_missing_directory_is_an_input_error() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::create_dir(dir.path().join("somedir")).unwrap();
    std::fs::write(dir.path().join("afile"), "precious\n").unwrap();
    std::os::unix::fs::symlink("loop2", dir.path().join("loop1")).unwrap();
    std::os::unix::fs::symlink("loop1", dir.path().join("loop2")).unwrap();
    let socket = std::os::unix::net::UnixListener::bind(dir.path().join("sock")).unwrap();
    let cases = [
        ("somedir", "-o somedir: expected a file, found a directory"),
        (
            "somedir/",
            "-o somedir/: expected a file, found a directory",
        ),
        (".", "-o .: expected a file, found a directory"),
        (
            "missing/dir/out.csv",
            "-o missing/dir/out.csv: directory missing/dir does not exist",
        ),
        (
            "afile/out.csv",
            "-o afile/out.csv: afile is not a directory",
        ),
        (
            "loop1",
            "-o loop1: expected a file, found a loop of symbolic links",
        ),
        ("sock", "-o sock: expected a file, found a socket"),
    ];
    for (target, message) in cases {
        let out = interp_to(dir.path(), target);
        assert_eq!(out.status.code(), Some(2), "{target}");
        assert_eq!(
            String::from_utf8_lossy(&out.stderr),
            format!("inbetween: error: {message}\n"),
            "{target}"
        );
        assert!(out.stdout.is_empty());
        assert_eq!(
            names(dir.path()),
            ["afile", "loop1", "loop2", "sock", "somedir"],
            "{target}"
        );
        assert!(names(&dir.path().join("somedir")).is_empty());
    }
    drop(socket);
}

/// Whether this process ignores `sig` (a child inherits that; the test is then moot).
fn ignored_here(sig: i32) -> bool {
    let status = std::fs::read_to_string("/proc/self/status").unwrap_or_default();
    status
        .lines()
        .find_map(|l| l.strip_prefix("SigIgn:"))
        .and_then(|mask| u64::from_str_radix(mask.trim(), 16).ok())
        .is_some_and(|mask| mask & (1 << (sig - 1)) != 0)
}

/// A run that writes for a long while (2·10⁷ frames) to `dir/out.csv`, from keys in `keys_dir`.
fn long_run(keys_dir: &Path, dir: &Path, wrapper: Option<&str>) -> Child {
    let keys = keys_dir.join("keys.csv");
    let mut text = String::from("time,w,x,y,z\n");
    for i in 0..=1000 {
        let half = 0.15 * i as f64;
        text += &format!("{i},{},{},0,0\n", half.cos(), half.sin());
    }
    std::fs::write(&keys, text).unwrap();
    let mut cmd = match wrapper {
        Some(w) => {
            let mut c = Command::new(w);
            c.arg(BIN);
            c
        }
        None => Command::new(BIN),
    };
    cmd.current_dir(dir)
        .arg("interp")
        .arg(&keys)
        .args(["--fps", "20000", "-o", "out.csv"])
        .stdin(Stdio::null())
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap()
}

fn temp_files(dir: &Path) -> Vec<String> {
    names(dir)
        .into_iter()
        .filter(|n| n.starts_with(".inbetween-"))
        .collect()
}

/// Waits until the run has created its temporary file.
fn wait_for_temp_file(child: &mut Child, dir: &Path) {
    let start = Instant::now();
    while temp_files(dir).is_empty() {
        if let Some(status) = child.try_wait().unwrap() {
            panic!("the run ended before writing: {status:?}");
        }
        assert!(
            start.elapsed() < Duration::from_secs(60),
            "no temporary file"
        );
        std::thread::sleep(Duration::from_millis(10));
    }
}

fn kill(child: &Child, sig: &str) {
    let ok = Command::new("kill")
        .args([&format!("-{sig}"), &child.id().to_string()])
        .status()
        .unwrap();
    assert!(ok.success());
}

/// Waits for the end (killing the run if it goes on: it would fill the disk).
fn wait(child: &mut Child) -> std::process::ExitStatus {
    let start = Instant::now();
    loop {
        if let Some(status) = child.try_wait().unwrap() {
            return status;
        }
        if start.elapsed() > Duration::from_secs(60) {
            let _ = child.kill();
            let _ = child.wait();
            panic!("the run did not end on the signal");
        }
        std::thread::sleep(Duration::from_millis(10));
    }
}

/// The run ends by the signal itself (a shell reports 128 + its number), the temporary file is
/// gone, and the target is as it was.
fn interrupted_run_leaves_nothing(sig: &str, number: i32, existing: Option<&str>) {
    if ignored_here(number) {
        eprintln!("skipped: this test process ignores SIG{sig}, and so would the binary");
        return;
    }
    let keys = tempfile::tempdir().unwrap();
    let dir = tempfile::tempdir().unwrap();
    let target = dir.path().join("out.csv");
    if let Some(text) = existing {
        std::fs::write(&target, text).unwrap();
    }
    let mut child = long_run(keys.path(), dir.path(), None);
    wait_for_temp_file(&mut child, dir.path());
    kill(&child, sig);
    let status = wait(&mut child);
    assert_eq!(status.signal(), Some(number), "{status:?}");
    assert_eq!(temp_files(dir.path()), Vec::<String>::new());
    match existing {
        Some(text) => assert_eq!(std::fs::read_to_string(&target).unwrap(), text),
        None => assert!(!target.exists()),
    }
}

#[test]
fn sigterm_removes_the_temporary_file() {
    interrupted_run_leaves_nothing("TERM", 15, None);
}

#[test]
fn sigint_removes_the_temporary_file_and_keeps_the_old_target() {
    interrupted_run_leaves_nothing("INT", 2, Some("precious\n"));
}

#[test]
fn sighup_removes_the_temporary_file() {
    interrupted_run_leaves_nothing("HUP", 1, None);
}

/// Under `nohup` SIGHUP stays ignored: the run goes on (a later SIGTERM still cleans up).
#[test]
fn an_ignored_signal_stays_ignored() {
    if Command::new("nohup").arg("true").status().is_err() {
        eprintln!("skipped: no nohup");
        return;
    }
    let keys = tempfile::tempdir().unwrap();
    let dir = tempfile::tempdir().unwrap();
    let mut child = long_run(keys.path(), dir.path(), Some("nohup"));
    wait_for_temp_file(&mut child, dir.path());
    kill(&child, "HUP");
    std::thread::sleep(Duration::from_millis(300));
    assert!(child.try_wait().unwrap().is_none(), "SIGHUP ended the run");
    kill(&child, "TERM");
    let status = wait(&mut child);
    assert_eq!(status.signal(), Some(15), "{status:?}");
    assert_eq!(temp_files(dir.path()), Vec::<String>::new());
    assert!(!dir.path().join("out.csv").exists());
}

/// `-o /dev/stdout` is standard output itself: appended to a `>>` file, not a replaced file.
#[test]
fn dev_stdout_is_standard_output_not_the_file_behind_it() {
    let dir = tempfile::tempdir().unwrap();
    let log = dir.path().join("log");
    std::fs::write(&log, "PREVIOUS\n").unwrap();
    let append = std::fs::OpenOptions::new().append(true).open(&log).unwrap();
    let status = std::process::Command::new(assert_cmd::cargo::cargo_bin("inbetween"))
        .current_dir(concat!(env!("CARGO_MANIFEST_DIR"), "/../.."))
        .args(["interp", "fixtures/interp/uniform.json", "--fps", "2"])
        .args(["--output-format", "csv", "-o", "/dev/stdout"])
        .stdout(append)
        .status()
        .unwrap();
    assert!(status.success());
    let text = std::fs::read_to_string(&log).unwrap();
    assert!(text.starts_with("PREVIOUS\nframe,time,w,x,y,z\n"), "{text}");
    assert_eq!(text.lines().count(), 7);
    // Into a pipe, too (there is no file behind it to follow).
    let out = crate::support::bin()
        .args(["interp", "fixtures/interp/uniform.json", "--fps", "2"])
        .args(["--output-format", "csv", "-o", "/dev/stdout"])
        .output()
        .unwrap();
    assert!(out.status.success());
    assert!(out.stdout.starts_with(b"frame,time"));
}

/// A path through a file, through a loop of links, or ending in `/`: input errors naming it.
#[test]
fn impossible_paths_are_input_errors() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    std::fs::write(d.join("target.csv"), "precious\n").unwrap();
    std::os::unix::fs::symlink("l3b", d.join("l3")).unwrap();
    std::os::unix::fs::symlink("l3", d.join("l3b")).unwrap();
    for (o, msg) in [
        (
            "newfile/",
            "-o newfile/: expected a file, found a directory name (ending in /)",
        ),
        (
            "target.csv/",
            "-o target.csv/: expected a file, found a directory name (ending in /)",
        ),
        (
            "target.csv/dir/out.csv",
            "-o target.csv/dir/out.csv: target.csv/dir is not a directory",
        ),
        ("l3/x.csv", "-o l3/x.csv: l3 is a loop of symbolic links"),
    ] {
        let out = crate::support::bin()
            .current_dir(d)
            .arg("interp")
            .arg(
                std::path::Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../.."))
                    .join("fixtures/interp/uniform.json"),
            )
            .args(["-o", o])
            .output()
            .unwrap();
        assert_eq!(out.status.code(), Some(2), "{o}");
        assert_eq!(
            String::from_utf8_lossy(&out.stderr),
            format!("inbetween: error: {msg}\n"),
            "{o}"
        );
    }
    assert_eq!(
        std::fs::read_to_string(d.join("target.csv")).unwrap(),
        "precious\n"
    );
    assert!(!d.join("newfile").exists());
}

/// A write that fails (a full device) names the user's path, exit 1.
#[test]
fn a_failed_write_names_the_o_path() {
    if !std::path::Path::new("/dev/full").exists() {
        eprintln!("skipped: no /dev/full here");
        return;
    }
    let out = crate::support::bin()
        .args(["interp", "fixtures/interp/uniform.json", "-o", "/dev/full"])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(1));
    assert_eq!(
        String::from_utf8_lossy(&out.stderr),
        "inbetween: error: -o /dev/full: cannot write: No space left on device (os error 28)\n"
    );
}

/// `-o` naming a file the command reads — its input by any name (itself, a symbolic link, a
/// relative path), the skeleton of `--skeleton`, or `diff`'s other file — is refused before
/// anything is written (exit 2, the file untouched): the run would destroy what it reads.
#[test]
fn an_output_that_is_a_file_the_command_reads_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    let keys = dir.path().join("keys.json");
    std::fs::copy(fixture(), &keys).unwrap();
    std::os::unix::fs::symlink("keys.json", dir.path().join("link.json")).unwrap();
    let skeleton = dir.path().join("skeleton.bvh");
    std::fs::copy(
        crate::support::fixtures().join("bvh/mixed_orders.bvh"),
        &skeleton,
    )
    .unwrap();
    let walk = skeleton.to_str().unwrap();
    let runs: Vec<(Vec<&str>, &str)> = vec![
        (vec!["convert", "keys.json", "-o", "keys.json"], "keys.json"),
        (
            vec!["interp", "keys.json", "--fps", "30", "-o", "./link.json"],
            "keys.json",
        ),
        (
            vec!["interp", "link.json", "--fps", "30", "-o", "keys.json"],
            "keys.json",
        ),
        (
            vec!["reduce", "keys.json", "--tolerance", "1", "-o", "keys.json"],
            "keys.json",
        ),
        (vec!["analyze", "keys.json", "-o", "keys.json"], "keys.json"),
        (
            vec!["diff", "keys.json", "link.json", "-o", "link.json"],
            "keys.json",
        ),
        (
            vec!["convert", walk, "--skeleton", walk, "-o", walk],
            "skeleton.bvh",
        ),
        (
            vec!["interp", walk, "--skeleton", walk, "-o", walk],
            "skeleton.bvh",
        ),
    ];
    for (args, file) in runs {
        let path = dir.path().join(file);
        let before = std::fs::read(&path).unwrap();
        let o = Command::new(BIN)
            .current_dir(dir.path())
            .args(&args)
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {err}");
        assert!(err.contains("which the command reads"), "{args:?}: {err}");
        assert_eq!(std::fs::read(&path).unwrap(), before, "{args:?}");
        assert_eq!(names(dir.path()).len(), 3, "{args:?}: a file was left");
    }
    // Another file beside it is written as ever.
    let o = Command::new(BIN)
        .current_dir(dir.path())
        .args(["convert", "keys.json", "-o", "copy.json"])
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
}

/// An output named for a format that is read but not written (binary USD) is refused before
/// anything is read or written, by every command that writes one, and so is a bare `.fbx` (no
/// name before the extension); `--output-format` says what to write under any name. (Until
/// issue 50, `.fbx` was refused too; it is written now: `fbx_output.rs`.)
#[test]
fn an_output_named_for_a_format_not_written_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    let bvh = crate::support::fixtures().join("bvh/cmu_01_01.bvh");
    let cases: [(&str, &Path, &str, &str); 5] = [
        (
            "interp",
            &bvh,
            ".fbx",
            "FBX output needs a file name before .fbx",
        ),
        (
            "convert",
            &bvh,
            ".FBX",
            "FBX output needs a file name before .fbx",
        ),
        (
            "convert",
            &bvh,
            "clip.USDC",
            "USD is written as text only: name it .usda",
        ),
        (
            "interp",
            &bvh,
            "clip.usdc",
            "USD is written as text only: name it .usda",
        ),
        (
            "reduce",
            &fixture(),
            "small.usdz",
            "USD is written as text only: name it .usda",
        ),
    ];
    for (command, input, target, says) in cases {
        let mut cmd = Command::new(BIN);
        cmd.current_dir(dir.path()).arg(command).arg(input);
        match command {
            "interp" => cmd.args(["--fps", "30"]),
            "reduce" => cmd.args(["--tolerance", "1"]),
            _ => &mut cmd,
        };
        let out = cmd.args(["-o", target]).output().unwrap();
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{command} -o {target}: {err}");
        assert!(err.contains(&format!("{target}: {says}")), "{err}");
        assert!(
            names(dir.path()).is_empty(),
            "{command} -o {target} wrote {:?}",
            names(dir.path())
        );
    }
    // Named explicitly, the format is written under the name asked for.
    let out = Command::new(BIN)
        .current_dir(dir.path())
        .args(["interp", "--output-format", "csv", "-o", "keys.fbx"])
        .arg(fixture())
        .output()
        .unwrap();
    assert_ok(&out);
    let csv = Command::new(BIN)
        .args(["interp", "--output-format", "csv"])
        .arg(fixture())
        .output()
        .unwrap();
    assert!(csv.status.success() && csv.stdout.starts_with(b"frame,time,"));
    assert_eq!(
        std::fs::read(dir.path().join("keys.fbx")).unwrap(),
        csv.stdout
    );
}

/// `analyze` and `diff` write a report (text, CSV, JSON): an `-o` named for a format of motion is
/// refused before anything is read, nothing written; with `--output-format` the report is
/// written under that name; `.txt` and a name without extension stay text.
#[test]
fn a_report_named_for_a_format_of_motion_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    let bvh = crate::support::fixtures().join("bvh/cmu_01_01.bvh");
    for (command, target) in [
        ("analyze", "report.fbx"),
        ("analyze", "report.BVH"),
        ("diff", "d.usdc"),
        ("diff", "d.html"),
        ("diff", "d.npz"),
    ] {
        let mut cmd = Command::new(BIN);
        cmd.current_dir(dir.path()).arg(command).arg(&bvh);
        if command == "diff" {
            cmd.arg(&bvh);
        }
        let out = cmd.args(["-o", target]).output().unwrap();
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{command} -o {target}: {err}");
        let ext = target.rsplit('.').next().unwrap().to_ascii_lowercase();
        assert!(
            err.contains(&format!(
                "{target}: a report is text, csv or json, not the .{ext} this name says"
            )) && err.contains("--output-format"),
            "{err}"
        );
        assert!(names(dir.path()).is_empty(), "{command} -o {target} wrote");
    }
    for (args, target, starts) in [
        (
            &["--output-format", "csv"][..],
            "d.fbx",
            &b"kind,track,"[..],
        ),
        (&[][..], "d.txt", &b"track "[..]),
        (&[][..], "d", &b"track "[..]),
    ] {
        let out = Command::new(BIN)
            .current_dir(dir.path())
            .arg("diff")
            .args([&bvh, &bvh])
            .args(args)
            .args(["-o", target])
            .output()
            .unwrap();
        assert_ok(&out);
        let written = std::fs::read(dir.path().join(target)).unwrap();
        assert!(
            written.starts_with(starts),
            "{target}: {}",
            String::from_utf8_lossy(&written[..written.len().min(80)])
        );
    }
}
