//! Grouping by small integer keys (compressed sparse rows): a counting sort, linear in
//! the items, used wherever per-face or per-vertex lists are built from pairs.

/// Groups `(key, value)` pairs by key (each below `n`) into offsets (`n + 1`: key k's
/// values are `values[at[k]..at[k + 1]]`) and values, keeping the values' order within a
/// key. `items` is walked twice (counted, then placed), so it should be cheap to clone.
pub fn csr_of<V: Copy>(
    n: usize,
    items: impl Iterator<Item = (u32, V)> + Clone,
) -> (Vec<u32>, Vec<V>) {
    let mut at = vec![0u32; n + 1];
    let mut first = None;
    for (k, v) in items.clone() {
        at[k as usize + 1] += 1;
        first.get_or_insert(v);
    }
    for i in 0..n {
        at[i + 1] += at[i];
    }
    let Some(first) = first else {
        return (at, Vec::new());
    };
    // every slot is written below: `first` only fills them until then
    let mut values = vec![first; at[n] as usize];
    let mut fill: Vec<u32> = at[..n].to_vec();
    for (k, v) in items {
        let f = &mut fill[k as usize];
        values[*f as usize] = v;
        *f += 1;
    }
    (at, values)
}

/// Sorts each key's values (`at` from [`csr_of`]) by `key`, stably: the values that
/// tie keep their order.
pub fn sort_within<V, K: Ord>(at: &[u32], values: &mut [V], mut key: impl FnMut(&V) -> K) {
    for w in at.windows(2) {
        let run = &mut values[w[0] as usize..w[1] as usize];
        if run.len() > 1 {
            run.sort_by_key(&mut key);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn values_grouped_by_key_in_their_order_and_sorted_within() {
        let items = [
            (2u32, 'a'),
            (0, 'b'),
            (2, 'c'),
            (3, 'd'),
            (0, 'e'),
            (2, 'b'),
        ];
        let (at, mut values) = csr_of(5, items.iter().copied());
        assert_eq!(at, vec![0, 2, 2, 5, 6, 6]);
        assert_eq!(values, vec!['b', 'e', 'a', 'c', 'b', 'd']);
        sort_within(&at, &mut values, |&c| c);
        assert_eq!(values, vec!['b', 'e', 'a', 'b', 'c', 'd']);
        let (at, values) = csr_of::<char>(2, std::iter::empty());
        assert_eq!((at, values), (vec![0, 0, 0], vec![]));
    }
}
