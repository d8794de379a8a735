//! Track names that cannot collide, for formats whose objects may share a name (BVH joints,
//! glTF nodes).
//!
//! The rule (docs/spec.md §3, *BVH* and *glTF*): a name no earlier object has is kept as given; a later
//! duplicate gets `#<id>` appended, where `id` is the object's index in its file (the joint's
//! position in the hierarchy, the node's index), and when that too is taken, by any given name
//! or an earlier result, `#<id>#2`, `#<id>#3`, … the first that is free. Every result is
//! distinct from every other result, whatever the given names are (`a#2` beside two `a`s
//! included). Names are labels only: code that maps a track back to its object keeps the index.

use std::collections::HashSet;

/// Unique names for objects named `given` with indices `ids` (same length), by the rule of the
/// module documentation. Linear in the number of names (hash sets).
///
/// (Its example is a unit test: `unique_names_example`.)
pub(crate) fn unique_names<S: AsRef<str>>(given: &[S], ids: &[usize]) -> Vec<String> {
    assert_eq!(given.len(), ids.len(), "one id per name");
    let all: HashSet<&str> = given.iter().map(AsRef::as_ref).collect();
    let mut taken: HashSet<String> = HashSet::with_capacity(given.len());
    let mut out = Vec::with_capacity(given.len());
    for (name, &id) in given.iter().zip(ids) {
        let name = name.as_ref();
        let mut candidate = name.to_string();
        if taken.contains(&candidate) {
            let base = format!("{name}#{id}");
            candidate = base.clone();
            let mut n = 2u64;
            while taken.contains(&candidate) || all.contains(candidate.as_str()) {
                candidate = format!("{base}#{n}");
                n += 1;
            }
        }
        taken.insert(candidate.clone());
        out.push(candidate);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::unique_names;
    use std::collections::HashSet;

    fn distinct(names: &[String]) -> bool {
        names.iter().collect::<HashSet<_>>().len() == names.len()
    }

    #[test]
    fn distinct_names_are_kept() {
        assert_eq!(unique_names(&["hip", "knee"], &[0, 1]), ["hip", "knee"]);
    }

    #[test]
    fn a_later_duplicate_gets_its_index() {
        assert_eq!(
            unique_names(&["a", "b", "a"], &[0, 1, 7]),
            ["a", "b", "a#7"]
        );
    }

    #[test]
    fn a_given_name_that_looks_generated_is_not_reused() {
        // `a#2` is a given name: the duplicate `a` (index 2) must not become it, whichever
        // comes first.
        let names = unique_names(&["a", "a", "a#2"], &[0, 2, 5]);
        assert_eq!(names, ["a", "a#2#2", "a#2"]);
        assert!(distinct(&names));
        let names = unique_names(&["a#2", "a", "a"], &[0, 1, 2]);
        assert_eq!(names, ["a#2", "a", "a#2#2"]);
    }

    #[test]
    fn many_duplicates_and_adversarial_names_stay_distinct() {
        let mut given: Vec<String> = Vec::new();
        for i in 0..200 {
            given.push("x".into());
            given.push(format!("x#{i}"));
            given.push(format!("x#{i}#2"));
        }
        let ids: Vec<usize> = (0..given.len()).map(|i| i / 3).collect();
        let names = unique_names(&given, &ids);
        assert!(distinct(&names));
        assert_eq!(names[0], "x");
    }
}

#[cfg(test)]
mod examples {
    #[test]
    fn unique_names_example() {
        use crate::names::unique_names;
        let names = unique_names(&["a#2", "a", "a"], &[0, 1, 2]);
        assert_eq!(names, ["a#2", "a", "a#2#2"]);
    }
}
