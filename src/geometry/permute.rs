//! Tables reordered in place: a table of large records (200k faces, edges of 112 bytes)
//! moved into a new one pays for memory not touched yet (page faults) and a copy.

/// Puts `items[order[k]]` at `k` for every k (`order` a permutation), in place: each cycle
/// of the permutation followed by swaps (a copy of 200k faces through a table of options
/// was a third of the patch ordering's time).
pub fn permute<T>(items: &mut [T], order: &[u32]) {
    debug_assert_eq!(items.len(), order.len());
    let mut placed = vec![false; items.len()];
    for start in 0..items.len() {
        let mut k = start;
        while !placed[k] {
            placed[k] = true;
            let from = order[k] as usize;
            if from == start {
                break;
            }
            items.swap(k, from);
            k = from;
        }
    }
}

/// Keeps `items[from[0]]`, `items[from[1]]`, … in that order and drops the rest, in
/// place (`from`: distinct indices).
pub fn gather<T>(items: &mut Vec<T>, mut from: Vec<u32>) {
    let (n, kept) = (items.len(), from.len());
    // the items dropped fill the places after those kept: a permutation of all
    let mut taken = vec![false; n];
    for &i in &from {
        assert!(!taken[i as usize], "item {i} gathered twice");
        taken[i as usize] = true;
    }
    from.extend((0..n as u32).filter(|&i| !taken[i as usize]));
    permute(items, &from);
    items.truncate(kept);
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A reordering is checked against the copy it replaces, on permutations with every
    /// cycle length from 1 to the table's (a shift by s of n items has gcd(n, s) cycles).
    #[test]
    fn in_place_as_a_copy_would_be() {
        for n in [0usize, 1, 2, 7, 12, 64] {
            for s in 0..n.max(1) {
                let order: Vec<u32> = (0..n).map(|k| ((k + s) % n) as u32).collect();
                let items: Vec<u64> = (0..n as u64).map(|i| i * 1000 + 7).collect();
                let copy: Vec<u64> = order.iter().map(|&i| items[i as usize]).collect();
                let mut moved = items.clone();
                permute(&mut moved, &order);
                assert_eq!(moved, copy, "n {n}, shift {s}");
                // keep every third of the shifted order, reversed
                let from: Vec<u32> = order.iter().rev().step_by(3).copied().collect();
                let copy: Vec<u64> = from.iter().map(|&i| items[i as usize]).collect();
                let mut kept = items.clone();
                gather(&mut kept, from);
                assert_eq!(kept, copy, "n {n}, shift {s}, gathered");
            }
        }
    }

    #[test]
    #[should_panic(expected = "gathered twice")]
    fn an_item_gathered_twice_is_refused() {
        gather(&mut vec![1, 2, 3], vec![0, 2, 0]);
    }
}
