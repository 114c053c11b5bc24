//! Pairing the parts of two scenes one to one, whatever order made them:
//! a minimum-cost assignment between the reference's parts of one kind and
//! the submission's.
//!
//! Up to [`EXACT_LIMIT`] parts a side, the assignment is exact (the
//! Hungarian method, O(n² m) for n ≤ m: 300 parts take a few milliseconds).
//! Beyond it that cost grows too fast (10,000 parts would take minutes), so
//! the parts whose keys are equal (the same values to within the
//! tolerances) are paired first, in one sort; what is left is assigned
//! exactly if it is small enough, and otherwise paired in the order of the
//! keys. A correct submission of a large scene is thus paired exactly in
//! O(n log n), and a few wrong parts among many still get the exact
//! assignment.

/// The most parts on either side for which the assignment is exact.
pub const EXACT_LIMIT: usize = 300;

/// The pairs `(reference, submission)` of a minimum-cost assignment of
/// `reference` parts to `submission` parts (as many pairs as the smaller
/// side has parts), by `cost`; `key` gives each part the numbers that must
/// be equal for it to be paired before the others when the sides are large.
pub fn assign<T>(
    reference: &[T],
    submission: &[T],
    cost: impl Fn(&T, &T) -> f64,
    key: impl Fn(&T) -> Vec<i64>,
) -> Vec<(usize, usize)> {
    let all_reference: Vec<usize> = (0..reference.len()).collect();
    let all_submission: Vec<usize> = (0..submission.len()).collect();
    if reference.len().max(submission.len()) <= EXACT_LIMIT {
        let mut pairs = assign_exactly(&all_reference, &all_submission, |r, s| cost(&reference[r], &submission[s]));
        pairs.sort_unstable();
        return pairs;
    }
    let mut keyed_reference: Vec<(Vec<i64>, usize)> = all_reference.iter().map(|&r| (key(&reference[r]), r)).collect();
    let mut keyed_submission: Vec<(Vec<i64>, usize)> =
        all_submission.iter().map(|&s| (key(&submission[s]), s)).collect();
    keyed_reference.sort();
    keyed_submission.sort();
    let (mut pairs, left_reference, left_submission) = pair_equal_keys(&keyed_reference, &keyed_submission);
    if left_reference.len().max(left_submission.len()) <= EXACT_LIMIT {
        pairs.extend(assign_exactly(&left_reference, &left_submission, |r, s| cost(&reference[r], &submission[s])));
    } else {
        // Both lists are in key order: neighbours in it are alike.
        pairs.extend(left_reference.into_iter().zip(left_submission));
    }
    pairs.sort_unstable();
    pairs
}

/// Walks two key-sorted lists together and pairs the entries with equal
/// keys; returns the pairs and the indices left on each side, in key order.
fn pair_equal_keys(
    reference: &[(Vec<i64>, usize)],
    submission: &[(Vec<i64>, usize)],
) -> (Vec<(usize, usize)>, Vec<usize>, Vec<usize>) {
    let (mut pairs, mut left_reference, mut left_submission) = (Vec::new(), Vec::new(), Vec::new());
    let (mut r, mut s) = (0, 0);
    while r < reference.len() && s < submission.len() {
        match reference[r].0.cmp(&submission[s].0) {
            std::cmp::Ordering::Equal => {
                pairs.push((reference[r].1, submission[s].1));
                r += 1;
                s += 1;
            }
            std::cmp::Ordering::Less => {
                left_reference.push(reference[r].1);
                r += 1;
            }
            std::cmp::Ordering::Greater => {
                left_submission.push(submission[s].1);
                s += 1;
            }
        }
    }
    left_reference.extend(reference[r..].iter().map(|(_, index)| *index));
    left_submission.extend(submission[s..].iter().map(|(_, index)| *index));
    (pairs, left_reference, left_submission)
}

/// A minimum-cost assignment between the parts `reference` and
/// `submission` (indices), by the Hungarian method on the smaller side as
/// rows.
fn assign_exactly(
    reference: &[usize],
    submission: &[usize],
    cost: impl Fn(usize, usize) -> f64,
) -> Vec<(usize, usize)> {
    if reference.len() <= submission.len() {
        let rows = hungarian(reference.len(), submission.len(), |i, j| cost(reference[i], submission[j]));
        rows.into_iter().enumerate().map(|(i, j)| (reference[i], submission[j])).collect()
    } else {
        let rows = hungarian(submission.len(), reference.len(), |i, j| cost(reference[j], submission[i]));
        rows.into_iter().enumerate().map(|(i, j)| (reference[j], submission[i])).collect()
    }
}

