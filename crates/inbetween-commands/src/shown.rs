//! A user's text in a message: a file name or an input's bytes, with its control characters
//! escaped, so that a message cannot move the cursor, colour or clear the terminal, or forge a
//! line of its own.

use std::path::Path;

/// `text` with its control characters escaped (`\n`, `\t`, `\u{1b}`).
pub fn printable(text: &str) -> String {
    if !text.chars().any(char::is_control) {
        return text.to_string();
    }
    let mut out = String::with_capacity(text.len() + 8);
    for c in text.chars() {
        if c.is_control() {
            out.extend(c.escape_default());
        } else {
            out.push(c);
        }
    }
    out
}

/// `path` as messages show it ([`printable`]).
pub fn shown(path: &Path) -> String {
    printable(&path.display().to_string())
}

/// At most this many characters of a line of stderr; the rest is cut, saying how much.
pub const MAX_LINE_CHARS: usize = 2000;

/// A line for stderr: [`printable`], every run of more than 256 characters without a space or
/// quote cut to its first 100 (so a value quoted whole by mistake shows as its start), and at
/// most [`MAX_LINE_CHARS`] characters. Messages quote bounded parts of their input already;
/// this is the last guard, applied to every line the command line prints.
pub fn line(text: &str) -> String {
    let text = printable(text);
    let mut out = String::with_capacity(text.len().min(MAX_LINE_CHARS + 64));
    let mut run = String::new();
    let flush = |run: &mut String, out: &mut String| {
        if run.chars().count() > 256 {
            out.extend(run.chars().take(100));
            out.push('…');
        } else {
            out.push_str(run);
        }
        run.clear();
    };
    for c in text.chars() {
        if c.is_whitespace() || c == '\'' || c == '"' {
            flush(&mut run, &mut out);
            out.push(c);
        } else {
            run.push(c);
        }
    }
    flush(&mut run, &mut out);
    let count = out.chars().count();
    if count > MAX_LINE_CHARS {
        let cut: String = out.chars().take(MAX_LINE_CHARS).collect();
        return format!("{cut}… ({} more characters)", count - MAX_LINE_CHARS);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::{MAX_LINE_CHARS, line, printable};

    #[test]
    fn lines_escape_control_characters_and_cut_long_runs() {
        let long = "x".repeat(300_000);
        let l = line(&format!("k.json:1: bad value \"{long}\" here"));
        assert!(l.starts_with("k.json:1: bad value \"xxx"), "{l}");
        assert!(l.chars().count() < 200, "{}", l.len());
        assert!(l.ends_with("…\" here"), "{l}");
        let words = "word ".repeat(1000);
        let l = line(&words);
        assert!(l.ends_with("more characters)"), "{l}");
        assert!(l.chars().count() < MAX_LINE_CHARS + 40);
        // A path of 200 characters is not cut.
        let path = format!("/{}/x.bvh", "d".repeat(200));
        assert_eq!(line(&path), path);
    }

    #[test]
    fn control_characters_are_escaped() {
        assert_eq!(printable("a\nb\u{1b}[2Jc\td"), "a\\nb\\u{1b}[2Jc\\td");
        assert_eq!(printable("plain é"), "plain é");
    }
}
