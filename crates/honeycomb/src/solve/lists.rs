//! Many short lists in one flat array, built without a vector per list: where each unknown
//! occurs, and its neighbours, are kept this way.

/// Lists in one flat array: list k is `items[start[k]..start[k + 1]]`.
pub(super) struct Lists<T> {
    start: Vec<usize>,
    items: Vec<T>,
}

impl<T: Copy + Default> Lists<T> {
    /// `count` lists of the items `each` visits as (list, item); `each` runs twice (to count,
    /// then to place), which spares a vector per list.
    pub(super) fn build(count: usize, each: impl Fn(&mut dyn FnMut(usize, T))) -> Lists<T> {
        let mut start = vec![0usize; count + 1];
        each(&mut |k, _| start[k + 1] += 1);
        for k in 0..count {
            start[k + 1] += start[k];
        }
        let mut items = vec![T::default(); start[count]];
        let mut next = start[..count].to_vec();
        each(&mut |k, item| {
            items[next[k]] = item;
            next[k] += 1;
        });
        Lists { start, items }
    }

    pub(super) fn get(&self, k: usize) -> &[T] {
        &self.items[self.start[k]..self.start[k + 1]]
    }
}
