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

#[cfg(test)]
mod tests {
    use super::printable;

    #[test]
    fn control_characters_are_escaped() {
        assert_eq!(printable("a\nb\u{1b}[2Jc\td"), "a\\nb\\u{1b}[2Jc\\td");
        assert_eq!(printable("plain é"), "plain é");
    }
}