/// The column given to each of `rows` rows (`rows <= columns`) by a
/// minimum-cost assignment of the matrix `cost(row, column)`: the
/// Hungarian method with potentials `u` (rows) and `v` (columns), adding
/// one row at a time and growing a tree of tight edges (reduced cost
/// `cost - u - v = 0`) to an unassigned column.
fn hungarian(rows: usize, columns: usize, cost: impl Fn(usize, usize) -> f64) -> Vec<usize> {
    // Index 0 is a sentinel: rows and columns count from 1 below.
    let mut u = vec![0.0; rows + 1];
    let mut v = vec![0.0; columns + 1];
    // The row assigned to each column (0: none).
    let mut row_of = vec![0usize; columns + 1];
    let mut way = vec![0usize; columns + 1];
    for row in 1..=rows {
        row_of[0] = row;
        let mut column = 0;
        let mut least = vec![f64::INFINITY; columns + 1];
        let mut used = vec![false; columns + 1];
        loop {
            used[column] = true;
            let current = row_of[column];
            let (mut delta, mut next) = (f64::INFINITY, 0);
            for j in 1..=columns {
                if used[j] {
                    continue;
                }
                let reduced = cost(current - 1, j - 1) - u[current] - v[j];
                if reduced < least[j] {
                    least[j] = reduced;
                    way[j] = column;
                }
                if least[j] < delta {
                    delta = least[j];
                    next = j;
                }
            }
            for j in 0..=columns {
                if used[j] {
                    u[row_of[j]] += delta;
                    v[j] -= delta;
                } else {
                    least[j] -= delta;
                }
            }
            column = next;
            if row_of[column] == 0 {
                break;
            }
        }
        // Flip the path of the tree back to the root.
        while column != 0 {
            let previous = way[column];
            row_of[column] = row_of[previous];
            column = previous;
        }
    }
    let mut column_of = vec![0; rows];
    for j in 1..=columns {
        if row_of[j] != 0 {
            column_of[row_of[j] - 1] = j - 1;
        }
    }
    column_of
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The smallest total cost over every assignment, by trying them all.
    fn best_by_brute_force(costs: &[Vec<f64>]) -> f64 {
        fn walk(costs: &[Vec<f64>], row: usize, used: &mut Vec<bool>) -> f64 {
            if row == costs.len() {
                return 0.0;
            }
            let mut best = f64::INFINITY;
            for column in 0..costs[0].len() {
                if !used[column] {
                    used[column] = true;
                    best = best.min(costs[row][column] + walk(costs, row + 1, used));
                    used[column] = false;
                }
            }
            best
        }
        walk(costs, 0, &mut vec![false; costs[0].len()])
    }

    #[test]
    fn the_assignment_is_the_cheapest_one() {
        // A fixed pseudo-random series: every size from 1x1 to 5x6.
        let mut seed = 12345u64;
        let mut next = || {
            seed = seed.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
            (seed >> 33) as f64 / f64::from(u32::MAX >> 1)
        };
        for rows in 1..=5 {
            for columns in rows..=6 {
                let costs: Vec<Vec<f64>> = (0..rows).map(|_| (0..columns).map(|_| next()).collect()).collect();
                let assigned = hungarian(rows, columns, |i, j| costs[i][j]);
                let total: f64 = assigned.iter().enumerate().map(|(i, &j)| costs[i][j]).sum();
                assert!((total - best_by_brute_force(&costs)).abs() < 1e-9, "{rows}x{columns}");
                let mut distinct = assigned.clone();
                distinct.sort_unstable();
                distinct.dedup();
                assert_eq!(distinct.len(), rows, "one column each");
            }
        }
    }

    #[test]
    fn parts_pair_with_their_like_whatever_their_order() {
        let reference: [f64; 3] = [1.0, 5.0, 9.0];
        let submission: [f64; 4] = [9.1, 1.2, 40.0, 5.0];
        let pairs = assign(&reference, &submission, |a, b| (a - b).abs(), |a| vec![*a as i64]);
        assert_eq!(pairs, [(0, 1), (1, 3), (2, 0)]);
        let pairs = assign(&submission, &reference, |a, b| (a - b).abs(), |a| vec![*a as i64]);
        assert_eq!(pairs, [(0, 2), (1, 0), (3, 1)]);
    }

    #[test]
    fn large_sides_pair_equal_keys_first_then_the_rest_exactly() {
        let reference: Vec<f64> = (0..1000).map(f64::from).collect();
        let mut submission: Vec<f64> = reference.iter().rev().copied().collect();
        submission[10] = 2000.5; // was 989
        submission.remove(500); // was 499
        let pairs = assign(&reference, &submission, |a, b| (a - b).abs(), |a| vec![(a * 10.0).round() as i64]);
        assert_eq!(pairs.len(), 999);
        let paired_with = |r: usize| pairs.iter().find(|&&(a, _)| a == r).map(|&(_, s)| submission[s]);
        assert_eq!(paired_with(3), Some(3.0));
        assert_eq!(paired_with(989), Some(2000.5), "the one changed pairs with what is left");
        assert_eq!(paired_with(499), None, "the one removed is left over");
    }
}
