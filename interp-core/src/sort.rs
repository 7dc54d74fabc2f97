//! An in-place heapsort for the interpreter's few sorts (a program's sequence
//! index, a path's cut points): O(n log n) on any input and ~200 bytes of code,
//! where `core`'s `sort_unstable` brings ~9 KB of quicksort and small-sort
//! variants per element type into the firmware. Not stable: the keys sorted here
//! are unique or plain numbers.

/// Sorts `v` in place so that no element is `less` than the one before it.
pub(crate) fn heap_sort_by<T>(v: &mut [T], less: impl Fn(&T, &T) -> bool) {
    let n = v.len();
    for start in (0..n / 2).rev() {
        sift_down(v, start, n, &less);
    }
    for end in (1..n).rev() {
        v.swap(0, end);
        sift_down(v, 0, end, &less);
    }
}

/// Restores the max-heap below `root` within `v[..end]`.
fn sift_down<T>(v: &mut [T], mut root: usize, end: usize, less: &impl Fn(&T, &T) -> bool) {
    loop {
        let mut child = 2 * root + 1;
        if child >= end {
            return;
        }
        if child + 1 < end && v.get(child).zip(v.get(child + 1)).is_some_and(|(a, b)| less(a, b)) {
            child += 1;
        }
        if !v.get(root).zip(v.get(child)).is_some_and(|(r, c)| less(r, c)) {
            return;
        }
        v.swap(root, child);
        root = child;
    }
}

#[cfg(test)]
mod tests {
    use super::heap_sort_by;

    #[test]
    fn sorts_like_the_standard_sort() {
        let mut seed = 12345u32;
        for n in 0..70 {
            let mut v: std::vec::Vec<(u32, u32)> = (0..n)
                .map(|i| {
                    seed = seed.wrapping_mul(1_103_515_245).wrapping_add(12345);
                    ((seed >> 16) % 10, i)
                })
                .collect();
            let mut expected = v.clone();
            expected.sort_unstable();
            heap_sort_by(&mut v, |a, b| a < b);
            assert_eq!(v, expected, "n = {n}");
        }
        let mut f: [f64; 6] = [0.5, 1.0, 0.0, 0.25, 0.75, 0.25];
        heap_sort_by(&mut f, |a, b| a.total_cmp(b).is_lt());
        assert_eq!(f, [0.0, 0.25, 0.25, 0.5, 0.75, 1.0]);
    }
}
