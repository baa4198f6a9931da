//! Nearest-name suggestions for unknown keys and variants ("did you mean ...?").

/// Levenshtein edit distance over Unicode scalar values (insert, delete, substitute,
/// each cost 1). O(|a|·|b|) time, O(|b|) memory.
pub(crate) fn levenshtein(a: &str, b: &str) -> usize {
    let b: Vec<char> = b.chars().collect();
    let mut row: Vec<usize> = (0..=b.len()).collect();
    for (i, ca) in a.chars().enumerate() {
        let mut diag = row[0];
        row[0] = i + 1;
        for (j, &cb) in b.iter().enumerate() {
            let above = row[j + 1];
            let cost = usize::from(ca != cb);
            row[j + 1] = (diag + cost).min(above + 1).min(row[j] + 1);
            diag = above;
        }
    }
    row[b.len()]
}

/// The candidate nearest to `given`, if it is near enough to be a plausible typo.
///
/// Comparison is case-insensitive and treats `-`, ` ` as `_`. A candidate is accepted
/// when its edit distance is at most max(2, ⌊len/3⌋) (len = the candidate's length),
/// or when one name is a prefix of the other and the shorter has at least 4
/// characters (`bending` → `bending_stiffness`). Ties go to the earlier candidate.
pub(crate) fn nearest<'a, I>(given: &str, candidates: I) -> Option<String>
where
    I: IntoIterator<Item = &'a str>,
{
    let norm = |s: &str| -> String {
        s.chars()
            .map(|c| match c {
                '-' | ' ' => '_',
                c => c.to_ascii_lowercase(),
            })
            .collect()
    };
    // Very long keys are not typos of a short name; also bounds the O(n·m) cost.
    if given.chars().count() > 200 {
        return None;
    }
    let g = norm(given);
    let mut best: Option<(usize, &str)> = None;
    for cand in candidates {
        let c = norm(cand);
        let d = levenshtein(&g, &c);
        let limit = 2.max(c.chars().count() / 3);
        let shorter = g.len().min(c.len());
        let prefix = shorter >= 4 && (c.starts_with(&g) || g.starts_with(&c));
        if d <= limit || prefix {
            // prefix matches rank after genuine near-misses of equal distance
            let score = if d <= limit { d } else { limit + 1 + d };
            if best.is_none_or(|(s, _)| score < s) {
                best = Some((score, cand));
            }
        }
    }
    best.map(|(_, c)| c.to_string())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn distances() {
        assert_eq!(levenshtein("", ""), 0);
        assert_eq!(levenshtein("abc", ""), 3);
        assert_eq!(levenshtein("kitten", "sitting"), 3);
        assert_eq!(levenshtein("axial_stifness", "axial_stiffness"), 1);
        assert_eq!(levenshtein("μ", "mu"), 2);
    }

    #[test]
    fn suggestions() {
        let names = [
            "theory",
            "length",
            "axial_stiffness",
            "bending_stiffness",
            "shear_stiffness",
        ];
        assert_eq!(
            nearest("axial_stifness", names).as_deref(),
            Some("axial_stiffness")
        );
        assert_eq!(nearest("Length", names).as_deref(), Some("length"));
        assert_eq!(
            nearest("bending", names).as_deref(),
            Some("bending_stiffness")
        );
        assert_eq!(nearest("colour", names), None);
        assert_eq!(nearest("", names), None);
        assert_eq!(
            nearest("bvp_collocation", ["bvp-collocation", "bvp-shooting"]).as_deref(),
            Some("bvp-collocation")
        );
    }
}
