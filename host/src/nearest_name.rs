//! "Did you mean …?" for misspelt names: the known name at the smallest edit distance.
//!
//! The distance is the optimal-string-alignment edit distance (insertions, deletions,
//! substitutions and swaps of adjacent characters, each costing 1, so `plna` is one edit
//! from `plan`). A suggestion is offered only when the distance is at most a third of the
//! longer name, so unrelated names are not suggested.
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

/// Edit distance between `a` and `b` in characters: insertions, deletions, substitutions
/// and swaps of two adjacent characters each cost 1 (optimal string alignment distance).
pub fn edit_distance(a: &str, b: &str) -> usize {
    let a: Vec<char> = a.chars().collect();
    let b: Vec<char> = b.chars().collect();
    // d[i][j]: distance between the first i chars of a and the first j chars of b.
    let mut d = vec![vec![0usize; b.len() + 1]; a.len() + 1];
    for (i, row) in d.iter_mut().enumerate() {
        row[0] = i;
    }
    for (j, cell) in d[0].iter_mut().enumerate() {
        *cell = j;
    }
    for i in 1..=a.len() {
        for j in 1..=b.len() {
            let cost = usize::from(a[i - 1] != b[j - 1]);
            let mut best = (d[i - 1][j] + 1)
                .min(d[i][j - 1] + 1)
                .min(d[i - 1][j - 1] + cost);
            if i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1] {
                best = best.min(d[i - 2][j - 2] + 1);
            }
            d[i][j] = best;
        }
    }
    d[a.len()][b.len()]
}
