//! "Did you mean …?" for misspelt names: the known name at the smallest edit distance.
//!
//! Levenshtein distance (insertions, deletions, substitutions, each costing 1), computed
//! with the usual two-row dynamic programme over characters. A suggestion is offered only
//! when the distance is at most a third of the longer name, so unrelated names are not
//! suggested.
//!
//! ```
//! use arachis::study::nearest_name;
//! let known = ["pod-pod.static_friction", "pod-pod.rolling_friction"];
//! assert_eq!(nearest_name("pod-pod.static_fricton", &known), Some("pod-pod.static_friction"));
//! assert_eq!(nearest_name("moisture", &known), None);
//! ```

/// The known name closest to `name`, if one is close enough to be a likely typo.
pub fn nearest_name<'a>(name: &str, known: &[&'a str]) -> Option<&'a str> {
    let lower = name.to_lowercase();
    known
        .iter()
        .map(|k| (edit_distance(&lower, &k.to_lowercase()), *k))
        .filter(|(d, k)| *d * 3 <= lower.chars().count().max(k.chars().count()))
        .min_by_key(|(d, _)| *d)
        .map(|(_, k)| k)
}

/// Levenshtein distance between `a` and `b`, in characters.
pub fn edit_distance(a: &str, b: &str) -> usize {
    let b: Vec<char> = b.chars().collect();
    let mut previous: Vec<usize> = (0..=b.len()).collect();
    let mut current = vec![0; b.len() + 1];
    for (i, ca) in a.chars().enumerate() {
        current[0] = i + 1;
        for (j, cb) in b.iter().enumerate() {
            let substitution = previous[j] + usize::from(ca != *cb);
            current[j + 1] = substitution.min(previous[j + 1] + 1).min(current[j] + 1);
        }
        std::mem::swap(&mut previous, &mut current);
    }
    previous[b.len()]
}
