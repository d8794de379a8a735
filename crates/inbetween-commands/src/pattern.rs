//! Name patterns (`--tracks`, `--position-tolerance` joint globs, a batch's path globs):
//! `*` any run of characters, `?` one character, anything else itself.

/// Whether `name` matches `pattern`: `*` any run of characters, `?` one character, anything else
/// itself.
pub fn glob(pattern: &str, name: &str) -> bool {
    let (p, n): (Vec<char>, Vec<char>) = (pattern.chars().collect(), name.chars().collect());
    // Classic two-pointer match with backtracking to the last `*`.
    let (mut i, mut j) = (0, 0);
    let mut star: Option<(usize, usize)> = None;
    while j < n.len() {
        if i < p.len() && (p[i] == '?' || p[i] == n[j]) {
            i += 1;
            j += 1;
        } else if i < p.len() && p[i] == '*' {
            star = Some((i, j));
            i += 1;
        } else if let Some((si, sj)) = star {
            i = si + 1;
            j = sj + 1;
            star = Some((si, sj + 1));
        } else {
            return false;
        }
    }
    p[i..].iter().all(|&c| c == '*')
}

#[cfg(test)]
mod tests {
    use super::glob;

    #[test]
    fn globs() {
        assert!(glob("Left*", "LeftArm") && glob("Left*", "Left"));
        assert!(glob("*Arm", "LeftArm") && !glob("*Arm", "LeftArms"));
        assert!(glob("L?ft*m", "LeftArm") && !glob("L?ft", "Lft"));
        assert!(glob("*", "") && glob("a*b*c", "aXbYbZc") && !glob("a*b*c", "aXbY"));
        assert!(glob("hip", "hip") && !glob("hip", "Hip"));
    }
}
